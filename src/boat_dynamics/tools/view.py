"""`boatsim view [BAG]`: the boats on the sea in 3-D, in a browser, live or from a bag.

Drawn by Rerun (https://rerun.io, the ``view`` extra: ``pip install 'boatsim[view]'``): this
process logs the scene (:class:`boat_dynamics.tools.scene.Scene`) to a Rerun server, the
``rerun --serve-web`` of the rerun-sdk wheel started as a child, which also serves Rerun's web
viewer from this machine: nothing is fetched from the internet and no account is needed
(Foxglove's client is a hosted web app; its open-source fork would have to be built from npm).
Both listen on ``--bind`` only, 127.0.0.1 by default (the SDK's in-process servers of Rerun
0.41 listen on every interface and take no address). ``--save FILE.rrd`` writes the recording
instead (open it with ``rerun FILE.rrd``, also from the extra).

Live (no BAG): a node subscribes to ``/ocean/wave_field``, to every ``*/odom`` on the graph
(looked for once a second, so boats of any running simulation appear) and to the wrench
topics drawn; times are message stamps minus the wave field's stamp (simulation time, in real
time and ``--fast`` alike). A bag is read whole and logged on the same timeline. The hulls'
shapes come from ``--scenario`` (default: the default scenario); a boat it does not have is
drawn as the default box.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO
from urllib.parse import quote

from boat_dynamics.physics.scenario import Scenario
from boat_dynamics.tools.scene import DEFAULT_SOURCES, POSE_PERIOD, Scene, hull_shape
from boat_msgs_py import names

__all__ = ["ViewError", "ViewOptions", "view_bag", "view_live"]

#: How often the live view looks for new boats' odometry on the graph, s (wall).
_DISCOVERY_PERIOD = 1.0
#: How often the recording sends what was logged, s (wall): one chunk per entity per flush.
#: Rerun's web viewer ingests for 10 ms per frame, and a browser drawing in software (no GPU:
#: SwiftShader) makes about one frame a second; at Rerun's default (0.2 s: some 35 chunks per
#: second of a live run) it fell behind the simulation by 0.7 s every second, and after ten
#: minutes stopped drawing altogether while the server and this process held the backlog.
_FLUSH_TICK = 2.0
#: Live: the drawing periods of the sea, of a boat's pose and of a force arrow, s of
#: simulation time (a bag's are finer: the whole of it is read at once, nothing lags).
_LIVE_SEA_PERIOD = 1.0
_LIVE_POSE_PERIOD = 0.1
_LIVE_WRENCH_PERIOD = 0.5


class ViewError(RuntimeError):
    """The view cannot be shown (no Rerun, a port in use, nothing to show)."""


@dataclass(frozen=True)
class ViewOptions:
    """How to show the view.

    Attributes:
        scenario: the hulls' shapes (by boat name), or None: every boat the default box.
        save: write the recording to this .rrd file instead of serving it.
        web_port: the web viewer's HTTP port.
        grpc_port: the Rerun server's port (the page connects to it).
        bind: the address both listen on (127.0.0.1: this machine only; 0.0.0.0: every
            interface).
        sources: the wrench sources drawn as arrows.
        sea_size: m, side of the sea drawn (at least).
        sea_resolution: m between the sea's grid points.
        sea_period: s of simulation time between two drawings of the sea.
        duration: live: stop after this many s of simulation time (None: at Ctrl-C).
    """

    scenario: Scenario | None = None
    save: str | None = None
    web_port: int = 9090
    grpc_port: int = 9876
    bind: str = "127.0.0.1"
    sources: tuple[str, ...] = DEFAULT_SOURCES
    sea_size: float = 60.0
    sea_resolution: float = 1.0
    sea_period: float = 0.5
    duration: float | None = None


def _rerun():
    try:
        import rerun
    except ImportError as exc:
        raise ViewError("boatsim view needs the `view` extra (Rerun): "
                        "pip install 'boatsim[view]' (make test installs it)") from exc
    return rerun


#: How long the Rerun server may take to listen, s (wall).
_SERVER_START_TIMEOUT = 30.0


def _start_server(options: ViewOptions):
    """The ``rerun --serve-web`` child, listening on ``options.bind``; dies with us."""
    import socket
    import subprocess
    import tempfile

    from boat_msgs_py.process import die_with_parent

    command = [sys.executable, "-m", "rerun", "--serve-web", "--bind", options.bind,
               "--port", str(options.grpc_port), "--web-viewer-port", str(options.web_port),
               "--server-memory-limit", "1GiB"]
    log = tempfile.TemporaryFile()  # its log: read if it fails (a pipe could fill and block)
    # its own session: Ctrl-C in the terminal reaches only this process, which sends what it
    # logged and then stops the server (the same SIGINT ended both at once, and the SDK's
    # last flush printed "transport error" and "gRPC connection severed")
    child = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                             stderr=log, preexec_fn=die_with_parent, start_new_session=True)
    host = "127.0.0.1" if options.bind in ("0.0.0.0", "::") else options.bind
    deadline = time.monotonic() + _SERVER_START_TIMEOUT
    for port in (options.grpc_port, options.web_port):
        while True:
            if child.poll() is not None:
                log.seek(0)
                words = log.read().decode(errors="replace").split()[-40:]
                raise ViewError(f"the Rerun server ended at start-up (exit {child.returncode}): "
                                + " ".join(words))
            with socket.socket() as probe:
                if probe.connect_ex((host, port)) == 0:
                    break
            if time.monotonic() > deadline:
                child.kill()
                child.wait()
                raise ViewError(f"the Rerun server did not listen on {host}:{port} within "
                                f"{_SERVER_START_TIMEOUT:g} s")
            time.sleep(0.05)
    log.close()  # the child keeps its own descriptor
    return child, host


#: How long the view waits for its last logged data to reach the server when it ends, s.
_FINAL_FLUSH_TIMEOUT = 2.0


def _stop_server(child, recording) -> None:
    """Send what ``recording`` holds, disconnect it, then end the Rerun server child."""
    from boat_msgs_py.process import stop_processes

    if child is None:
        return
    try:
        recording.flush(timeout_sec=_FINAL_FLUSH_TIMEOUT)
        recording.disconnect()
    finally:
        stop_processes([child], timeout=5.0)


def _scene(options: ViewOptions, status: TextIO, live: bool = False
           ) -> tuple[Scene, object, str | None, object]:
    """A scene on a new recording, saved or served: (scene, recording, page URL, server)."""
    rr = _rerun()
    rec = rr.RecordingStream("boatsim", batcher_config=rr.ChunkBatcherConfig(
        flush_tick=_FLUSH_TICK))
    shapes = ({b.name: hull_shape(b.params) for b in options.scenario.boats}
              if options.scenario is not None else {})
    periods = ((_LIVE_SEA_PERIOD, _LIVE_POSE_PERIOD, _LIVE_WRENCH_PERIOD) if live
               else (options.sea_period, POSE_PERIOD, 0.0))
    scene = Scene(rec, shapes, options.sources, options.sea_size, options.sea_resolution,
                  *periods)
    blueprint = scene.blueprint(*_framing(options.scenario))
    if options.save:
        rr.save(options.save, default_blueprint=blueprint, recording=rec)
        return scene, rec, None, None
    for port, what in ((options.grpc_port, "--grpc-port"), (options.web_port, "--web-port")):
        _check_free(options.bind, port, what)  # Rerun only logs a taken port
    server, host = _start_server(options)
    uri = f"rerun+http://{host}:{options.grpc_port}/proxy"
    rr.connect_grpc(uri, default_blueprint=blueprint, recording=rec)
    url = f"http://{host}:{options.web_port}/?url={quote(uri, safe='')}"
    print(f"boatsim view: open {url} in a browser (Ctrl-C ends the view; listening on "
          f"{options.bind} only)", file=status)
    return scene, rec, url, server


def _framing(scenario: Scenario | None) -> tuple[str | None, float]:
    """The camera's boat (a lone boat's, followed) and distance scale (the fleet's extent)."""
    if scenario is None or not scenario.boats:
        return None, 20.0
    if len(scenario.boats) == 1:
        return scenario.boats[0].name, 4.0 * scenario.boats[0].params.hull.length
    starts = [b.initial.position[:2] for b in scenario.boats]
    return None, 1.2 * float(max(max(abs(v) for v in p) for p in starts)) + 10.0


def _check_free(address: str, port: int, option: str) -> None:
    """Raise ViewError when ``port`` is taken (another view, another server)."""
    import socket

    with socket.socket() as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # a closed view's is free
        try:
            probe.bind((address, port))
        except OSError as exc:
            raise ViewError(f"port {port} is in use ({exc.strerror}): another `boatsim view`? "
                            f"Choose another with {option}") from exc


def _pose(msg) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)


def _force(msg) -> tuple[float, float, float]:
    f = msg.wrench.force
    return f.x, f.y, f.z


def _stamp_ns(msg) -> int:
    return msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec


def view_bag(bag: str | Path, options: ViewOptions, status: TextIO | None = None,
             stop: threading.Event | None = None) -> int:
    """Show (or save) a bag's boats on its sea; serves until ``stop`` (Ctrl-C) unless saved.

    Raises:
        BagError: the bag cannot be read.
        ViewError: no Rerun, the ports are taken, or the bag has no odometry.
    """
    status = sys.stderr if status is None else status  # now, not at import
    from boat_dynamics.tools.bags import BagError, odometry_topics, read_bag, read_bag_topics
    from boat_msgs_py.convert import wave_field_from_msg

    topics = read_bag_topics(bag)
    try:
        boats = odometry_topics(bag)
    except BagError as exc:
        raise ViewError(str(exc)) from None
    wrenches = {names.wrench_topic(b, s): (b, s) for b in boats.values()
                for s in options.sources if names.wrench_topic(b, s) in topics}
    wanted = [*boats, *wrenches, *([names.WAVE_FIELD] if names.WAVE_FIELD in topics else []),
              *([names.WORLD_MARKERS] if names.WORLD_MARKERS in topics else [])]
    messages = read_bag(bag, wanted)
    fields = messages.pop(names.WAVE_FIELD, [])
    obstacles = messages.pop(names.WORLD_MARKERS, [])
    try:
        sea = wave_field_from_msg(fields[0][1]) if fields else None
    except ValueError as exc:  # InvalidSeaStateError: what the ocean would refuse
        raise ViewError(f"{bag}: its {names.WAVE_FIELD} is not a sea the ocean accepts "
                        f"({exc})") from None
    events = sorted(((stamp, topic, msg) for topic, msgs in messages.items()
                     for stamp, msg in msgs), key=lambda e: e[:2])  # repeated stamps: in order
    epoch = _stamp_ns(fields[0][1]) if fields else events[0][0]
    scene, rec, url, server = _scene(options, status)
    for _, markers in obstacles[-1:]:  # latched: the last is the world
        scene.markers(markers)
    for stamp, topic, msg in events:
        t = (stamp - epoch) / 1e9
        if topic in boats:
            scene.pose(t, boats[topic], *_pose(msg))
            if sea is not None:
                scene.sea(t, sea)
        else:
            scene.wrench(t, *wrenches[topic], _force(msg))
    scene.finish()
    print(f"boatsim view: {len(events)} messages of {len(boats)} boat(s) from {bag}, "
          f"{events[-1][0] / 1e9 - epoch / 1e9:.1f} s", file=status)
    if url is not None:
        try:
            _serve(stop or threading.Event())
        finally:
            _stop_server(server, rec)
    return 0


def _serve(stop: threading.Event) -> None:
    """Keep the server up until ``stop`` (set by Ctrl-C / SIGTERM)."""
    while not stop.wait(0.2):
        pass


class _Live:
    """The live view's subscriptions: the sea, the obstacles, each boat's odom and wrenches."""

    def __init__(self, node, scene: Scene, sources: tuple[str, ...]) -> None:
        from boat_msgs.msg import WaveField

        from boat_msgs_py.qos import WAVE_FIELD_QOS

        self.node, self.scene, self.sources = node, scene, sources
        self.sea = None
        self.epoch_ns: int | None = None
        self.t = -math.inf  # the latest simulation time seen
        self._boats: set[str] = set()
        self._next_discovery = -math.inf
        self.refused = 0  # wave fields refused
        node.create_subscription(WaveField, names.WAVE_FIELD, self._on_field, WAVE_FIELD_QOS)
        from visualization_msgs.msg import MarkerArray

        from boat_msgs_py.qos import WORLD_QOS

        node.create_subscription(MarkerArray, names.WORLD_MARKERS,
                                 lambda msg: self.scene.markers(msg), WORLD_QOS)

    def _on_field(self, msg) -> None:
        from boat_msgs_py.convert import wave_field_from_msg

        try:
            self.sea, self.epoch_ns = wave_field_from_msg(msg), _stamp_ns(msg)
        except ValueError as exc:  # InvalidSeaStateError: what the ocean would refuse
            if not self.refused:  # logged once; the sea drawn so far stays
                self.node.get_logger().error(f"ignoring an invalid {names.WAVE_FIELD}: {exc}")
            self.refused += 1

    def discover(self, now: float) -> None:
        """Subscribe to the boats whose odometry appeared on the graph since the last look."""
        if now < self._next_discovery:
            return
        self._next_discovery = now + _DISCOVERY_PERIOD
        from geometry_msgs.msg import WrenchStamped
        from nav_msgs.msg import Odometry

        from boat_msgs_py.qos import DIAGNOSTICS_QOS, STATE_QOS

        for topic, types in self.node.get_topic_names_and_types():
            boat = names.boat_of(topic, names.ODOM)
            if boat is None or boat in self._boats or "nav_msgs/msg/Odometry" not in types:
                continue
            self._boats.add(boat)
            self.node.create_subscription(Odometry, topic, lambda m, b=boat: self._on_odom(b, m),
                                          STATE_QOS)
            for source in self.sources:
                self.node.create_subscription(
                    WrenchStamped, names.wrench_topic(boat, source),
                    lambda m, b=boat, s=source: self._on_wrench(b, s, m), DIAGNOSTICS_QOS)
            self.node.get_logger().info(f"showing boat {boat or '(root namespace)'}")

    def _time(self, msg) -> float | None:
        return None if self.epoch_ns is None else (_stamp_ns(msg) - self.epoch_ns) / 1e9

    def _on_odom(self, boat: str, msg) -> None:
        if (t := self._time(msg)) is None:
            return  # no sea state yet: no epoch
        self.scene.pose(t, boat, *_pose(msg))
        self.scene.sea(t, self.sea)
        self.t = max(self.t, t)

    def _on_wrench(self, boat: str, source: str, msg) -> None:
        if (t := self._time(msg)) is not None:
            self.scene.wrench(t, boat, source, _force(msg))


def view_live(options: ViewOptions, status: TextIO | None = None,
              stop: threading.Event | None = None) -> int:
    """Show the running simulation until ``stop`` (Ctrl-C) or ``options.duration``.

    Raises:
        ViewError: no Rerun, or the ports are taken.
    """
    status = sys.stderr if status is None else status  # now, not at import
    import rclpy
    from rclpy.executors import SingleThreadedExecutor

    stop = stop or threading.Event()
    scene, rec, _, server = _scene(options, status, live=True)
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("boatsim_view", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    live = _Live(node, scene, options.sources)
    waiting_since = time.monotonic()
    try:
        while not stop.is_set():
            if options.duration is not None and live.t >= options.duration:
                break
            live.discover(time.monotonic())
            executor.spin_once(timeout_sec=0.05)
            if live.sea is None and time.monotonic() - waiting_since > 5.0:
                print(f"boatsim view: waiting for {names.WAVE_FIELD} (is a simulation "
                      f"running on ROS_DOMAIN_ID {context.get_domain_id()}?)", file=status)
                waiting_since = math.inf  # said once
        scene.finish()
    finally:
        executor.shutdown(timeout_sec=0.1)
        node.destroy_node()
        rclpy.try_shutdown(context=context)
    try:
        if options.save is None and options.duration is not None:
            print("boatsim view: the view's duration is over; still serving it (Ctrl-C ends)",
                  file=status)
            _serve(stop)
    finally:
        _stop_server(server, rec)
    return 0
