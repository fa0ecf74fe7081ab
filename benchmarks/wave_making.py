"""The cost of boats that make waves (`make bench`, `--only wakes`): prints, asserts nothing.

Fleets of 2 and 10 default boxes at 3 m/s in a column 20 m apart (each in the wakes of those
ahead) on calm water, stepped with `made_waves: all` and `none`: the difference per step,
and per boat pair (a source and a receiver). Then two boxes at rest 6 m apart in the default
sea (3 components) and in a 16-component JONSWAP sea, `scattered` against `none`: the
radiated and scattered waves' cost per pair (both passes of the multiple scattering). Then
the wake's elevation per point and boat (the view draws it on its sea).
"""

from __future__ import annotations

import numpy as np
from timing import best_of

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.physics.wave_making.kelvin_wake import wake_elevation

__all__ = ["bench_wave_making"]


def _step_cost(count: int, made: str, ocean: dict | None = None) -> float:
    """Seconds per step of ``count`` boats: in a column at 3 m/s (calm), or at rest.

    At rest (``ocean``, a scenario's ocean block, given): 6 m apart abeam.
    """
    if ocean is None:
        boats = [{"name": f"b{i}", "hydrodynamics": {"made_waves": made},
                  "initial_pose": {"position": [-20.0 * i, 2.0 * (i % 2), 0.0],
                                   "velocity": [3.0, 0.0, 0.0]}} for i in range(count)]
        sc = parse_scenario({"boats": boats})
    else:
        sc = parse_scenario({"ocean": ocean, "boats": [
            {"name": f"b{i}", "hydrodynamics": {"made_waves": made},
             "initial_pose": {"position": [0.0, 6.0 * i, 0.0]}} for i in range(count)]})
    system, state = pipeline.start(sc.boats, sc.sea)
    inputs = FleetInputs.stack([BoatInputs(1.0, 0.0)] * count)
    held = [state]

    def steps():
        s = held[0]
        for _ in range(20):
            s = pipeline.step(system, s, inputs, sc.sea, 0.01).state
        held[0] = s

    steps()
    return best_of(steps, 5) / 20


def bench_wave_making() -> None:
    """Print the made waves' cost per step and per boat pair, and the wake's per point."""
    print("== Boats that make waves: default boxes at 3 m/s in a column, calm water")
    for count in (2, 10):
        on, off = _step_cost(count, "all"), _step_cost(count, "none")
        pairs = count * (count - 1)
        print(f"  {count:2d} boats: step {off * 1e6:8.1f} us without, {on * 1e6:8.1f} us with "
              f"made waves: {(on - off) * 1e6 / pairs:6.1f} us per boat pair ({pairs} pairs)")
    seas = {"the default sea (3 components)": None,
            "16 JONSWAP components": {"spectrum": {"significant_height": 0.5, "peak_period": 3.0,
                                                   "components": 16}}}
    for name, ocean in seas.items():
        if ocean is None:
            ocean = {"components": [
                {"amplitude": 0.30, "wavelength": 25.0, "steepness": 0.5},
                {"amplitude": 0.15, "wavelength": 12.0, "direction_deg": 30.0, "steepness": 0.5},
                {"amplitude": 0.08, "wavelength": 6.0, "direction_deg": -20.0}]}
        on, off = _step_cost(2, "scattered", ocean), _step_cost(2, "none", ocean)
        print(f"  2 boats at rest 6 m apart in {name}: step {off * 1e6:8.1f} us without, "
              f"{on * 1e6:8.1f} us with radiated and scattered waves: "
              f"{(on - off) * 1e6 / 2:6.1f} us per boat pair")
    sc = pipeline.init_scenario(parse_scenario({"boats": [{}]}))
    ship = sc.boats[0].params.thin_ship
    xy = np.random.default_rng(2).uniform((-80.0, -30.0), (0.0, 30.0), (20000, 2))
    per_point = best_of(lambda: wake_elevation(ship, 3.0, np.zeros(2), 0.0, xy), 5) / len(xy)
    print(f"  a wake's elevation (the view): {per_point * 1e6:6.2f} us per point and boat "
          "(half the points inside its wedge)")
