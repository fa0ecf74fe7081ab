"""The FFT ocean's costs (`make bench`, `--only fft`): prints figures, asserts nothing.

A JONSWAP tile (ocean_sim/physics/fft.py) at N = 16, 32, 64 against 16 Gerstner components of
the same spectrum (spectra.generate_sea): the tile's build by FFT against the direct sum at its
grid points, the per-point surface query (inverted), and a boat's step.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from timing import best_of

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.scenario import parse_scenario
from ocean_sim.physics.fft import TileSpec, build_tile, tile_amplitudes, tile_sea
from ocean_sim.physics.spectra import SpectrumSpec, generate_sea
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["bench_fft"]


def _per_point(sea: WaveField, xy: np.ndarray) -> float:
    """Seconds per point of sample_surface (float64, inverted) at ``xy``."""
    sample_surface(sea, xy, 1.0)
    return best_of(lambda: sample_surface(sea, xy, 12.3), 5) / xy.shape[0]


def _boat_step(sea: WaveField) -> float:
    """Seconds per step of one 7-sample-point boat (the boat layout) in ``sea``."""
    sc = pipeline.init_scenario(replace(parse_scenario({"boats": [{"buoyancy": {
        "model": "sample_points", "layout": "boat"}}]}), sea=sea))
    system = System.build([sc.boats[0].params])
    state = [FleetState.stack([sc.boats[0].initial])]
    inputs = FleetInputs.stack([BoatInputs(1.0, 0.2)])

    def steps():
        s = state[0]
        for _ in range(20):
            s = pipeline.step(system, s, inputs, sea, 0.01).state
        state[0] = s

    steps()
    return best_of(steps, 5) / 20


def bench_fft() -> None:
    """Print the tile's build, query and boat-step costs beside 16 Gerstner components."""
    hs, tp, size = 1.5, 7.0, 200.0
    print(f"== FFT ocean: JONSWAP H_s {hs} m, T_p {tp} s, {size:g} m tile, choppiness 0.5, "
          "against 16 Gerstner components of the same spectrum (float64, inverted queries)")
    xy = np.random.default_rng(1).uniform(-100.0, 100.0, (200, 2))
    gerstner = generate_sea(SpectrumSpec("jonswap", hs, tp, components=16))
    print(f"  16 Gerstner components: query {_per_point(gerstner, xy) * 1e6:8.2f} us/point, "
          f"boat step (7 points) {_boat_step(gerstner) * 1e6:8.1f} us")
    for n in (16, 32, 64):
        spec = TileSpec(size=size, resolution=n, spectrum="jonswap", significant_height=hs,
                        peak_period=tp)
        sea, h0 = tile_sea(spec), tile_amplitudes(spec)
        x0 = np.arange(n) * size / n
        grid = np.stack([g.ravel() for g in np.meshgrid(x0, x0, indexing="ij")], axis=1)
        fft = best_of(lambda spec=spec, h0=h0: build_tile(spec, 12.3, h0), 10)
        direct = best_of(lambda sea=sea, grid=grid: sample_surface(sea, grid, 12.3,
                                                                    invert=False), 3)
        print(f"  tile {n:>2} x {n:<2} ({len(sea.components):>4} waves): build by FFT "
              f"{fft * 1e3:7.3f} ms ({fft / n**2 * 1e9:5.0f} ns/grid point), direct sum at "
              f"the grid {direct * 1e3:8.2f} ms; query {_per_point(sea, xy) * 1e6:8.2f} "
              f"us/point, boat step (7 points) {_boat_step(sea) * 1e6:8.1f} us")
