"""``boatsim topic|node|param ...``: the ``ros2`` verbs a PyPI install lacks, same flags and output.

The PyPI wheels of ROS 2 Jazzy have no ``ros2`` command line. These verbs cover what a user
of boatsim reaches for, with ``ros2``'s flags and output shapes where they exist: ``topic list
[-t] [-c]``, ``topic info TOPIC [-v]``, ``topic echo TOPIC [--once] [--full-length]``,
``topic hz TOPIC [--window N]``, ``topic pub TOPIC TYPE VALUES [-r HZ] [-1] [-t N]``,
``node list``, ``param list|get|set|dump``. On a full ROS install ``ros2`` works as well.

Each verb makes one hidden node (``_boatsim_cli``) in its own context and waits for the graph
``--spin-time`` (default 1 s, as ``ros2``'s daemon-less discovery) before answering.
"""

from __future__ import annotations

import math
import statistics
import time
from collections import deque
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TextIO

__all__ = ["IntrospectionError", "Session", "TopicRate", "node_list", "param_dump", "param_get",
           "param_list", "param_set", "session", "topic_echo", "topic_hz", "topic_info",
           "topic_list", "topic_pub"]

#: How long a verb lets DDS discovery fill the graph at least, s (wall) ...
SPIN_TIME = 1.0
#: ... and then until the graph has not changed for this long, s ...
_QUIET = 1.0
#: ... but no longer than this, s (a graph that keeps changing).
_SETTLE_LIMIT = 10.0


class IntrospectionError(ValueError):
    """A topic, node, type or parameter that is not there, or a value that does not fit."""


class Session:
    """The verbs' hidden node (``_boatsim_cli``) and the executor that spins it.

    Attributes:
        node: the node, for graph queries, subscriptions and clients.
    """

    def __init__(self, node, executor) -> None:
        self.node = node
        self._executor = executor

    def spin_once(self, timeout: float) -> None:
        """Serve the callbacks ready within ``timeout`` s."""
        self._executor.spin_once(timeout_sec=timeout)

    def settle(self, spin_time: float) -> None:
        """Let discovery fill the graph: ``spin_time`` s, then until it stops changing.

        A participant's endpoints arrive over a second or more (a 3-boat run's 40 topics:
        2 to 40 after 1 s, measured), and ``ros2`` has a daemon that already knows them. On
        a loaded machine participants are found seconds apart: a longer ``spin_time`` (the
        ``--spin-time`` option) also waits longer for quiet (half of it, at least 1 s).
        """
        quiet = max(_QUIET, spin_time / 2)
        start = time.monotonic()
        last, since = None, start
        while (now := time.monotonic()) - start < _SETTLE_LIMIT:
            graph = (len(self.node.get_topic_names_and_types()),
                     len(self.node.get_node_names_and_namespaces()))
            if graph != last:
                last, since = graph, now
            elif now - start >= spin_time and now - since >= quiet:
                return
            self.spin_once(0.1)

    def spin_until(self, done: Callable[[], bool], timeout: float | None) -> bool:
        """Spin until ``done()`` (True) or ``timeout`` s (False; None = no limit)."""
        end = math.inf if timeout is None else time.monotonic() + timeout
        while not done():
            if time.monotonic() > end:
                return False
            self.spin_once(0.05)
        return True


@contextmanager
def session(spin_time: float = SPIN_TIME) -> Iterator[Session]:
    """A hidden node in a context of its own, the graph discovered for ``spin_time`` s."""
    import rclpy
    from rclpy.executors import SingleThreadedExecutor

    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("_boatsim_cli", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    try:
        s = Session(node, executor)
        s.settle(spin_time)
        yield s
    finally:
        executor.shutdown(timeout_sec=0.5)
        node.destroy_node()
        context.try_shutdown()


def _visible(name: str) -> bool:
    return not any(part.startswith("_") for part in name.split("/") if part)


def topic_list(s: Session, show_types: bool = False, count: bool = False) -> list[str]:
    """``ros2 topic list`` lines (``-t``: with ``[type]``; ``-c``: the count only)."""
    topics = [(name, types) for name, types in s.node.get_topic_names_and_types()
              if _visible(name)]
    if count:
        return [str(len(topics))]
    return [f"{name} [{', '.join(types)}]" if show_types else name for name, types in topics]


def _qos_lines(info) -> list[str]:
    q = info.qos_profile
    return ["QoS profile:",
            f"  Reliability: {q.reliability.name}", f"  History (Depth): {q.history.name} "
            f"({q.depth})", f"  Durability: {q.durability.name}",
            f"  Lifespan: {_duration(q.lifespan)}", f"  Deadline: {_duration(q.deadline)}",
            f"  Liveliness: {q.liveliness.name}",
            f"  Liveliness lease duration: {_duration(q.liveliness_lease_duration)}"]


def _duration(d) -> str:
    ns = d.nanoseconds
    return "Infinite" if ns >= 0x7FFFFFFFFFFFFFFF else f"{ns} nanoseconds"


def topic_info(s: Session, topic: str, verbose: bool = False) -> list[str]:
    """``ros2 topic info TOPIC [-v]`` lines.

    Raises:
        IntrospectionError: the topic is not on the graph.
    """
    types = dict(s.node.get_topic_names_and_types()).get(topic)
    if types is None:
        raise IntrospectionError(f"Unknown topic '{topic}'")
    pubs = s.node.get_publishers_info_by_topic(topic)
    subs = s.node.get_subscriptions_info_by_topic(topic)
    lines = [f"Type: {', '.join(types)}", ""] if verbose else [f"Type: {', '.join(types)}"]
    for kind, infos in (("Publisher", pubs), ("Subscription", subs)):
        lines.append(f"{kind} count: {len(infos)}")
        if verbose:
            lines.append("")
            for info in infos:
                lines += [f"Node name: {info.node_name}",
                          f"Node namespace: {info.node_namespace}",
                          f"Topic type: {info.topic_type}",
                          f"Endpoint type: {info.endpoint_type.name}",
                          *_qos_lines(info), ""]
    return lines


def _type_of(s: Session, topic: str, wait: float) -> str:
    """The topic's type, waiting ``wait`` s for it to appear."""
    found: list[str] = []

    def seen() -> bool:
        found[:] = dict(s.node.get_topic_names_and_types()).get(topic, [])
        return bool(found)

    if not s.spin_until(seen, wait):
        raise IntrospectionError(f"topic {topic} is not on the graph (after {wait:g} s); "
                                 "`boatsim topic list` shows what is")
    return found[0]


def _matching_qos(s: Session, topic: str, wait: float):
    """A QoS every publisher of ``topic`` can serve (``boat_msgs_py.qos.serving``).

    A topic may be on the graph by its subscriptions before its publisher is (discovery
    brings a participant's endpoints one by one): this waits up to ``wait`` s for a
    publisher, else a latched topic would get a volatile subscription and its message would
    never come (seen in CI: `echo /ocean/wave_field --once` printed nothing in 30 s).
    """
    from boat_msgs_py.qos import serving

    def offered():
        return [i.qos_profile for i in s.node.get_publishers_info_by_topic(topic)]

    s.spin_until(lambda: bool(offered()), wait)
    return serving(offered())


def topic_echo(s: Session, topic: str, out: TextIO, once: bool = False, full_length: bool = False,
               wait: float = 5.0, timeout: float | None = None) -> int:
    """``ros2 topic echo TOPIC``: each message as YAML, then ``---``; returns messages printed.

    Args:
        s: the session.
        topic: absolute topic name.
        out: where to print.
        once: stop after the first message (``--once``).
        full_length: print long arrays whole (``--full-length``).
        wait: s to wait for the topic to appear on the graph.
        timeout: s to print for (None: until Ctrl-C).
    """
    from boat_msgs_py.fields import message_class, message_to_yaml

    cls = message_class(_type_of(s, topic, wait))
    printed = [0]

    def show(msg) -> None:
        if once and printed[0]:
            return
        out.write(message_to_yaml(msg, full_length) + "---\n")
        out.flush()
        printed[0] += 1

    s.node.create_subscription(cls, topic, show, _matching_qos(s, topic, wait))
    s.spin_until(lambda: once and printed[0] > 0, timeout)
    return printed[0]


class TopicRate:
    """``ros2 topic hz``'s figures over the last ``window`` arrival intervals.

    Args:
        window: intervals kept (``--window``).
    """

    def __init__(self, window: int = 10000) -> None:
        self._last: float | None = None
        self._intervals: deque[float] = deque(maxlen=window)

    def arrived(self, t: float) -> None:
        """A message arrived at ``t`` s."""
        if self._last is not None:
            self._intervals.append(t - self._last)
        self._last = t

    def report(self) -> str | None:
        """``average rate: R`` with min, max, std dev and window; None before two messages."""
        d = self._intervals
        if not d:
            return None
        mean = statistics.fmean(d)
        rate = 1.0 / mean if mean > 0 else math.inf
        std = statistics.pstdev(d) if len(d) > 1 else 0.0
        return (f"average rate: {rate:.3f}\n\tmin: {min(d):.3f}s max: {max(d):.3f}s "
                f"std dev: {std:.5f}s window: {len(d) + 1}")


def topic_hz(s: Session, topic: str, out: TextIO, window: int = 10000, wait: float = 5.0,
             timeout: float | None = None, clock: Callable[[], float] = time.monotonic) -> int:
    """``ros2 topic hz TOPIC --wall-time``: the arrival rate, printed every second.

    Returns the number of messages counted.
    """
    from boat_msgs_py.fields import message_class

    cls = message_class(_type_of(s, topic, wait))
    rate, count = TopicRate(window), [0]

    def arrived(_msg) -> None:
        rate.arrived(clock())
        count[0] += 1

    s.node.create_subscription(cls, topic, arrived, _matching_qos(s, topic, wait))
    end = math.inf if timeout is None else time.monotonic() + timeout
    next_print = time.monotonic() + 1.0
    while time.monotonic() < end:
        s.spin_once(0.05)
        if time.monotonic() >= next_print:
            next_print += 1.0
            line = rate.report()
            out.write((line or f"no new messages on {topic}") + "\n")
            out.flush()
    return count[0]


def topic_pub(s: Session, topic: str, type_name: str, values: str, out: TextIO,
              rate_hz: float = 1.0, times: int | None = None, wait_matching: int = 0) -> int:
    """``ros2 topic pub TOPIC TYPE VALUES``: publish at ``rate_hz``; returns messages sent.

    ``values`` is YAML (``'{data: 0.5}'``). ``times``: stop after that many (None: until
    Ctrl-C). ``wait_matching``: first wait for that many matching subscriptions (``-w``; as
    ``ros2``, 1 by default with ``--once`` or ``--times``, so they are not lost to discovery).
    """
    import yaml

    from boat_dynamics.physics.scenario import MAX_DEPTH, ScenarioError, check_bounded
    from boat_dynamics.physics.scenario.read import yaml_depth
    from boat_msgs_py.fields import FieldError, message_class, set_fields
    from boat_msgs_py.qos import COMMAND_QOS

    cls = message_class(type_name)
    try:
        if yaml_depth(values, MAX_DEPTH) > MAX_DEPTH:  # before the recursive composer
            raise IntrospectionError(f"VALUES must nest at most {MAX_DEPTH} levels deep")
        parsed = yaml.safe_load(values) if values.strip() else {}
        check_bounded(parsed, "VALUES")  # an alias fan-out: 60-99 s in set_fields before
        msg = set_fields(cls(), {} if parsed is None else parsed)
    except yaml.YAMLError as exc:
        raise IntrospectionError(f"VALUES {values!r} is not YAML: {' '.join(str(exc).split())}"
                                 ) from None
    except FieldError as exc:
        raise IntrospectionError(str(exc)) from None
    except ScenarioError as exc:
        raise IntrospectionError(f"VALUES {exc.allowed}") from None
    pub = s.node.create_publisher(cls, topic, COMMAND_QOS)
    if wait_matching:
        out.write(f"Waiting for at least {wait_matching} matching subscription(s)...\n")
        out.flush()
        s.spin_until(lambda: pub.get_subscription_count() >= wait_matching, None)
    out.write("publisher: beginning loop\n")
    sent = 0
    next_send = time.monotonic()
    while times is None or sent < times:
        s.spin_once(max(0.0, next_send - time.monotonic()))
        if time.monotonic() < next_send:
            continue
        pub.publish(msg)
        sent += 1
        out.write(f"publishing #{sent}: {msg!r}\n\n")
        out.flush()
        next_send += 1.0 / rate_hz
    s.spin_until(lambda: False, 0.2)  # let a last reliable message go out
    return sent


def node_list(s: Session) -> list[str]:
    """``ros2 node list`` lines: every visible node's full name, sorted."""
    names = []
    for name, namespace in s.node.get_node_names_and_namespaces():
        full = f"{namespace.rstrip('/')}/{name}"
        if _visible(full):
            names.append(full)
    return sorted(names)


def _parameter_client(s: Session, target: str, wait: float):
    from rclpy.parameter_client import AsyncParameterClient

    client = AsyncParameterClient(s.node, target)
    if not client.wait_for_services(timeout_sec=wait):
        raise IntrospectionError(f"Node not found: {target} (`boatsim node list` shows the "
                                 "nodes)")
    return client


def _result(s: Session, future, what: str, wait: float):
    if not s.spin_until(future.done, wait) or future.result() is None:
        raise IntrospectionError(f"{what}: no answer within {wait:g} s")
    return future.result()


def param_list(s: Session, target: str, wait: float = 5.0) -> list[str]:
    """``ros2 param list NODE`` lines: the parameter names, sorted."""
    client = _parameter_client(s, target, wait)
    result = _result(s, client.list_parameters(), f"listing {target}'s parameters", wait)
    return [f"  {name}" for name in sorted(result.result.names)]


def _value(value) -> tuple[str, object]:
    """(ros2's type word, Python value) of an rcl_interfaces ParameterValue."""
    from rclpy.parameter import parameter_value_to_python

    words = {1: "Boolean value is", 2: "Integer value is", 3: "Double value is",
             4: "String value is", 5: "Byte values are", 6: "Boolean values are",
             7: "Integer values are", 8: "Double values are", 9: "String values are"}
    return words.get(value.type, "Parameter not set"), parameter_value_to_python(value)


def param_get(s: Session, target: str, name: str, wait: float = 5.0) -> str:
    """``ros2 param get NODE NAME``: ``Double value is: 50.0``."""
    client = _parameter_client(s, target, wait)
    result = _result(s, client.get_parameters([name]), f"getting {name}", wait)
    if not result.values or result.values[0].type == 0:
        raise IntrospectionError(f"Parameter not set: {name} (on {target}; `boatsim param "
                                 f"list {target}` shows its parameters)")
    word, value = _value(result.values[0])
    return f"{word}: {value}"


def param_set(s: Session, target: str, name: str, text: str, wait: float = 5.0) -> str:
    """``ros2 param set NODE NAME VALUE``: ``Set parameter successful``.

    VALUE is YAML (``2``, ``2.5``, ``true``, ``sea``); a whole number for a double parameter
    is taken as a double (``ros2`` refuses it as the wrong type).

    Raises:
        IntrospectionError: the node refused the value (``Setting parameter failed: `` and
            its reason: out of range, read-only, the wrong type), so that a script sees a
            non-zero exit status where ``ros2 param set`` exits 0.
    """
    import yaml
    from rcl_interfaces.msg import ParameterType
    from rclpy.parameter import Parameter

    from boat_dynamics.physics.scenario import MAX_DEPTH
    from boat_dynamics.physics.scenario.read import yaml_depth

    client = _parameter_client(s, target, wait)
    try:
        value = text if yaml_depth(text, MAX_DEPTH) > MAX_DEPTH else yaml.safe_load(text)
    except yaml.YAMLError:
        value = text
    current = _result(s, client.get_parameters([name]), f"getting {name}", wait)
    if current.values and current.values[0].type == ParameterType.PARAMETER_DOUBLE and (
            isinstance(value, int) and not isinstance(value, bool)):
        value = float(value)
    result = _result(s, client.set_parameters([Parameter(name, value=value)]),
                     f"setting {name}", wait)
    answer = result.results[0]
    if not answer.successful:
        raise IntrospectionError(f"Setting parameter failed: {answer.reason}")
    return "Set parameter successful"


def param_dump(s: Session, target: str, wait: float = 5.0) -> str:
    """``ros2 param dump NODE``: YAML that ``--params-file`` style tools read."""
    import yaml

    client = _parameter_client(s, target, wait)
    names = sorted(_result(s, client.list_parameters(), "listing", wait).result.names)
    values = _result(s, client.get_parameters(names), "getting", wait).values
    params = {n: _value(v)[1] for n, v in zip(names, values, strict=True)}
    full = target if target.startswith("/") else f"/{target}"
    return yaml.safe_dump({full: {"ros__parameters": params}}, sort_keys=True,
                          default_flow_style=False)


