"""The FFT ocean's costs (`make bench`, `--only fft`): prints figures, asserts nothing.

A JONSWAP tile (ocean_sim/physics/fft.py) at N = 16, 32, 64 against 16 Gerstner components of
the same spectrum (spectra.generate_sea): the tile's build by FFT against the direct sum at its
grid points, the per-point surface query (inverted), a boat's step, and what the view and
/ocean/surface draw (a 61 x 61 mesh at 1 m) from the tile's FFT grid against the direct sum.
Then the boats' cost on the 64 x 64 tile when they feel only its waves longer than
``boats[].min_wavelength``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from timing import best_of

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.scenario import parse_scenario
from ocean_sim.physics.fft import (
    TileSpec,
    build_tile,
    grid_points,
    grid_surface,
    tile_amplitudes,
    tile_sea,
)
from ocean_sim.physics.spectra import SpectrumSpec, generate_sea
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["bench_fft"]

#: The sampled boat: the default hull felt at 7 sample points (the boat layout).
_POINTS_BOAT = {"buoyancy": {"model": "sample_points", "layout": "boat"}}


def _per_point(sea: WaveField, xy: np.ndarray) -> float:
    """Seconds per point of sample_surface (float64, inverted) at ``xy``."""
    sample_surface(sea, xy, 1.0)
    return best_of(lambda: sample_surface(sea, xy, 12.3), 5) / xy.shape[0]


def _boat_step(sea: WaveField, boat: dict, repeats: int = 5) -> float:
    """Seconds per step of one boat of the scenario's ``boat`` block in ``sea``."""
    sc = pipeline.init_scenario(replace(parse_scenario({"boats": [boat]}), sea=sea))
    system = System.build([sc.boats[0].params])
    state = [FleetState.stack([sc.boats[0].initial])]
    inputs = FleetInputs.stack([BoatInputs(1.0, 0.2)])

    def steps():
        s = state[0]
        for _ in range(20):
            s = pipeline.step(system, s, inputs, sea, 0.01).state
        state[0] = s

    steps()
    return best_of(steps, repeats) / 20


def _mesh(sea: WaveField) -> tuple[float, float]:
    """Seconds for the view's 61 x 61 mesh at 1 m: by the tile's FFT grid, by the direct sum."""
    m = grid_points(sea.tile, 1.0)
    cells = np.stack(np.meshgrid(np.arange(61), np.arange(61), indexing="ij"), -1).reshape(-1, 2)
    spacing = sea.tile.size / m
    grid = best_of(lambda: grid_surface(sea, 12.3, cells, m, normals=False), 5)
    direct = best_of(lambda: sample_surface(sea, cells * spacing, 12.3), 2)
    return grid, direct


def bench_fft() -> None:
    """Print the tile's build, query, boat-step and mesh costs beside 16 Gerstner components."""
    hs, tp, size = 1.5, 7.0, 200.0
    print(f"== FFT ocean: JONSWAP H_s {hs} m, T_p {tp} s, {size:g} m tile, choppiness 0.5, "
          "against 16 Gerstner components of the same spectrum (float64, inverted queries)")
    xy = np.random.default_rng(1).uniform(-100.0, 100.0, (200, 2))
    gerstner = generate_sea(SpectrumSpec("jonswap", hs, tp, components=16))
    print(f"  16 Gerstner components: query {_per_point(gerstner, xy) * 1e6:8.2f} us/point, "
          f"boat step (7 points) {_boat_step(gerstner, _POINTS_BOAT) * 1e6:8.1f} us, "
          f"mesh boat step {_boat_step(gerstner, {}) * 1e6:8.1f} us")
    seas = {}
    for n in (16, 32, 64):
        spec = TileSpec(size=size, resolution=n, spectrum="jonswap", significant_height=hs,
                        peak_period=tp)
        sea, h0 = tile_sea(spec), tile_amplitudes(spec)
        seas[n] = sea
        x0 = np.arange(n) * size / n
        grid = np.stack([g.ravel() for g in np.meshgrid(x0, x0, indexing="ij")], axis=1)
        fft = best_of(lambda spec=spec, h0=h0: build_tile(spec, 12.3, h0), 10)
        direct = best_of(lambda sea=sea, grid=grid: sample_surface(sea, grid, 12.3,
                                                                    invert=False), 3)
        print(f"  tile {n:>2} x {n:<2} ({len(sea.components):>4} waves): build by FFT "
              f"{fft * 1e3:7.3f} ms ({fft / n**2 * 1e9:5.0f} ns/grid point), direct sum at "
              f"the grid {direct * 1e3:8.2f} ms; query {_per_point(sea, xy) * 1e6:8.2f} "
              f"us/point, boat step (7 points) {_boat_step(sea, _POINTS_BOAT) * 1e6:8.1f} us, "
              f"mesh boat step {_boat_step(sea, {}, 3) * 1e6:8.1f} us")
        mesh_grid, mesh_direct = _mesh(sea)
        print(f"      the view's 61 x 61 mesh at 1 m (M = {grid_points(sea.tile, 1.0)}): "
              f"by the FFT grid {mesh_grid * 1e3:7.2f} ms, by the direct sum "
              f"{mesh_direct * 1e3:8.2f} ms ({mesh_direct / mesh_grid:5.1f}x)")
    _bench_filtered(seas[64])


def _wave_wrenches(sea: WaveField, shortest: float, times: np.ndarray, initial
                   ) -> np.ndarray:
    """(T, 6) the default boat's buoyancy + diffraction wrench at ``times``, at ``initial``.

    The boat feels ``sea``'s waves >= ``shortest`` m (``boats[].min_wavelength``), from the
    same state (``initial``'s pose, at rest) at each time.
    """
    sc = pipeline.init_scenario(replace(parse_scenario({"boats": [{
        "min_wavelength": shortest}]}), sea=sea))
    system = System.build([sc.boats[0].params])
    inputs = FleetInputs.stack([BoatInputs(0.0, 0.0)])
    out = []
    for t in times:
        state = FleetState.stack([replace(initial, t=float(t))])
        f = pipeline.step(system, state, inputs, sea, 0.01).forces
        out.append(np.concatenate([f.buoyancy.force[0] + f.diffraction.force[0],
                                   f.buoyancy.torque[0] + f.diffraction.torque[0]]))
    return np.array(out)


def _bench_filtered(sea: WaveField) -> None:
    """The mesh boat on the 64 x 64 tile feeling only waves >= min_wavelength: cost, error.

    Error: the RMS over 8 instants of the difference of its buoyancy + diffraction wrench
    from the full sea's, over the RMS of the full sea's less a flat sea's (the waves' part).
    """
    print("  the default (mesh) boat on the 64 x 64 tile, feeling only its waves >= "
          "boats[].min_wavelength (wrench error: RMS over 8 instants, held level, / the "
          "waves' RMS):")
    times = 5.0 + 1.37 * np.arange(8)
    initial = pipeline.init_scenario(replace(parse_scenario({"boats": [{}]}),
                                             sea=WaveField())).boats[0].initial  # level
    full = _wave_wrenches(sea, 0.0, times, initial)
    waves = full - _wave_wrenches(WaveField(), 0.0, times, initial)
    rms = np.sqrt(np.mean(waves**2, axis=0))
    for shortest in (0.0, 6.0, 8.0, 12.0, 16.0):
        kept = len(sea.filtered(shortest).components)
        step = _boat_step(sea, {"min_wavelength": shortest}, 3)
        felt = _wave_wrenches(sea, shortest, times, initial)
        err = np.sqrt(np.mean((felt - full) ** 2, axis=0)) / rms
        print(f"    min_wavelength {shortest:4.0f} m: {kept:>4} waves, step "
              f"{step * 1e6:8.1f} us ({0.01 / step:5.2f}x real time at 100 Hz); error heave "
              f"force {err[2]:6.1%}, roll moment {err[3]:6.1%}, pitch moment {err[4]:6.1%}")
