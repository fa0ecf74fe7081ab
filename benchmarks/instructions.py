"""Instructions per physics step, counted by valgrind's callgrind (`make bench`).

Counts hold on a busy machine where times do not. Each case runs in a child process under
callgrind twice, for a short and a long stretch of steps after the same set-up; the
difference divided by the extra steps is the cost of a step, set-up and imports cancelled.
The anchor is Fossen's PythonVehicleSimulator Otter step (``pvs_otter.py``, vendored for this
purpose), counted the same way. Prints nothing but a note when valgrind is not installed.

Child use (what the parent runs under callgrind): ``instructions.py --child CASE STEPS``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import math
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent

#: Case -> (boats, label, target instructions per boat-step or None).
CASES = {
    "one": (1, "one default boat, physics step", 180e3),
    "fleet10": (10, "per boat in a fleet of 10 default boats", None),
    "fk10": (10, "  of which the Froude-Krylov pressure (768 triangles)", 400e3),
    "fleet100": (100, "per boat in a fleet of 100 default boats", 20e3),
}
#: Steps of the short and the long stretch per case (fewer for big fleets: callgrind is slow).
STEPS = {"one": (20, 120), "fleet10": (5, 25), "fk10": (5, 25), "fleet100": (2, 6),
         "pvs": (200, 1200)}


def _child(case: str, steps: int) -> None:
    """Set up ``case`` and run ``steps`` physics steps (or PVS Otter steps)."""
    if case == "pvs":
        sys.path.insert(0, str(HERE))
        import pvs_otter

        pvs_otter.run(20)
        pvs_otter.run(steps)
        return
    import yaml

    from boat_dynamics.physics.core import pipeline
    from boat_dynamics.physics.core.boat import BoatInputs
    from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
    from boat_dynamics.physics.scenario import default_scenario_path, parse_scenario

    count = CASES[case][0]
    data = yaml.safe_load(default_scenario_path().read_text())
    side = math.ceil(math.sqrt(count))
    data["boats"] = [{**data["boats"][0], "name": f"b{i}", "initial_pose": {
        "position": [12.0 * (i % side), 12.0 * (i // side), 0.0]}} for i in range(count)]
    scenario = pipeline.init_scenario(parse_scenario(data))
    initial = [b.initial for b in scenario.boats]
    system = System.build([b.params for b in scenario.boats])
    state = FleetState.stack(initial)
    inputs = FleetInputs.stack([BoatInputs(1.0, 0.2)] * count)
    for _ in range(10 + (0 if case == "fk10" else steps)):
        state = pipeline.step(system, state, inputs, scenario.sea, 0.01).state
    if case == "fk10":
        _froude_krylov(system, state, scenario.sea, steps)


def _froude_krylov(system, state, sea, steps: int) -> None:
    """The Froude-Krylov pressure model alone, ``steps`` times 0.01 s apart.

    The surface at the hull vertices, the pressure head there, the clip and the pressure
    integral, with the boats held at ``state``'s poses.
    """
    import numpy as np

    from boat_dynamics.physics.body.clip import clip_hulls
    from boat_dynamics.physics.body.owner_kernel import to_world_f64
    from boat_dynamics.physics.core.contact import reference_points
    from boat_dynamics.physics.force_models.mesh_buoyancy import pressure_wrenches
    from ocean_sim.physics.waves import pressure_head, sample_surface

    (g,) = system.groups
    rot, ref = reference_points(system, state)
    world = to_world_f64(rot, ref, g.owner, g.body)
    rho_g = system.water_density * system.gravity
    for k in range(steps):
        t = state.t + 0.01 * k
        surface = sample_surface(sea, world[:, :2], t)
        heads = pressure_head(sea, surface.rest_xy, surface.heights, world[:, 2], t)
        wet = clip_hulls(g.faces, world, surface.heights - world[:, 2], heads)
        pressure_wrenches(wet, g.face_owner.take(wet.faces), g.index.shape[0], state.position,
                          np.asarray(rho_g))


def _count(case: str, steps: int) -> float:
    """Instructions of one child run under callgrind."""
    # a venv's python is started through its base interpreter: follow it (--trace-children)
    # and add up every process's count; (with /dev/null as the output it prints no totals)
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(
            ["valgrind", "--tool=callgrind", "--trace-children=yes",
             f"--callgrind-out-file={tmp}/callgrind.%p.out", sys.executable,
             str(Path(__file__).resolve()), "--child", case, str(steps)],
            capture_output=True, text=True, check=True)
    found = re.findall(r"Collected\s*:\s*(\d+)", out.stderr)
    if not found:
        raise RuntimeError(f"no instruction count from callgrind: {out.stderr[-500:]}")
    return float(sum(int(n) for n in found))


def per_step(case: str) -> float:
    """Instructions per step of ``case`` (the difference of a short and a long run).

    A first run of the case's set-up alone compiles whatever kernels its arrays need that no
    earlier run did (for the CPU valgrind shows, without AVX-512: minutes, once), so that
    neither counted run includes a compilation.
    """
    short, long = STEPS[case]
    _count(case, 0)
    return (_count(case, long) - _count(case, short)) / (long - short)


def bench_instructions() -> None:
    """Print instructions per step of every case beside its target and the PVS anchor."""
    print("== instructions per physics step (valgrind's callgrind; default boat: Froude-Krylov "
          "pressure on 768 triangles, its coefficients, Cummins; the default scenario's sea)")
    if shutil.which("valgrind") is None:
        print("  valgrind not installed: no instruction counts (Debian: apt-get install valgrind)")
        return
    anchor = None
    if (HERE / "pvs_otter.py").exists():
        anchor = per_step("pvs")
        print(f"  {'anchor: PythonVehicleSimulator Otter step (numpy, no waves)':<52} "
              f"{anchor / 1e3:9.0f} k")
    for case, (boats, label, target) in CASES.items():
        each = per_step(case) / boats
        notes = []
        if target is not None:
            notes.append(f"target {target / 1e3:.0f} k")
        if anchor:
            notes.append(f"{each / anchor:.2f}x the anchor")
        print(f"  {label:<52} {each / 1e3:9.0f} k  ({'; '.join(notes)})")


def main() -> None:
    """Print the counts, or (``--child``) be one counted run."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--child", nargs=2, metavar=("CASE", "STEPS"))
    args = parser.parse_args()
    if args.child:
        _child(args.child[0], int(args.child[1]))
    else:
        bench_instructions()


if __name__ == "__main__":
    main()
