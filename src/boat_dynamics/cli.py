"""The ``boatsim`` command line (console script; also ``python -m boat_dynamics``).

Exit status: 0 success, 1 runtime failure, 2 invalid input (scenario, arguments, bag path).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Sequence

# One BLAS thread, set before numpy loads (unless the user set it): the wave kernels make many
# small matrix products, and OpenBLAS waking its threads for each one made a 1,000-point x
# 60-component surface query 1.6x slower on the 2-core reference machine (benchmarks/run.py).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__all__ = ["main"]


def _positive_seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number of seconds > 0")
    return value


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="boatsim", description="ROS 2 simulation of boats on Gerstner waves.")
    verbs = parser.add_subparsers(dest="verb", metavar="VERB", required=True)
    run = verbs.add_parser("run", help="start the ocean and dynamics nodes for a scenario",
                           description="Start the ocean node and the dynamics node for every "
                                       "boat of SCENARIO in one process.")
    run.add_argument("scenario", nargs="?", metavar="SCENARIO",
                     help="scenario YAML file (default: scenarios/default.yaml)")
    run.add_argument("--fast", action="store_true",
                     help="run as fast as the machine allows and publish /clock")
    run.add_argument("--duration", type=_positive_seconds, metavar="S",
                     help="stop after S seconds of simulated time")
    run.add_argument("--record", metavar="DIR",
                     help="write every topic to a rosbag2 (MCAP) bag in the new directory DIR")
    run.add_argument("--processes", action="store_true",
                     help="run the ocean and each boat's dynamics in processes of their own "
                          "(real time only)")
    node = verbs.add_parser("_node", help=argparse.SUPPRESS)
    node.add_argument("role", choices=("ocean", "boat"))
    node.add_argument("scenario")
    node.add_argument("--boat", default="")
    node.add_argument("--epoch", type=float, required=True)
    node.add_argument("--duration", type=_positive_seconds)
    node.add_argument("--quiet", action="store_true")
    query = verbs.add_parser(
        "query", help="ask the running ocean for the surface at points",
        description="Print height, normal and water velocity at world points (x, y) from "
                    "/ocean/sample_surface of a running simulation.")
    query.add_argument("coords", nargs="+", type=_finite, metavar="X Y",
                       help="world coordinates, m (pairs: X Y [X Y ...])")
    query.add_argument("--time", type=_finite, metavar="T", dest="sim_time",
                       help="simulation time to sample at, s (default: the ocean's now)")
    query.add_argument("--timeout", type=_positive_seconds, default=5.0, metavar="S",
                       help="seconds to wait for the ocean (default 5)")
    return parser


def _finite(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number")
    return value


def _query(args: argparse.Namespace) -> int:
    from ocean_sim.client import OceanUnavailableError, query_surface

    if len(args.coords) % 2:
        print(f"boatsim query: error: coordinates come in X Y pairs; got {len(args.coords)} "
              "numbers", file=sys.stderr)
        return 2
    points = list(zip(args.coords[::2], args.coords[1::2], strict=True))
    try:
        result = query_surface(points, args.sim_time, args.timeout)
    except OceanUnavailableError as exc:
        print(f"boatsim query: error: {exc}; is `boatsim run` running on this ROS_DOMAIN_ID?",
              file=sys.stderr)
        return 1
    r = result.response
    if not r.success:
        print(f"boatsim query: error: the ocean refused: {r.message}", file=sys.stderr)
        return 2
    when = "now" if args.sim_time is None else f"t = {args.sim_time:g} s"
    print(f"# surface at {when}: x y [m]  height [m]  normal (x y z)  velocity [m/s] (x y z)")
    for (x, y), h, n, v in zip(points, r.heights, r.normals, r.velocities, strict=True):
        print(f"{x:10.3f} {y:10.3f}  {h:9.4f}  ({n.x:8.5f} {n.y:8.5f} {n.z:8.5f})  "
              f"({v.x:7.4f} {v.y:7.4f} {v.z:7.4f})")
    return 0


def _run(args: argparse.Namespace) -> int:
    # Imported here so that `boatsim --help` answers without starting ROS.
    from boat_dynamics.recording import RecordError
    from boat_dynamics.scenario import ScenarioError, default_scenario_path, load_scenario
    from boat_dynamics.simulation import RunOptions, run

    path = args.scenario or default_scenario_path()
    try:
        scenario = load_scenario(path)
    except ScenarioError as exc:
        print(f"boatsim: error: invalid scenario {path}: {exc}", file=sys.stderr)
        return 2
    if args.verb == "_node":
        options = RunOptions(duration=args.duration, role=args.role, boat=args.boat,
                             epoch=args.epoch)
        return run(scenario, options, status=open(os.devnull, "w") if args.quiet
                   else sys.stderr)
    if args.processes:
        if args.fast or args.record or not scenario.simulation.realtime:
            print("boatsim: error: --processes runs in real time, without --fast or --record "
                  "(lockstep and recording across processes are not implemented yet)",
                  file=sys.stderr)
            return 2
        from boat_dynamics.simulation import run_processes

        return run_processes(scenario, str(path), RunOptions(duration=args.duration))
    try:
        return run(scenario, RunOptions(fast=args.fast, duration=args.duration,
                                        record=args.record))
    except RecordError as exc:
        print(f"boatsim: error: {exc}", file=sys.stderr)
        return 2


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``boatsim``; returns the exit status."""
    args = _parser().parse_args(argv)
    try:
        if args.verb in ("run", "_node"):
            return _run(args)
        if args.verb == "query":
            return _query(args)
    except KeyboardInterrupt:
        return 0
    return 2


if __name__ == "__main__":
    sys.exit(main())
