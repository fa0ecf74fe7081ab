"""The ``boatsim`` command line (console script; also ``python -m boat_dynamics``).

Exit status: 0 success, 1 runtime failure, 2 invalid input (scenario, arguments, bag path).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Sequence
from pathlib import Path

# One BLAS thread, set before numpy loads (unless the user set it): the wave kernels make many
# small matrix products, and OpenBLAS waking its threads for each one made a 1,000-point x
# 60-component surface query 1.6x slower on the 2-core reference machine (benchmarks/run.py).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from boat_msgs_py.process import keep_freed_memory, stop_on_signals

keep_freed_memory()

__all__ = ["main"]


def _positive(text: str, what: str = "number") -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite {what} > 0")
    return value


def _positive_seconds(text: str) -> float:
    return _positive(text, "number of seconds")


def _speed_factor(text: str) -> float:
    return _positive(text, "speed factor (a multiple of real time)")


def _shard(text: str) -> tuple[int, int]:
    """``K/N`` of ``--only shard K/N``: shard K (0 .. N - 1) of N."""
    k, _, n = text.partition("/")
    try:
        index, count = int(k), int(n)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not K/N (shard K of N, "
                                         "e.g. 0/2)") from None
    if not 0 <= index < count:
        raise argparse.ArgumentTypeError(f"{text!r}: K must be 0 .. N - 1 (e.g. 0/2 and 1/2)")
    return index, count


def _too_many_shards(count: int, boats: int) -> str | None:
    """Why ``count`` shards cannot share ``boats`` boats, or None when they can."""
    if count > boats:
        return f"{count} shards for {boats} boat(s); at most one shard per boat"
    return None


def _integer(text: str, low: int) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < low:
        raise argparse.ArgumentTypeError(f"{text!r}: must be at least {low}")
    return value


def _count(text: str) -> int:
    return _integer(text, 1)


def _whole_number(text: str) -> int:
    return _integer(text, 0)


def _port(text: str) -> int:
    value = _integer(text, 1)
    if value > 65535:
        raise argparse.ArgumentTypeError(f"{text!r}: a port is at most 65535")
    return value


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="boatsim", description="ROS 2 simulation of boats on Gerstner waves.")
    verbs = parser.add_subparsers(dest="verb", metavar="VERB", required=True)
    _add_run(verbs)
    _add_query(verbs)
    _add_bag_verbs(verbs)
    _add_rao(verbs)
    _add_hydro(verbs)
    _add_introspection(verbs)
    _add_view(verbs)
    teleop = verbs.add_parser("teleop", help="drive a boat from the keyboard")
    teleop.add_argument("--ns", default="", metavar="NAME",
                        help="the boat's namespace (default: the root namespace)")
    for verb, sub in verbs.choices.items():
        sub.set_defaults(handler=_HANDLERS[verb])
    return parser


def _add_introspection(verbs) -> None:
    """``topic``, ``node``, ``param``: ``ros2``'s verbs, for an install without ``ros2``."""
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--spin-time", type=_positive_seconds, default=1.0, metavar="S",
                        help="seconds of discovery before answering (default 1)")
    topic = verbs.add_parser("topic", help="as `ros2 topic`: list, info, echo, hz, pub")
    sub = topic.add_subparsers(dest="action", metavar="ACTION", required=True)
    listing = sub.add_parser("list", parents=[common], help="the topics on the graph")
    listing.add_argument("-t", "--show-types", action="store_true")
    listing.add_argument("-c", "--count-topics", action="store_true")
    info = sub.add_parser("info", parents=[common], help="a topic's type and endpoints")
    info.add_argument("topic_name")
    info.add_argument("-v", "--verbose", action="store_true",
                      help="each endpoint's node and QoS")
    echo = sub.add_parser("echo", parents=[common], help="print a topic's messages as YAML")
    echo.add_argument("topic_name")
    echo.add_argument("--once", action="store_true", help="the first message, then exit")
    echo.add_argument("--full-length", "-f", action="store_true",
                      help="print long arrays whole")
    hz = sub.add_parser("hz", parents=[common],
                        help="a topic's rate, by wall-clock arrival (ros2's --wall-time)")
    hz.add_argument("topic_name")
    hz.add_argument("--window", "-w", type=_count, default=10000, metavar="N")
    for p in (echo, hz):
        p.add_argument("--timeout", type=_positive_seconds, metavar="S",
                       help="stop after S seconds (default: at Ctrl-C)")
    pub = sub.add_parser("pub", parents=[common], help="publish a message from YAML values")
    pub.add_argument("topic_name")
    pub.add_argument("message_type", help="e.g. std_msgs/msg/Float64")
    pub.add_argument("values", nargs="?", default="{}", help="YAML, e.g. '{data: 0.5}'")
    pub.add_argument("-r", "--rate", type=_positive, default=1.0, metavar="HZ")
    pub.add_argument("-1", "--once", action="store_true", help="publish one message, exit")
    pub.add_argument("-t", "--times", type=_count, metavar="N", help="publish N, then exit")
    pub.add_argument("-w", "--wait-matching-subscriptions", type=_whole_number, metavar="N",
                     help="first wait for N matching subscriptions (default 1 with --once or "
                          "--times, else 0)")
    node = verbs.add_parser("node", help="as `ros2 node`: list")
    node.add_subparsers(dest="action", metavar="ACTION", required=True).add_parser(
        "list", parents=[common], help="the nodes on the graph")
    param = verbs.add_parser("param", help="as `ros2 param`: list, get, set, dump")
    psub = param.add_subparsers(dest="action", metavar="ACTION", required=True)
    for action, extra in (("list", ()), ("get", ("name",)), ("set", ("name", "value")),
                          ("dump", ())):
        p = psub.add_parser(action, parents=[common], help=f"`ros2 param {action}`")
        p.add_argument("node_name", help="e.g. /boat_dynamics")
        for name in extra:
            p.add_argument(name)
        p.add_argument("--timeout", type=_positive_seconds, default=5.0, metavar="S",
                       help="seconds to wait for the node's parameter services and for each "
                            "answer (default 5)")


def _add_run(verbs) -> None:
    """``run``, and the internal ``_node`` of its ``--processes`` children."""
    run = verbs.add_parser("run", help="start the ocean and dynamics nodes for a scenario",
                           description="Start the ocean node and the dynamics node for every "
                                       "boat of SCENARIO in one process.")
    run.add_argument("scenario", nargs="?", metavar="SCENARIO",
                     help="scenario YAML file (default: scenarios/default.yaml)")
    run.add_argument("--fast", action="store_true",
                     help="run as fast as the machine allows (not paced to the wall clock)")
    run.add_argument("--duration", type=_positive_seconds, metavar="S",
                     help="stop after S seconds of simulated time")
    run.add_argument("--record", metavar="DIR",
                     help="write every topic to a rosbag2 (MCAP) bag in the new directory DIR")
    run.add_argument("--exclude-topics", nargs="+", default=[], metavar="TOPIC",
                     help="with --record: topics not to record (as `ros2 bag record "
                          "--exclude-topics`; e.g. /rosout, whose wall-clock stamps differ "
                          "between two otherwise identical runs)")
    run.add_argument("--lockstep", action="store_true",
                     help="with --fast: advance only as far as `boatsim replay` grants, so a "
                          "replay gives the same result on any machine")
    spread = run.add_mutually_exclusive_group()
    spread.add_argument("--processes", action="store_true",
                        help="run the ocean and each boat's dynamics in processes of their own")
    spread.add_argument("--shards", type=_count, metavar="N",
                        help="spread the boats over N dynamics processes, each stepping its "
                             "share as one fleet, and the ocean in a process of its own")
    run.add_argument("--only", nargs="+", metavar="ROLE",
                     help="start one process of a sharded run alone (on this or another "
                          "machine, same ROS_DOMAIN_ID): `ocean` (with --shards N: it owns "
                          "the clock) or `shard K/N`; with --fast")
    # Internal (the --processes children). A sub-parser added without help= stays out of the
    # verb list; help=argparse.SUPPRESS would print "_node ==SUPPRESS==" there.
    node = verbs.add_parser("_node")
    node.add_argument("role", choices=("ocean", "shard"))
    node.add_argument("scenario")
    node.add_argument("--shard", type=_shard)  # a shard's K/N
    node.add_argument("--shards", type=int, default=0)  # the ocean: the clock of N shards
    node.add_argument("--fast", action="store_true")
    node.add_argument("--lockstep", action="store_true")
    node.add_argument("--record")  # fast: this process's part of the bag
    node.add_argument("--exclude-topics", nargs="+", default=[])
    node.add_argument("--epoch", type=float)  # joining a run (a restarted ocean)
    node.add_argument("--ready-fd", type=int)  # the start-up handshake (see runner.RunOptions)
    node.add_argument("--await-recorder", action="store_true")
    node.add_argument("--duration", type=_positive_seconds)
    node.add_argument("--quiet", action="store_true")
    node.add_argument("--checkpoint")  # a shard: its snapshot, saved every simulated second
    node.add_argument("--resume")  # a restarted shard: continue from this snapshot
    surface = verbs.add_parser("_surface")  # `run`'s surface server (ocean_sim.ros)
    surface.add_argument("--time-file", required=True)


def _add_query(verbs) -> None:
    """``query``: the ocean's surface at points."""
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


def _add_bag_verbs(verbs) -> None:
    """``record``, ``compare``, ``plot`` and ``replay``: the verbs on bags."""
    record = verbs.add_parser("record", help="record topics to a rosbag2 (MCAP) bag",
                              description="Record TOPICs (default: every topic, new ones as "
                                          "they appear) until Ctrl-C.")
    record.add_argument("topics", nargs="*", metavar="TOPIC")
    record.add_argument("-o", "--output", required=True, metavar="DIR",
                        help="new directory for the bag")
    record.add_argument("--exclude-topics", nargs="+", default=[], metavar="TOPIC",
                        help="topics not to record")
    compare = verbs.add_parser(
        "compare", help="compare two bags topic by topic within tolerances",
        description="Align two bags by message stamp and report per topic every field that "
                    "moved, with its largest difference, the farthest outside its tolerance "
                    "first. Numeric arrays are compared element by element (a PointCloud2 by "
                    "its points' fields), texts as equal or different. Exit 0 within "
                    "tolerance, 1 outside, 2 unreadable.")
    compare.add_argument("a", metavar="A")
    compare.add_argument("b", metavar="B")
    compare.add_argument("--topics", nargs="+", metavar="TOPIC")
    compare.add_argument("--tol", action="append", default=[], metavar="FIELD=VALUE",
                         help="absolute tolerance for fields matching FIELD (fnmatch, e.g. "
                              "'*.position.*=0.01' or '/odom:twist.*=1e-3'); default 1e-9")
    compare.add_argument("--max-fields", type=_whole_number, default=20, metavar="N",
                         help="fields shown per topic, the farthest outside first (0: every "
                              "one; default 20)")
    reindex = verbs.add_parser(
        "reindex", help="make a bag whose recording was killed readable again",
        description="Rebuild the MCAP summary and metadata.yaml of BAG (as `ros2 bag "
                    "reindex`): every message of every intact chunk is kept, those after "
                    "damage in the middle included; a killed recording loses at most its "
                    "last second. The original file is kept unchanged as NAME.mcap.orig; a "
                    "whole bag is left alone; a bag still being recorded is refused. Exit "
                    "status 0: readable, nothing lost but a killed recording's tail; 1: "
                    "damage in the middle lost messages; 2: not a bag, or being recorded.")
    reindex.add_argument("bag", metavar="BAG")
    plot = verbs.add_parser(
        "plot", help="plot a recorded run: a PNG per boat",
        description="Per boat: trajectory with heading marks, commands, speed and yaw rate, "
                    "heading, heave, roll and pitch, and the wrench sources' surge force and "
                    "yaw moment. One boat: FILE.png (default BAG.png); several: FILE_<boat>.png.")
    plot.add_argument("bag", metavar="BAG")
    plot.add_argument("-o", "--output", metavar="FILE.png")
    plot.add_argument("--scenario", metavar="SCENARIO",
                      help="the run's scenario: its boats' scripted commands (which are not "
                           "on any topic) are drawn with the commands")
    replay = verbs.add_parser(
        "replay", help="republish a bag's command topics with their recorded timing",
        description="Republish the command topics of BAG (default: every */cmd_thrust and "
                    "*/cmd_rudder) at their recorded simulation times. Against `boatsim run "
                    "--fast --lockstep` the simulation never runs ahead of the commands.")
    replay.add_argument("bag", metavar="BAG")
    replay.add_argument("--topics", nargs="+", metavar="TOPIC")
    replay.add_argument("--rate", type=_speed_factor, default=1.0, metavar="R",
                        help="speed factor against a real-time simulation (default 1)")
    replay.add_argument("--timeout", type=_positive_seconds, default=30.0, metavar="S",
                        help="seconds to wait for the simulation (default 30)")


def _add_view(verbs) -> None:
    """``view``: the boats on the sea in 3-D in a browser (Rerun), live or from a bag."""
    from boat_dynamics.tools.scene import DEFAULT_SOURCES
    from boat_msgs_py.names import WRENCH_SOURCES

    view = verbs.add_parser(
        "view", help="the boats on the sea in 3-D in a browser (live, or a bag)",
        description="Serve a 3-D view of the running simulation (or of BAG) on this machine: "
                    "the hulls at their poses, the sea around them, their paths and the "
                    "forces on them, in Rerun's web viewer (the `view` extra). Open the URL "
                    "it prints. Hull shapes come from --scenario (default: the default "
                    "scenario); other boats are drawn as 4 x 2 x 1 m boxes.")
    view.add_argument("bag", nargs="?", metavar="BAG", help="a recorded run (default: live)")
    view.add_argument("--scenario", metavar="SCENARIO", help="the hulls' shapes")
    view.add_argument("--save", metavar="FILE.rrd",
                      help="write a Rerun recording instead of serving (`rerun FILE.rrd`)")
    view.add_argument("--web-port", type=_port, default=9090, metavar="N",
                      help="HTTP port of the web viewer (default 9090)")
    view.add_argument("--grpc-port", type=_port, default=9876, metavar="N",
                      help="port of the Rerun server the page connects to (default 9876)")
    view.add_argument("--bind", default="127.0.0.1", metavar="ADDRESS",
                      help="address the page and the server listen on (default 127.0.0.1: "
                           "this machine only; 0.0.0.0: every interface)")
    view.add_argument("--wrenches", nargs="*", choices=WRENCH_SOURCES,
                      default=list(DEFAULT_SOURCES), metavar="SOURCE",
                      help="wrench sources drawn as arrows over the centre of mass, a hull "
                           "length at full thrust (default: "
                           f"{' '.join(DEFAULT_SOURCES)}; none: no arrows; any of "
                           f"{', '.join(WRENCH_SOURCES)})")
    view.add_argument("--sea-size", type=_positive, default=60.0, metavar="M",
                      help="side of the sea drawn, m (widened to the fleet; default 60)")
    view.add_argument("--sea-resolution", type=_positive, default=1.0, metavar="M",
                      help="grid step of the sea, m (default 1)")
    view.add_argument("--duration", type=_positive_seconds, metavar="S",
                      help="live: stop drawing after S s of simulation time")


def _view(args: argparse.Namespace) -> int:
    import threading

    from boat_dynamics.tools.bags import BagError
    from boat_dynamics.tools.view import ViewError, ViewOptions, view_bag, view_live

    scenario = _read_scenario(args.scenario)
    if args.save:
        Path(args.save).parent.mkdir(parents=True, exist_ok=True)
    options = ViewOptions(scenario=scenario, save=args.save, web_port=args.web_port,
                          grpc_port=args.grpc_port, bind=args.bind,
                          sources=tuple(args.wrenches),
                          sea_size=args.sea_size, sea_resolution=args.sea_resolution,
                          duration=args.duration)
    stop = threading.Event()
    restore_signals = stop_on_signals(stop)
    try:
        if args.bag:
            return view_bag(args.bag, options, stop=stop)
        return view_live(options, stop=stop)
    except (BagError, ViewError) as exc:
        raise CommandLineError(str(exc)) from exc
    finally:
        restore_signals()


def _add_rao(verbs) -> None:
    """``rao``: a boat's RAOs in regular waves, beside potential flow's."""
    from boat_dynamics.tools.rao import DEFAULT_DIRECTIONS_DEG, DEFAULT_WAVELENGTHS

    rao = verbs.add_parser(
        "rao", help="a boat's heave, roll and pitch RAOs in regular waves",
        description="Run one boat of SCENARIO alone in small regular waves of each "
                    "wavelength and direction, print its heave (m/m), roll and pitch (deg/m) "
                    "amplitudes per metre of wave, beside linear potential flow's when the "
                    "boat has a coefficient file, and draw them to a PNG.")
    rao.add_argument("scenario", nargs="?", metavar="SCENARIO",
                     help="scenario file (default: the default scenario)")
    rao.add_argument("--boat", metavar="NAME", help="the boat (default: the first)")
    rao.add_argument("--wavelengths", nargs="+", type=_finite, metavar="L",
                     default=list(DEFAULT_WAVELENGTHS),
                     help="wavelengths in boat lengths (default: %(default)s)")
    rao.add_argument("--directions-deg", nargs="+", type=_finite, metavar="DEG",
                     default=list(DEFAULT_DIRECTIONS_DEG),
                     help="directions the waves travel toward, relative to the bow: 180 head "
                          "seas, 90 beam seas from starboard, 0 following (default: "
                          "%(default)s)")
    rao.add_argument("--amplitude", type=_finite, metavar="M",
                     help="wave amplitude, m (default: 0.5 %% of the boat length, at most "
                          "k a = 0.05)")
    rao.add_argument("--speed", type=_finite, metavar="M/S", default=0.0,
                     help="towed ahead at this speed on a carriage, heave, roll and pitch free "
                          "(negative: astern); the table adds the encounter frequency and "
                          "the plot draws against it (default: 0, held by a soft mooring)")
    rao.add_argument("-o", "--output", metavar="FILE.png",
                     help="the plot (default: SCENARIO-NAME_rao.png here)")


def _rao(args: argparse.Namespace) -> int:
    from boat_dynamics.physics.scenario import ScenarioError, default_scenario_path, load_scenario
    from boat_dynamics.tools.rao import (
        RaoError,
        format_table,
        plot_raos,
        rao_points,
        theory_curve,
    )

    path = Path(args.scenario or default_scenario_path())
    try:
        scenario = load_scenario(path)
        points = rao_points(scenario, args.boat, args.wavelengths, args.directions_deg,
                            args.amplitude, args.speed)
    except (ScenarioError, RaoError) as exc:
        raise CommandLineError(str(exc)) from exc
    boat = next(b for b in scenario.boats if args.boat in (None, b.name))
    length = boat.params.hull.length
    sea = scenario.sea
    towed = (f"towed at {args.speed:g} m/s (Froude number "
             f"{args.speed / math.sqrt(sea.gravity * length):.3g}); ") if args.speed else ""
    print(f"boatsim rao: {path}, boat {boat.name or '(root namespace)'}, length {length:g} m; "
          f"{towed}(pf) = linear potential flow" + ("" if boat.params.hydro is not None else
                                                    " (none: no hydrodynamics.coefficients)"))
    print(format_table(points, length))
    out = plot_raos(points, length, args.output or f"{path.stem}_rao.png",
                    f"{path.name}: boat {boat.name or '(root)'}, RAOs of the centre of mass",
                    theory_curve(boat.params, sea.gravity, sea.depth, args.speed),
                    sea.gravity, sea.depth)
    print(f"boatsim: wrote {out}")
    return 0


def _add_hydro(verbs) -> None:
    """``hydro``: a scenario's potential-flow coefficient files."""
    hydro = verbs.add_parser(
        "hydro", help="potential-flow coefficient files of the hulls",
        description="For each boat of SCENARIO, find its hull's coefficient file (keyed by "
                    "mesh, mass properties and water) where `coefficients: auto` looks, or "
                    "solve it with Capytaine (pip install 'boatsim[bem]') into DIR. Exit 2 "
                    "on a bad scenario or option, or when a solve needs Capytaine.")
    hydro.add_argument("scenario", nargs="?", metavar="SCENARIO",
                       help="scenario file (default: the default scenario)")
    hydro.add_argument("--boat", nargs="+", metavar="NAME", help="only these boats")
    hydro.add_argument("-o", "--output", metavar="DIR",
                       help="where new files go (default: hydro/ beside the scenario)")
    hydro.add_argument("--panel-size", type=_finite, metavar="M",
                       help="largest panel edge, m (default: L/40, at most the larger of B/16 "
                            "and (T + B/2)/8, and fine enough for --shortest-wavelength)")
    hydro.add_argument("--shortest-wavelength", type=_finite, metavar="L",
                       help="the shortest wave, in boat lengths, the default panels resolve "
                            "(panel edge at most a wavelength / 5.7, Capytaine's criterion; "
                            "default: the hull alone sets them)")
    hydro.add_argument("--dry-run", action="store_true",
                       help="print each solve's panels, problems and estimated CPU time, and "
                            "solve nothing (Capytaine not needed)")
    hydro.add_argument("--force", action="store_true",
                       help="solve again even if a file of the hull exists")


def _hydro(args: argparse.Namespace) -> int:
    from boat_dynamics.physics.scenario import ScenarioError, default_scenario_path, load_scenario
    from boat_dynamics.tools.hydro import HydroError, coefficient_files, file_warnings

    path = Path(args.scenario or default_scenario_path())
    try:
        scenario = load_scenario(path)
        files = coefficient_files(scenario, path.resolve().parent, args.boat,
                                  Path(args.output) if args.output else None, args.force,
                                  args.panel_size, report=lambda line: print(line, flush=True),
                                  shortest_wavelength=args.shortest_wavelength,
                                  dry_run=args.dry_run)
    except (ScenarioError, HydroError, ValueError) as exc:
        raise CommandLineError(str(exc)) from exc
    for f in files:
        how = ("would be made" if f.seconds is None and f.plan is not None
               else "found" if f.seconds is None else f"made in {f.seconds:.0f} s")
        print(f"boat {f.boat or '(root)'}: {f.path} ({how}; key {f.key})")
    for path in dict.fromkeys(f.path for f in files if f.path.exists()):
        for line in file_warnings(path):
            print(f"boatsim hydro: warning: {line}", file=sys.stderr, flush=True)
    if not args.dry_run:
        print("use them with `hydrodynamics: {coefficients: auto}` (or the path) in the boat")
    return 0


def _introspect(args: argparse.Namespace) -> int:
    """``topic``, ``node`` and ``param``: print as ``ros2`` would; 1 when not found."""
    from boat_dynamics.tools import introspection as ros
    from boat_msgs_py.fields import FieldError

    out, verb = sys.stdout, f"{args.verb} {args.action}"
    try:
        with ros.session(args.spin_time) as s:
            if args.verb == "node":
                lines = ros.node_list(s)
            elif args.verb == "param":
                lines = _param(ros, s, args)
            elif args.action in ("list", "info"):
                lines = (ros.topic_list(s, args.show_types, args.count_topics)
                         if args.action == "list" else
                         ros.topic_info(s, args.topic_name, args.verbose))
            elif args.action == "echo":
                printed = ros.topic_echo(s, args.topic_name, out, args.once, args.full_length,
                                         timeout=args.timeout)
                if args.once and not printed:
                    raise CommandLineError(f"no message on {args.topic_name} within "
                                           f"{args.timeout:g} s", 1, f"boatsim {verb}")
                return 0
            elif args.action == "hz":
                ros.topic_hz(s, args.topic_name, out, args.window, timeout=args.timeout)
                return 0
            else:
                times = 1 if args.once else args.times
                wait = args.wait_matching_subscriptions
                ros.topic_pub(s, args.topic_name, args.message_type, args.values, out,
                              args.rate, times, (1 if times else 0) if wait is None else wait)
                return 0
    except (ros.IntrospectionError, FieldError) as exc:
        raise CommandLineError(str(exc), 1, f"boatsim {verb}") from exc
    print("\n".join(lines))
    return 0


def _param(ros, s, args) -> list[str]:
    wait = args.timeout
    if args.action == "list":
        return [f"{args.node_name}:", *ros.param_list(s, args.node_name, wait)]
    if args.action == "get":
        return [ros.param_get(s, args.node_name, args.name, wait)]
    if args.action == "set":
        return [ros.param_set(s, args.node_name, args.name, args.value, wait)]
    return [ros.param_dump(s, args.node_name, wait).rstrip("\n")]


def _compare(args: argparse.Namespace) -> int:
    from boat_dynamics.tools.bags import compare_bags

    tolerances = {}
    for item in args.tol:
        pattern, sep, value = item.rpartition("=")
        try:
            tol = float(value)
        except ValueError:
            tol = math.nan
        if not sep or not pattern or not math.isfinite(tol) or tol < 0:
            raise CommandLineError(f"--tol {item!r}: expected FIELD=VALUE with a number >= 0")
        tolerances[pattern] = tol
    result = compare_bags(args.a, args.b, args.topics, tolerances)  # a BagError: main's
    print(result.report(args.max_fields))
    return 0 if result.ok else 1


def _finite(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number")
    return value


def _query(args: argparse.Namespace) -> int:
    from ocean_sim.ros.client import OceanUnavailableError, query_surface

    if len(args.coords) % 2:
        raise CommandLineError(f"coordinates come in X Y pairs; got {len(args.coords)} numbers")
    points = list(zip(args.coords[::2], args.coords[1::2], strict=True))
    try:
        result = query_surface(points, args.sim_time, args.timeout)
    except OceanUnavailableError as exc:
        raise CommandLineError(f"{exc}; is `boatsim run` running on this ROS_DOMAIN_ID?",
                               1) from exc
    r = result.response
    if not r.success:
        raise CommandLineError(f"the ocean refused: {r.message}")
    when = "now" if args.sim_time is None else f"t = {args.sim_time:g} s"
    print(f"# surface at {when}: x y [m]  height [m]  normal (x y z)  velocity [m/s] (x y z)")
    for (x, y), h, n, v in zip(points, r.heights, r.normals, r.velocities, strict=True):
        print(f"{x:10.3f} {y:10.3f}  {h:9.4f}  ({n.x:8.5f} {n.y:8.5f} {n.z:8.5f})  "
              f"({v.x:7.4f} {v.y:7.4f} {v.z:7.4f})")
    return 0


def _read_scenario(path: str | None):
    """The scenario at ``path`` (None: the default one).

    Raises:
        CommandLineError: it is invalid (exit 2), saying which file.
    """
    from boat_dynamics.physics.scenario import ScenarioError, default_scenario_path, load_scenario

    path = path or default_scenario_path()
    try:
        return load_scenario(path)
    except ScenarioError as exc:
        raise CommandLineError(f"invalid scenario {path}: {exc}") from exc


def _run(args: argparse.Namespace) -> int:
    # Imported here so that `boatsim --help` answers without starting ROS.
    from boat_dynamics.physics.core.pipeline import InitError
    from boat_dynamics.physics.scenario import default_scenario_path
    from boat_dynamics.ros.runner import RunOptions, run
    from boat_msgs_py.process import sweep_temporaries

    path = args.scenario or default_scenario_path()
    scenario = _read_scenario(path)
    if args.verb == "_node":
        return _run_node(args, scenario, path)
    sweep_temporaries()  # what runs killed before could not remove
    for note in scenario.notes:  # the parent says it once
        print(f"boatsim: warning: {path}: {note}", file=sys.stderr)
    if args.lockstep and not args.fast:
        raise CommandLineError("--lockstep needs --fast (a real-time run follows the wall "
                               "clock)")
    fast = args.fast or not scenario.simulation.realtime
    if args.only:
        return _run_only(args, scenario, path, fast)
    if args.processes or args.shards:
        return _run_processes(args, scenario, path, fast)
    try:
        return run(scenario, RunOptions(fast=args.fast, duration=args.duration,
                                        record=args.record, lockstep=args.lockstep,
                                        exclude_topics=tuple(args.exclude_topics)))
    except InitError as exc:  # (a RecordError: main's)
        raise _refused_boat(path, exc, exc.boat) from exc


def _run_node(args: argparse.Namespace, scenario, path) -> int:
    """``_node``: one process of ``run --processes`` / ``--shards``, started by the parent."""
    from boat_dynamics.physics.core.pipeline import InitError
    from boat_dynamics.physics.core.snapshot import SnapshotError
    from boat_dynamics.ros.barrier import shard_slice
    from boat_dynamics.ros.runner import ProcessRole, RunOptions, run

    if (args.epoch is None) == (args.ready_fd is None):
        raise CommandLineError("exactly one of --epoch and --ready-fd")
    options = RunOptions(duration=args.duration, fast=args.fast, lockstep=args.lockstep,
                         record=args.record, exclude_topics=tuple(args.exclude_topics),
                         process=ProcessRole(role=args.role, shard=args.shard,
                                             shards=args.shards, epoch=args.epoch,
                                             ready_fd=args.ready_fd, supervised=True,
                                             await_recorder=args.await_recorder,
                                             checkpoint=args.checkpoint, resume=args.resume))
    try:
        return run(scenario, options, status=open(os.devnull, "w") if args.quiet
                   else sys.stderr)
    except SnapshotError as exc:
        raise CommandLineError(f"cannot resume: {exc}") from exc
    except InitError as exc:
        first = 0 if args.shard is None else shard_slice(*args.shard,
                                                         len(scenario.boats)).start
        raise _refused_boat(path, exc, first + exc.boat) from exc


def _run_processes(args: argparse.Namespace, scenario, path, fast: bool) -> int:
    """``run --processes`` / ``--shards N``: the ocean and the shards, each a process."""
    from boat_dynamics.physics.core.pipeline import InitError, start
    from boat_dynamics.ros.processes import run_processes
    from boat_dynamics.ros.runner import ProcessRole, RunOptions

    count = len(scenario.boats) if args.processes else args.shards
    if (problem := _too_many_shards(count, len(scenario.boats))) is not None:
        raise CommandLineError(f"--shards {count}: {problem}")
    try:  # refused here, before any process starts (each initializes its own boats)
        start(scenario.boats, scenario.sea)
    except InitError as exc:
        raise _refused_boat(path, exc, exc.boat) from exc
    return run_processes(scenario, str(path), RunOptions(  # a RecordError: main's
        duration=args.duration, record=args.record, fast=fast, lockstep=args.lockstep,
        exclude_topics=tuple(args.exclude_topics), process=ProcessRole(shards=count)))


def _run_only(args: argparse.Namespace, scenario, path, fast: bool) -> int:
    """``run --only ocean | shard K/N``: one process of a sharded run, started alone."""
    from boat_dynamics.physics.core.pipeline import InitError
    from boat_dynamics.ros.barrier import shard_slice
    from boat_dynamics.ros.runner import ProcessRole, RunOptions, run

    def refuse(message: str) -> CommandLineError:
        return CommandLineError(f"--only {' '.join(args.only)}: {message}")

    if not fast:
        raise refuse("the processes of a run started apart share its clock through the "
                      "step barrier: add --fast (and --lockstep to follow a replay)")
    if args.processes:
        raise refuse("--processes starts every process itself; use --shards N")
    role, rest = args.only[0], args.only[1:]
    if role == "ocean" and not rest:
        if not args.shards:
            raise refuse("add --shards N: the ocean owns the clock of N shards")
        shard, shards = None, args.shards
    elif role == "shard" and len(rest) == 1:
        try:
            shard = _shard(rest[0])
        except argparse.ArgumentTypeError as exc:
            raise refuse(str(exc)) from exc
        shards = 0
        if args.shards not in (None, shard[1]):
            raise refuse(f"--shards {args.shards} and shard {rest[0]} disagree")
    else:
        raise refuse("expected `ocean` or `shard K/N`")
    if (problem := _too_many_shards(shard[1] if shard else shards,
                                    len(scenario.boats))) is not None:
        raise refuse(problem)
    options = RunOptions(fast=True, lockstep=args.lockstep, duration=args.duration,
                         record=args.record, exclude_topics=tuple(args.exclude_topics),
                         process=ProcessRole(role=role, shard=shard, shards=shards,
                                             standalone=True))
    try:
        return run(scenario, options)  # a RecordError: main's
    except InitError as exc:
        first = shard_slice(*shard, len(scenario.boats)).start if shard else 0
        raise _refused_boat(path, exc, first + exc.boat) from exc


def _reindex(bag: str) -> int:
    """``boatsim reindex BAG``: exit status 0, 1 or 2 (see the verb's description).

    0 when whole (a killed recording's tail dropped), 1 when damage in the middle cost
    messages, 2 when BAG is not a bag or is still being recorded.
    """
    from boat_dynamics.tools.bagfile import ReindexError, reindex

    try:
        report = reindex(bag)
    except (ReindexError, OSError) as exc:
        raise CommandLineError(str(exc)) from exc
    topics = "  ".join(f"{t} {n}" for t, n in sorted(report.counts.items()))
    total = sum(report.counts.values())
    if report.original is None:
        print(f"boatsim: {bag} is whole: {total} messages on {len(report.counts)} topics; "
              f"nothing rewritten\n  {topics}")
        return 0
    print(f"boatsim: reindexed {bag}: {total} messages on {len(report.counts)} topics, up to "
          f"bag time {report.end_ns / 1e9:.3f} s; the original is kept unchanged as "
          f"{report.original}\n  {topics}")
    if report.dropped_bytes:
        print(f"  truncated: {report.dropped_bytes} bytes at the end held no whole record (the "
              "chunk being written when the recording stopped): dropped")
    if report.whole:
        return 0
    spans = ", ".join(f"{a}-{b}" for a, b in report.damaged)
    lost = ("an unknown number of messages" if report.lost is None
            else f"{report.lost} of the {report.lost + total} messages its summary lists")
    orphans = (f" ({report.orphans} read but dropped: their channel's definition was lost)"
               if report.orphans else "")
    print(f"boatsim reindex: warning: damaged in the middle (bytes {spans or 'none'}): "
          f"{lost} lost{orphans}; every intact chunk after the damage is kept",
          file=sys.stderr)
    return 1


def _refused_boat(path, exc, index: int) -> CommandLineError:
    """A boat ``pipeline.init`` refused (exit 2), named as the scenario names it."""
    return CommandLineError(f"invalid scenario {path}: boats[{index}].{exc.key}: "
                            f"{exc.value!r} is not allowed: {exc.allowed}")


def _record(args: argparse.Namespace) -> int:
    from boat_dynamics.tools.recording import record

    return record(args.topics, args.output, exclude=set(args.exclude_topics))


def _surface(args: argparse.Namespace) -> int:
    from ocean_sim.ros.surface_server import serve

    return serve(args.time_file)


def _plot(args: argparse.Namespace) -> int:
    from boat_dynamics.tools.plot import plot_bag

    for path in plot_bag(args.bag, args.output, args.scenario):
        print(f"boatsim: wrote {path}")
    return 0


def _replay(args: argparse.Namespace) -> int:
    from boat_dynamics.tools.replay import replay

    return replay(args.bag, args.topics, args.rate, args.timeout)


def _teleop(args: argparse.Namespace) -> int:
    from boat_dynamics.tools.teleop import teleop

    return teleop(args.ns)


#: Each verb's handler: (parsed arguments) -> exit status.
_HANDLERS = {
    "run": _run, "_node": _run, "_surface": _surface, "query": _query, "compare": _compare,
    "topic": _introspect, "node": _introspect, "param": _introspect, "rao": _rao,
    "hydro": _hydro, "view": _view, "record": _record, "reindex": lambda a: _reindex(a.bag),
    "plot": _plot, "replay": _replay, "teleop": _teleop,
}


class CommandLineError(Exception):
    """A user's error a verb reports: ``WHO: error: MESSAGE`` on stderr, exit ``status``.

    Args:
        message: what was wrong and what is allowed.
        status: the exit status (2: bad input; 1: a peer that is not there, a refused
            request, as ``ros2`` exits).
        who: the prefix, or None: the verb's (``boatsim VERB``; ``boatsim`` for ``run``).
    """

    def __init__(self, message: str, status: int = 2, who: str | None = None) -> None:
        super().__init__(message)
        self.status, self.who = status, who


def _who(verb: str) -> str:
    """The prefix of a verb's lines: ``boatsim`` for ``run`` (its log's), else ``boatsim VERB``."""
    return "boatsim" if verb == "run" else f"boatsim {verb}"


def _user_errors() -> tuple[type[Exception], ...]:
    """What a handler raises for a user's bad input: a value, a bag, a path, a recording."""
    from boat_dynamics.tools.bags import BagError
    from boat_dynamics.tools.plot import PlotError
    from boat_dynamics.tools.recording import RecordError
    from boat_dynamics.tools.replay import ReplayError
    from ocean_sim.physics.errors import InvalidValueError

    return (InvalidValueError, BagError, PlotError, RecordError, ReplayError)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``boatsim``; returns the exit status.

    The one place that turns a user's error into ``boatsim VERB: error: ...`` and its exit
    status: a :class:`CommandLineError`'s, 2 for the errors of :func:`_user_errors` (a bad
    option: argparse's own message and 2); Ctrl-C exits 0. A bug shows its traceback.
    """
    try:
        args = _parser().parse_args(argv)
        return args.handler(args)
    except KeyboardInterrupt:
        return 0
    except CommandLineError as exc:
        print(f"{exc.who or _who(args.verb)}: error: {exc}", file=sys.stderr)
        return exc.status
    except Exception as exc:
        if not isinstance(exc, _user_errors()):
            raise
        print(f"{_who(args.verb)}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
