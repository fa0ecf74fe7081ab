"""rosbag2 (MCAP) recording through rosbags, without ros2cli.

:class:`BagWriter` writes serialized messages; :class:`TopicRecorder` subscribes generically
(raw serialized messages, no per-type code) to every topic it discovers and writes them.
The simulation's own publishers hand their serialized messages to the same writer directly
(:class:`boat_msgs_py.tap.TappedPublisher`), so nothing it publishes can be dropped by a slow
subscriber.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TextIO

from rclpy.executors import Executor, TimeoutException
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile

from boat_dynamics.tools.bagfile import JazzyWriter
from boat_msgs_py import names
from boat_msgs_py.qos import RECORD_QOS, latched
from boat_msgs_py.tap import Tap
from boat_msgs_py.typestore import TypesNotInstalled, typestore

__all__ = ["BagWriter", "RecordError", "TopicRecorder", "declares_only", "record",
           "spin_pending"]

#: Callbacks a stopping recorder still runs: what DDS had received before the stop.
_DRAIN_LIMIT = 100_000
#: s (wall): a stopping recorder is drained once no callback is ready for this long.
_DRAIN_QUIET = 0.05


class RecordError(RuntimeError):
    """A bag that cannot be written (the directory exists, or is not writable)."""


def _bag_qos(profile: QoSProfile):
    """Rosbags' Qos of an rclpy QoSProfile (enum values are the rmw ones in both)."""
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    def span(d) -> QosTime:
        ns = d.nanoseconds
        return QosTime(ns // 1_000_000_000, ns % 1_000_000_000)

    return Qos(QosHistory(int(profile.history)), int(profile.depth),
               QosReliability(int(profile.reliability)), QosDurability(int(profile.durability)),
               span(profile.deadline), span(profile.lifespan),
               QosLiveliness(int(profile.liveliness)), span(profile.liveliness_lease_duration),
               bool(profile.avoid_ros_namespace_conventions))


class BagWriter:
    """A rosbag2 bag with MCAP storage, written from serialized (CDR) messages.

    Crash-safe: a chunk is written out once it spans half a second of bag time
    (:class:`boat_dynamics.tools.bagfile.JazzyWriter`); call :meth:`flush_due` when no message
    may come for a while. A write that fails (a full disk, a file-size limit, an I/O error)
    stops the recording, not the caller: :attr:`failed` says why, :attr:`dropped` counts the
    messages not written since, and the file keeps every whole chunk before (a killed
    recording's, which ``boatsim reindex`` makes readable).

    Args:
        path: directory to create; must not exist.
        exclude: topics never written (``boatsim run --exclude-topics``).
    """

    def __init__(self, path: str | Path, exclude: set[str] | frozenset[str] = frozenset()
                 ) -> None:
        self.path = Path(path)
        if self.path.exists():
            raise RecordError(f"{self.path} already exists; choose a new directory for the bag")
        try:
            self._store = typestore()
        except TypesNotInstalled as exc:
            raise RecordError(str(exc)) from exc
        self.exclude = frozenset(exclude)
        self._writer = JazzyWriter(self.path)
        try:
            self._writer.open()
        except Exception as exc:  # rosbags raises its own WriterError or OSError
            raise RecordError(f"cannot create bag {self.path}: {exc}") from exc
        self._connections: dict[str, object] = {}
        self.counts: dict[str, int] = {}
        self._closed = False
        #: Why the recording stopped (a failed write), or None while it records.
        self.failed: str | None = None
        #: Messages not written since it stopped.
        self.dropped = 0
        #: Bag time (ns) of the last message handed to the writer before it stopped.
        self.last_ns = 0

    def stopped_line(self) -> str:
        """What to tell the user once the recording has stopped on a failed write."""
        return (f"recording stopped at bag time {self.last_ns / 1e9:.3f} s: {self.failed}; "
                f"{self.dropped} message(s) not written since; {self.path} keeps every whole "
                "chunk before (at most the last second before it is lost): `boatsim reindex "
                f"{self.path}` makes it readable once the disk has room")

    def _guard(self, action: Callable[[], None]) -> bool:
        """Run a writing ``action``; on an OSError stop the recording (module docstring)."""
        try:
            action()
        except OSError as exc:
            self.failed = f"writing {self.path} failed: {exc.strerror or exc}"
            self._closed = True
            self._writer.abandon()
            return False
        return True

    def write(self, topic: str, msgtype: str, data: bytes, stamp_ns: int,
              qos: QoSProfile | None = None) -> None:
        """Append one serialized message of type ``msgtype`` on ``topic`` at ``stamp_ns``.

        ``qos``: the publisher's offered QoS, stored in the bag's metadata with the topic's
        first message (``ros2 bag play`` offers it again).
        """
        if topic in self.exclude:
            return
        if self._closed:
            self.dropped += self.failed is not None
            return
        conn = self._connections.get(topic)
        if conn is None:
            offered = (_bag_qos(qos),) if qos is not None else ()
            conn = self._writer.add_connection(topic, msgtype, typestore=self._store,
                                               offered_qos_profiles=offered)
            self._connections[topic] = conn
            self.counts[topic] = 0
        if self._guard(lambda: self._writer.write(conn, stamp_ns, data)):
            self.counts[topic] += 1
            self.last_ns = stamp_ns
        else:
            self.dropped += 1

    def flush_due(self, now_ns: int) -> None:
        """Write out the pending chunk if it is CHUNK_SPAN_NS (0.5 s) older than ``now_ns``."""
        if not self._closed:
            self._guard(lambda: self._writer.flush_due(now_ns))

    def flush(self) -> None:
        """Write out the pending chunk now, whatever its span (before a snapshot)."""
        if not self._closed:
            self._guard(lambda: self._writer.flush())

    def tap(self, stamp_ns: Callable[[], int]) -> Tap:
        """A :class:`Tap` writing into this bag, stamped by ``stamp_ns()`` (ns)."""
        tap = Tap(lambda topic, msgtype, data: self.write(topic, msgtype, data, stamp_ns(),
                                                          tap.qos.get(topic)))
        return tap

    def close(self) -> None:
        """Finalize the bag (metadata.yaml and MCAP summary). Safe to call twice."""
        if not self._closed and self._guard(self._writer.close):
            self._closed = True


class TopicRecorder:
    """Records every topic it discovers on the graph, as raw serialized messages.

    Args:
        node: node to create the subscriptions on.
        bag: where to write.
        stamp_ns: bag timestamp of the current time, ns.
        skip: topics not to subscribe to (those already tapped at their publisher).
        qos: subscription QoS.
        only: the topics to record (None = every one).
        skip_if: ``skip_if(node, topic)``: True = never subscribe to ``topic``, False =
            record it, None = not known yet, ask again at the next discovery (asked when the
            topic has a publisher).
        drop: per topic, ``drop[topic](data)``: True = leave this serialized message out
            (:func:`declares_only`: a simulation's bag leaves out the parameter declarations
            of a node starting beside it).
    """

    def __init__(self, node: Node, bag: BagWriter, stamp_ns: Callable[[], int],
                 skip: set[str], qos: QoSProfile, only: set[str] | None = None,
                 skip_if: Callable[[Node, str], bool | None] | None = None,
                 drop: Mapping[str, Callable[[bytes], bool]] | None = None) -> None:
        self._node = node
        self._bag = bag
        self._stamp_ns = stamp_ns
        self._skip = skip
        self._qos = qos
        self._only = only
        self._skip_if = skip_if
        self._drop = dict(drop or {})
        self._subs: dict[str, object] = {}

    def discover(self) -> None:
        """Subscribe to topics that appeared since the last call."""
        for topic, types in self._node.get_topic_names_and_types():
            if (topic in self._subs or topic in self._skip or topic in self._bag.exclude
                    or not types):
                continue
            if self._only is not None and topic not in self._only:
                continue
            msgtype = types[0]
            pkg, kind, name = msgtype.split("/")
            try:
                cls = getattr(importlib.import_module(f"{pkg}.{kind}"), name)
            except (ImportError, AttributeError):
                self._node.get_logger().warning(
                    f"not recording {topic}: type {msgtype} is not installed here")
                self._subs[topic] = None
                continue
            publishers = self._node.get_publishers_info_by_topic(topic)
            if not publishers:
                continue  # known only from a subscriber so far: wait for a publisher's QoS
            if self._skip_if is not None:
                verdict = self._skip_if(self._node, topic)
                if verdict is None:
                    continue  # ask again at the next discovery
                if verdict:
                    self._subs[topic] = None
                    continue
            qos = self._qos
            if all(p.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL
                   for p in publishers):
                # latched topics (/ocean/wave_field): ask for what was published before us
                qos = latched(self._qos)
            self._subs[topic] = self._node.create_subscription(
                cls, topic, self._writer_for(topic, msgtype, publishers[0].qos_profile), qos,
                raw=True)
            self._node.get_logger().info(f"recording {topic} [{msgtype}]")

    def _writer_for(self, topic: str, msgtype: str, offered: QoSProfile
                    ) -> Callable[[bytes], None]:
        drop = self._drop.get(topic)

        def on_message(data: bytes) -> None:
            if drop is None or not drop(data):
                self._bag.write(topic, msgtype, data, self._stamp_ns(), offered)
        return on_message


def spin_pending(executor: Executor, limit: int = 64, timeout: float = 0.0) -> int:
    """Run the callbacks that are ready, until none is within ``timeout`` (at most ``limit``).

    Args:
        executor: the executor.
        limit: at most this many callbacks.
        timeout: s (wall) to wait for the next one. With 0, Fast DDS (Jazzy) often reports
            nothing ready while a burst of messages is still queued: a drain that must take
            every received message waits a little (:data:`_DRAIN_QUIET`).

    Returns:
        How many ran.
    """
    for ran in range(limit):
        try:
            handler, _, _ = executor.wait_for_ready_callbacks(timeout_sec=timeout)
        except TimeoutException:
            return ran
        handler()
        if handler.exception() is not None:
            raise handler.exception()
    return limit


def declares_only(data: bytes) -> bool:
    """Whether a serialized /parameter_events message only declares parameters.

    A node declares its parameters (``use_sim_time`` at least) as it starts; a process that
    starts beside the simulation (the surface server) does so at a wall-clock moment, so
    whether the recorder has matched it yet, and the simulation time it is stamped with, differ
    between two identical runs. A value set or deleted is kept.
    """
    from rcl_interfaces.msg import ParameterEvent
    from rclpy.serialization import deserialize_message

    event = deserialize_message(data, ParameterEvent)
    return bool(event.new_parameters) and not (event.changed_parameters
                                               or event.deleted_parameters)


def record(topics: list[str], out: str, status: TextIO | None = None,
           exclude: set[str] | frozenset[str] = frozenset()) -> int:
    """`boatsim record`: record topics (all when empty) until Ctrl-C; returns the exit status.

    New topics are picked up as they appear (discovery every 0.2 s); a live line shows the
    count per topic; SIGINT/SIGTERM finalize the bag, with every message DDS had received
    before the signal (a publisher that saw its messages acknowledged finds them in the bag).

    Raises:
        RecordError: the bag directory cannot be created.
    """
    status = sys.stderr if status is None else status  # now, not at import
    import threading
    import time

    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.signals import SignalHandlerOptions

    from boat_msgs_py.process import stop_on_signals

    bag = BagWriter(out, exclude=exclude)
    stop = threading.Event()
    restore_signals = stop_on_signals(stop)
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = rclpy.create_node(names.RECORDER_NODE)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    tty = status.isatty()
    try:
        recorder = TopicRecorder(
            node, bag, time.time_ns, skip=set(),
            qos=RECORD_QOS,
            only=set(topics) if topics else None)
        node.get_logger().info(f"recording {'all topics' if not topics else ' '.join(topics)}"
                               f" to {bag.path}; Ctrl-C to stop")
        next_discovery = next_status = 0.0
        while not stop.is_set():
            now = time.monotonic()
            if now >= next_discovery:
                recorder.discover()
                next_discovery = now + 0.2  # new topics are caught within 0.2 s
            bag.flush_due(time.time_ns())
            if now >= next_status:
                counts = "  ".join(f"{t} {n}" for t, n in sorted(bag.counts.items()))
                line = f"{sum(bag.counts.values())} messages: {counts}"
                status.write(("\r" + line[:200]) if tty else line + "\n")
                status.flush()
                next_status = now + (0.5 if tty else 5.0)
            executor.spin_once(timeout_sec=0.05)
            if bag.failed is not None:
                node.get_logger().error(bag.stopped_line())
                return 1
        # received, not yet taken: into the bag (a wait of 0 s saw one of a queued burst)
        spin_pending(executor, _DRAIN_LIMIT, timeout=_DRAIN_QUIET)
        return 0 if bag.failed is None else 1
    finally:
        bag.close()
        if tty:
            status.write("\n")
        print(f"boatsim: wrote {sum(bag.counts.values())} messages on {len(bag.counts)} "
              f"topics to {bag.path}", file=status)
        executor.shutdown(timeout_sec=0.1)
        node.destroy_node()
        rclpy.try_shutdown()
        restore_signals()
