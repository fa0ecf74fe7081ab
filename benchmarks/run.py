"""boatsim benchmarks (`make bench`): prints figures, asserts nothing.

Wave queries (heights + normals + velocities, inversion included), the FFT ocean's tile and
queries beside the Gerstner sum (fft_ocean.py), the boat step, and the
real-time factor of `boatsim run --fast` (in-process, no subscribers), and the same run in one
process against shards (`--shards N`, subprocesses as a user starts them).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # as `boatsim` does (see cli.py)

import argparse
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from timing import best_of

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.scenario import default_scenario_path, load_scenario, parse_scenario
from boat_msgs_py.process import keep_freed_memory
from ocean_sim.physics.waves import WaveComponent, WaveField, sample_surface

keep_freed_memory()  # as `boatsim` does (see boat_msgs_py/process.py)

_BOX_COEFFICIENTS = (Path(__file__).resolve().parents[1] / "tests" / "data" / "hydro"
                     / "box_4x2x1_d0.5.npz")


def _sea(n: int, seed: int = 0) -> WaveField:
    rng = np.random.default_rng(seed)
    lam = rng.uniform(3.0, 120.0, n)
    a = 0.9 / n * lam / (2 * math.pi)  # sum Q k a = 0.9 * Q
    return WaveField(tuple(WaveComponent(float(a[i]), float(lam[i]), float(rng.uniform(-3, 3)),
                                         0.8, float(rng.uniform(0, 6.28))) for i in range(n)))


def bench_waves() -> None:
    """Time sample_surface at a boat's and fleets' point counts, and two large sizes.

    A boat's and fleets' point counts on a 3-component sea, then 1,000 points on 60 components
    and 100,000 on 16; float64 (compiled), its numpy oracle (float64 before it was compiled),
    float32 (numpy); with and without the inversion.
    """
    from ocean_sim.physics.waves import _sample_numpy

    print("== wave queries: sample_surface (heights, normals, velocities), "
          f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']}; float64 is compiled, "
          "numpy64 its numpy oracle")
    for points, comps, repeats in ((200, 3, 200), (2_000, 3, 50), (20_000, 3, 10),
                                   (1_000, 60, 30), (100_000, 16, 3)):
        sea = _sea(comps)
        xy = np.random.default_rng(1).uniform(-200, 200, (points, 2))
        ref = sample_surface(sea, xy, 123.4).heights
        for precision in ("float64", "numpy64", "float32"):
            for invert in (True, False):
                def query(sea=sea, xy=xy, precision=precision, invert=invert):
                    if precision == "numpy64":
                        return _sample_numpy(sea, xy, 123.4, "float64", invert)
                    return sample_surface(sea, xy, 123.4, precision=precision, invert=invert)

                sec = best_of(query, repeats)
                err = np.abs(query().heights - ref).max()
                label = "inverted" if invert else "ignore horizontal"
                print(f"  {points:>7} pts x {comps:>2} comps, {precision}, {label:<17}: "
                      f"{sec * 1e3:8.3f} ms ({sec / (points * comps) * 1e9:6.1f} ns/point-comp),"
                      f" max height error {err:.1e} m")


def bench_boat_step() -> None:
    """Microseconds per boat-step with 16 wave components, per buoyancy model.

    Two figures per hull: one boat stepped alone (a one-boat System, as the node steps a lone
    boat), and the cost per boat when a
    fleet of identical boats is stepped together (``pipeline.step``, what the dynamics node
    does), where numpy's per-call cost is shared by all boats.
    """
    print("== boat step, 16 wave components, float32 surface queries (the scenario default): "
          "one boat alone, and per boat in a fleet (best of 15 timed chunks)")
    sea = _sea(16)
    inputs = BoatInputs(1.0, 0.2)
    seed = {"buoyancy": {"pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}}
    cases = (
        ("sample points, 7 (boat layout)", {"buoyancy": {"model": "sample_points",
                                                          "layout": "boat"}}, (10, 100)),
        # a boat that sets nothing until 2026-12 (issue 32): the seed notes' mesh model
        ("seed notes' mesh box, 12 triangles", seed, (10, 100)),
        ("seed notes' mesh box, 972 triangles",
         {**seed, "hull": {"type": "box", "subdivisions": 9}}, (10,)),
        ("mesh box, 12 tri, coefficients, resonance", _coefficients("resonance"), (10, 100)),
        ("mesh box, 12 tri, coefficients, Cummins", _coefficients("cummins"), (10, 100)),
        ("mesh box, 12 tri, water velocity over the hull",
         {**seed, "damping": {"water_velocity": "hull"}}, (10, 100)),
        # the default scenario's boat from issue 10 to 2026-12: linear seakeeping
        ("linear seakeeping: file, Cummins, hull water",
         {"center_of_mass": [0.0, 0.0, -0.2], "buoyancy": {"pressure": "linear"},
          "hydrodynamics": {"coefficients": "auto"},
          "damping": {"linear": [500.0, 4000.0, 0.0, 1000.0, 0.0, 3000.0],
                      "water_velocity": "hull"}}, (10, 100)),
        # every mesh boat's default since 2026-12 (issue 32), panelled by pipeline.init for
        # this sea's shortest wave (so initialized in it): Froude-Krylov pressure on the
        # wetted hull, its coefficients (auto), Cummins, the added mass at speed
        ("default (sets nothing): Froude-Krylov, file, Cummins", {}, (10, 100)),
        ("mesh box, Froude-Krylov, no coefficients",
         {"buoyancy": {"pressure": "froude_krylov"}, "hydrodynamics": {"coefficients": "none"}},
         (10,)),
    )
    for label, boat, fleet_sizes in cases:
        fk = "Froude" in label or not boat
        sc = _initialized(parse_scenario({"boats": [boat]}), sea if fk else None)
        params, initial = sc.boats[0].params, sc.boats[0].initial
        if fk:
            label = f"{label}, {params.buoyancy.mesh.faces.shape[0]} tri"
        n = 20 if "972" in label or fk else 50

        one = System.build([params])
        state = [FleetState.stack([initial])]
        one_input = FleetInputs.stack([inputs])

        def alone(one=one, state=state, n=n, one_input=one_input):
            s = state[0]
            for _ in range(n):
                s = pipeline.step(one, s, one_input, sea, 0.01).state
            state[0] = s

        alone()  # settle from the release first, then time chunks of steps
        figures = [f"alone {best_of(alone, 15) / n * 1e6:8.1f}"]
        for fleet_size in fleet_sizes:
            side = math.ceil(math.sqrt(fleet_size))
            fleet_sc = _initialized(parse_scenario({"boats": [
                {**boat, "name": f"b{i}", "initial_pose": {"position": [
                    12.0 * (i % side), 12.0 * (i // side), 0.0]}} for i in range(fleet_size)]}),
                sea if fk else None)
            fleet = System.build([b.params for b in fleet_sc.boats])
            fleet_state = [FleetState.stack([b.initial for b in fleet_sc.boats])]
            commands = FleetInputs.stack([inputs] * fleet_size)
            m = 5 if "972" in label or fk else 10

            def together(fleet=fleet, fleet_state=fleet_state, commands=commands, m=m):
                s = fleet_state[0]
                for _ in range(m):
                    s = pipeline.step(fleet, s, commands, sea, 0.01).state
                fleet_state[0] = s

            together()
            fsec = best_of(together, 15)
            figures.append(f"in a fleet of {fleet_size:>3}: {fsec / (m * fleet_size) * 1e6:7.1f}")
        print(f"  {label:<42}: {'; '.join(figures)} us per boat-step")


def _coefficients(radiation: str) -> dict:
    """The default box with its potential-flow file (diffraction; radiation as given)."""
    return {"center_of_mass": [0.0, 0.0, -0.2], "buoyancy": {"pressure": "hydrostatic"},
            "hydrodynamics": {"coefficients": str(_BOX_COEFFICIENTS), "radiation": radiation}}


def _initialized(scenario, sea: WaveField | None):
    """``scenario`` initialized (pipeline.init_scenario), in ``sea`` instead of its own if given."""
    if sea is None:
        return pipeline.init_scenario(scenario)
    return pipeline.init_scenario(replace(scenario, sea=sea))


def _fleet(n: int) -> dict:
    side = math.ceil(math.sqrt(n))
    return {"ocean": {"spectrum": {"significant_height": 1.0, "peak_period": 6.0,
                                   "components": 16}},
            "boats": [{"name": f"b{i}", "initial_pose": {"position": [12.0 * (i % side),
                                                                       12.0 * (i // side),
                                                                       0.0]}}
                      for i in range(n)]}


def _quiet_nodes() -> None:
    """No per-boat start-up log lines between the figures."""
    import rclpy.logging

    for name in ("boat_dynamics", "ocean"):
        rclpy.logging.set_logger_level(name, rclpy.logging.LoggingSeverity.WARN)


def bench_run(seconds: float, boats: int) -> None:
    """Real-time factor of the whole in-process simulation with --fast (mesh boats).

    Two figures: the simulation loop alone (the run's own final status line, which counts
    from the first step), and the whole call including node set-up.
    """
    import io
    import re

    from boat_dynamics.ros.runner import RunOptions, run

    _quiet_nodes()
    sc = parse_scenario(_fleet(boats)) if boats > 1 else load_scenario(default_scenario_path())
    loops, totals = [], []
    for _ in range(3):  # this machine's speed varies between runs: best and range of three
        status = io.StringIO()
        t0 = time.perf_counter()
        run(sc, RunOptions(fast=True, duration=seconds), status=status)
        totals.append(seconds / (time.perf_counter() - t0))
        loops.append(float(re.findall(r"x\s*([\d.]+)", status.getvalue())[-1]))
    print(f"  {boats:>3} boat(s), {seconds:g} s simulated: real-time factor {max(loops):6.2f} "
          f"(loop, best of 3; range {min(loops):.2f}-{max(loops):.2f}; "
          f"{max(totals):.2f} with set-up)")


def phase_patches() -> list[tuple[object, str, str]]:
    """(owner, attribute, label) of every phase :func:`bench_phases` times (tests check them).

    The parts of a phase follow it, their labels indented.
    """
    from boat_dynamics.ros import node as node_module
    from boat_dynamics.ros import outputs
    from boat_dynamics.ros import runner as simulation

    return [
        (pipeline, "step", "physics (pipeline.step)"),
        (node_module.DynamicsNode, "publish_outputs", "all publishing"),
        (node_module.DynamicsNode, "_state_values", "  state values (B, 13)"),
        (outputs.FleetPublisher, "states", "  odom, pose, twist"),
        (outputs.FleetPublisher, "sensor_readings", "  sensors"),
        (outputs.FleetPublisher, "wrenches", "  wrench/*"),
        # the surface contact of the state reached, which the next step takes (no extra cost)
        (node_module, "contact", "  /diagnostics contact"),
        (node_module, "fleet_reports", "  /diagnostics reports"),
        (outputs.FleetPublisher, "diagnostics", "  /diagnostics packed"),
        (simulation.OceanNode, "advance", "/ocean/surface"),
        (simulation, "spin_pending", "ROS callbacks (spin)"),
    ]


def bench_phases(seconds: float, boats: int) -> None:
    """Where a step of `run --fast` goes: wall time per step of each phase (timed by wrappers).

    The wrappers cost about a microsecond per call; the figures are for finding the next thing
    to speed up, the real-time factor above is the figure that counts. A phase with parts
    (indented below it) has the rest of its time on a line of its own (/clock, stamps, calls).
    """
    import io

    from boat_dynamics.ros import runner as simulation

    _quiet_nodes()
    spent: dict[str, float] = {}

    def timed(owner, name, label):
        original = getattr(owner, name)

        def wrapper(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                spent[label] = spent.get(label, 0.0) + time.perf_counter() - t0

        setattr(owner, name, wrapper)
        return original

    patches = phase_patches()
    originals = [(owner, name, timed(owner, name, label)) for owner, name, label in patches]
    try:
        run_options = simulation.RunOptions(fast=True, duration=seconds)
        simulation.run(parse_scenario(_fleet(boats)), run_options, status=io.StringIO())
    finally:
        for owner, name, original in originals:
            setattr(owner, name, original)
    print(f"  {boats} boats, {seconds:g} s: wall time per 10 ms step")
    for label, per_step in _phase_lines([label for _, _, label in patches], spent,
                                        seconds * 100.0):
        print(f"    {label:<26} {per_step:8.1f} us")


def _phase_lines(labels: list[str], spent: dict[str, float],
                 steps: float) -> list[tuple[str, float]]:
    """(label, us per step) of each timed phase, in ``labels``' order.

    After the parts of a phase (the indented labels that follow it) comes the rest of it.
    """
    lines: list[tuple[str, float]] = []
    whole, parts = None, 0.0  # the last phase that is not a part, the sum of its parts
    for label in [*labels, None]:
        if label is not None and label.startswith(" "):
            parts += spent.get(label, 0.0)
        else:
            if whole in spent and parts:
                lines.append(("  rest", (spent[whole] - parts) / steps * 1e6))
            whole, parts = label, 0.0
        if label in spent:
            lines.append((label, spent[label] / steps * 1e6))
    return lines


def _fleet_file(boats: int, model: str, folder: Path) -> Path:
    """A scenario file of ``boats`` default boxes (``model``: their buoyancy model)."""
    import yaml

    data = _fleet(boats)
    if model != "mesh":
        for b in data["boats"]:
            b["buoyancy"] = {"model": model}
    path = folder / f"fleet_{boats}_{model}.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def _stat(pid: int) -> list[str] | None:
    """The fields of /proc/PID/stat after the command name (state, ppid, ...), or None."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None


def _roles(root: int) -> dict[int, str]:
    """Pid -> role (parent, ocean, shard K/N, surface server) of ``root``'s process tree."""
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit() and (fields := _stat(int(entry))):
            children.setdefault(int(fields[1]), []).append(int(entry))
    roles, todo = {}, [root]
    while todo:
        pid = todo.pop()
        todo += children.get(pid, [])
        try:
            words = Path(f"/proc/{pid}/cmdline").read_text().split("\0")
        except OSError:
            continue
        roles[pid] = "parent" if pid == root else _role(words)
    return roles


def _role(words: list[str]) -> str:
    """The role of a child of ``boatsim run`` from its command line."""
    if "_node" in words:
        role = words[words.index("_node") + 1]
        return f"shard {words[words.index('--shard') + 1]}" if "--shard" in words else role
    return "surface server" if "_surface" in words else "other"


def _cpu_seconds(pids) -> dict[int, float]:
    """Pid -> CPU seconds (user + system, all threads) so far, of those still there."""
    tick = os.sysconf("SC_CLK_TCK")
    out = {}
    for pid in pids:
        if fields := _stat(pid):
            out[pid] = (int(fields[11]) + int(fields[12])) / tick
    return out


def _timed_cli(args: list[str]) -> dict:
    """Run ``boatsim ARGS``: its loop's real-time factor, its start, where its CPU went.

    The loop factor is the run's last status line (the first dynamics process's, counted
    from its first step); the start is when that process logs "running". Each process's CPU
    over the loop is read from /proc (Linux) when that line appears and at the last status
    line (it comes as the loop ends), or, for a process that has ended by then, 0.05 s or less
    before it ended: CPU seconds per simulated second, by role.

    Returns:
        factor (loop real-time factor), start (s to the first step), total (s in all),
        cpu ({role: CPU s per simulated s over the loop}).
    """
    import re
    import subprocess
    import sys
    import threading

    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "boat_dynamics", *args],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    started = math.nan
    lines = []
    roles: dict[int, str] = {}
    first, last, latest = {}, {}, {}  # pid -> CPU s
    end_t = 0.0  # s, the simulation time of the last status line

    def sample() -> None:  # the latest reading of each process, for those that end early
        while proc.poll() is None:
            latest.update(_cpu_seconds(list(roles)))
            time.sleep(0.05)

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    status = re.compile(r"^t\s+([\d.]+) s\s+x\s*([\d.]+)")
    for line in proc.stderr:
        lines.append(line)
        if math.isnan(started) and "running " in line and "boat(s)" in line:
            started = time.perf_counter() - t0
            roles.update(_roles(proc.pid))
            first = _cpu_seconds(roles)
        elif (m := status.match(line)) and first:
            last, end_t = {**latest, **_cpu_seconds(list(roles))}, float(m.group(1))
    proc.wait()
    sampler.join()
    total = time.perf_counter() - t0
    factors = re.findall(r"t\s+[\d.]+ s\s+x\s*([\d.]+)", "".join(lines))
    if proc.returncode != 0 or not factors:
        raise RuntimeError(f"boatsim {' '.join(args)} failed:\n{''.join(lines[-20:])}")
    cpu: dict[str, float] = {}
    for pid, role in roles.items():
        if pid in first and pid in last and end_t > 0:
            cpu[role] = cpu.get(role, 0.0) + (last[pid] - first[pid]) / end_t
    return {"factor": float(factors[-1]), "start": started, "total": total, "cpu": cpu}


def _cpu_line(cpu: dict[str, float]) -> str:
    """'parent 0.01, ocean 0.02, ...' (CPU s per simulated s), then their sum."""
    parts = [f"{role} {s:.3f}" for role, s in sorted(cpu.items()) if s >= 0.0005]
    return f"{', '.join(parts)}; in all {sum(cpu.values()):.3f}"


def bench_scale(seconds: float) -> None:
    """One process against shards: `boatsim run --fast` as a user starts it (subprocesses).

    Figures per configuration: the loop's real-time factor (best and range of the runs), the
    seconds from launch to the first step, and where the CPU went (CPU seconds per simulated
    second of each process over the loop, from the best run); then the throughput ratio of
    the best loops, and with 100 boats the median and range of the ratios of runs made in
    turn (one process, then 2 shards: a change of this machine's speed hits both).
    """
    import statistics
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        for boats, model, sim_s, shard_counts, repeats in (
                (10, "mesh", seconds, (1, 2), 2), (100, "mesh", seconds, (1, 2), 5),
                (1000, "sample_points", 2.0, (1, 2), 1)):
            path = _fleet_file(boats, model, Path(tmp))
            runs: dict[int, list[dict]] = {shards: [] for shards in (0, *shard_counts)}
            for _ in range(repeats):  # in turn
                for shards in runs:
                    extra = ["--shards", str(shards)] if shards else []
                    runs[shards].append(_timed_cli(["run", str(path), "--fast", "--duration",
                                                    str(sim_s), *extra]))
            for shards, rs in runs.items():
                loops = [r["factor"] for r in rs]
                best = max(rs, key=lambda r: r["factor"])
                where = f"{shards} shard(s)" if shards else "one process"
                print(f"  {boats:>4} {model} boats, {where:<12}: real-time factor "
                      f"{max(loops):6.2f} (loop; range {min(loops):.2f}-{max(loops):.2f}), "
                      f"first step after {min(r['start'] for r in rs):5.1f} s, "
                      f"{min(r['total'] for r in rs):5.1f} s in all")
                print(f"         CPU s per simulated s (best run): {_cpu_line(best['cpu'])}")
            for shards in shard_counts:
                pairs = [b["factor"] / a["factor"] for a, b in zip(runs[0], runs[shards],
                                                                   strict=True)]
                spread = (f"; runs in turn: median {statistics.median(pairs):.2f}, range "
                          f"{min(pairs):.2f}-{max(pairs):.2f}" if len(pairs) > 2 else "")
                ratio = max(r["factor"] for r in runs[shards]) / max(r["factor"] for r in runs[0])
                print(f"  {boats:>4} boats: {shards} shard(s) / one process throughput "
                      f"{ratio:.2f} (best loops){spread}")


def bench_split() -> None:
    """What splitting 100 boats into 2 shards of 50 can gain in the physics, at best.

    ``pipeline.step`` of the scale bench's fleet (default mesh boxes, 16 components) at 50
    and 100 boats, timed in turn in one process (best of 15 chunks of 10 steps): its cost
    per step is a fixed part plus a part per boat, and every shard pays the fixed part again,
    so two shards of 50 step at most T(100) / T(50) times as fast as one process of 100, on
    two idle cores. The run's other work (publishing, spinning) is almost all per boat.
    """
    runs = {}
    for n in (50, 100):
        sc = pipeline.init_scenario(parse_scenario(_fleet(n)))
        runs[n] = (System.build([b.params for b in sc.boats]),
                   [FleetState.stack([b.initial for b in sc.boats])],
                   FleetInputs.stack([BoatInputs(0.5, 0.1)] * n), sc.sea)

    def chunk(n: int) -> None:
        system, state, commands, sea = runs[n]
        s = state[0]
        for _ in range(10):
            s = pipeline.step(system, s, commands, sea, 0.01).state
        state[0] = s

    for n in runs:
        chunk(n)  # settle from the release
    steps = {n: math.inf for n in runs}
    for _ in range(15):  # in turn: a change of this machine's speed hits both
        for n in runs:
            steps[n] = min(steps[n], best_of(lambda n=n: chunk(n), 1) / 10)
    per_boat = (steps[100] - steps[50]) / 50
    fixed = steps[50] - 50 * per_boat
    print(f"  pipeline.step, 50 / 100 mesh boats: {steps[50] * 1e6:.0f} / "
          f"{steps[100] * 1e6:.0f} us a step = {fixed * 1e6:.0f} us fixed + "
          f"{per_boat * 1e6:.1f} us a boat; 2 shards of 50 against one process of 100: "
          f"at most {steps[100] / steps[50]:.2f}x the physics throughput")


def main() -> None:
    """Run every benchmark."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--run-seconds", type=float, default=20.0)
    parser.add_argument("--only", choices=("instructions", "waves", "fft", "wakes", "boat", "run",
                                           "phases", "scale"),
                        help="one group only")
    args = parser.parse_args()
    if args.only in (None, "waves"):
        bench_waves()
    if args.only in (None, "fft"):
        from fft_ocean import bench_fft

        bench_fft()
    if args.only in (None, "wakes"):
        from wave_making import bench_wave_making

        bench_wave_making()
    if args.only in (None, "boat"):
        bench_boat_step()
    if args.only in (None, "run"):
        print("== boatsim run --fast (100 Hz physics, default publish rates, no subscribers)")
        for boats, seconds in ((1, args.run_seconds), (10, args.run_seconds / 4),
                               (100, args.run_seconds / 20)):
            bench_run(seconds, boats)
    if args.only in (None, "phases"):
        print("== where a step goes, boatsim run --fast with 10 mesh boats")
        bench_phases(args.run_seconds / 2, 10)
    if args.only in (None, "scale"):
        print("== boatsim run --fast in processes: one process against --shards N")
        bench_split()
        bench_scale(args.run_seconds / 2)
    if args.only in (None, "instructions"):  # last: minutes under valgrind
        from instructions import bench_instructions

        bench_instructions()


if __name__ == "__main__":
    main()
