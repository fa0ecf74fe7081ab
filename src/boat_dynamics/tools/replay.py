"""`boatsim replay BAG`: republish a bag's command topics at their recorded simulation times.

Times: a command's bag timestamp minus the bag's simulation epoch (the header stamp of its
/ocean/wave_field, which is the stamp of simulation time 0), so bags of real-time and fast
runs replay alike.

Against ``boatsim run --fast --lockstep`` the replay is in lockstep: before command i (due at
t_i) it grants "advance while t < t_i" on /boatsim/lockstep, waits on /clock until the
simulation holds at t_i, publishes the command, and grants the next time together with the
number of commands sent, so the simulation never steps past a command it has not received.
Each command then takes effect at the same step on a fast or a slow machine. Before the first
command it waits for every dynamics node subscribing to its command topics to say, on
/boatsim/lockstep_ready, that those subscriptions have matched its publishers (DDS loses what
is published before), and it repeats the current grant every 0.1 s while it waits (a grant is
"at most": the followers keep the largest). Against a real-time simulation the commands are
published on the wall clock (times divided by ``rate``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

from boat_dynamics.tools.bags import BagError, read_bag, read_bag_topics
from boat_msgs_py import names

__all__ = ["Command", "ReplayError", "command_schedule", "follows_lockstep", "parse_ready",
           "replay", "unannounced"]

_FOREVER = 1e18  # the last grant: run on to the end
#: s (wall) between two copies of the current grant while the replayer waits on /clock.
_GRANT_REPEAT = 0.1
#: s (wall) a replayer that has found the commands' subscribers waits for a lockstep follower
#: before it replays on the wall clock (a real-time simulation has none).
_FOLLOWER_GRACE = 2.0


def follows_lockstep(node_name: str) -> bool:
    """Whether a subscriber of /boatsim/lockstep with this node name obeys it.

    Only boatsim's own: a dynamics node (``boat_dynamics``, ``boat_dynamics_<boat>``,
    ``boat_dynamics_shard_<K>``) or the clock owner of a run over several processes. A
    recorder (``boatsim record``, ``ros2 bag record``) or a user's node that merely listens
    would otherwise be taken for a lockstep simulation: the replayer waited for its /clock
    until --timeout and failed, where a real-time run wants the wall clock.
    """
    return node_name.startswith(names.DYNAMICS_NODE) or node_name == names.CLOCK_NODE


def parse_ready(text: str) -> tuple[str, set[str]]:
    """A /boatsim/lockstep_ready message: (the node's name, the topics it has matched)."""
    node, *topics = text.split()
    return node, set(topics)


def unannounced(subscribers: dict[str, set[str]], ready: dict[str, set[str]]
                ) -> list[tuple[str, str]]:
    """The (node, topic) pairs whose match a lockstep node has not announced yet.

    Args:
        subscribers: per command topic, the names of the nodes subscribing to it (the graph).
        ready: per node, the topics it last announced on /boatsim/lockstep_ready.

    Only boatsim's dynamics nodes (:func:`follows_lockstep`) answer; another subscriber (a
    recorder, a user's node) is not waited for.
    """
    return sorted((node, topic) for topic, nodes in subscribers.items() for node in nodes
                  if follows_lockstep(node) and topic not in ready.get(node, set()))


class ReplayError(RuntimeError):
    """No simulation to replay into, or it stopped answering."""


@dataclass(frozen=True)
class Command:
    """One command of a replay.

    Attributes:
        t: simulation time, s.
        topic: the command topic.
        value: the Float64 value.
    """

    t: float
    topic: str
    value: float


def command_schedule(bag: str | Path, topics: list[str] | None = None) -> list[Command]:
    """The bag's commands in simulation time, in order.

    Raises:
        BagError: unreadable bag, no command topics, or a topic not in the bag.
    """
    available = read_bag_topics(bag)
    if topics is None:
        topics = [t for t in available if names.is_command_topic(t)]
        if not topics:
            raise BagError(f"{bag}: no command topics (*/cmd_thrust, */cmd_rudder, "
                           "*/thrusters/*/thrust|angle) to replay")
    wanted = list(topics)
    if names.WAVE_FIELD in available:
        wanted.append(names.WAVE_FIELD)
    messages = read_bag(bag, wanted)
    field = messages.pop(names.WAVE_FIELD, [])
    stamps = [s for msgs in messages.values() for s, _ in msgs]
    epoch = field[0][0] if field else (min(stamps) if stamps else 0)
    out = [Command((stamp - epoch) / 1e9, topic, float(msg.data))
           for topic, msgs in messages.items() for stamp, msg in msgs]
    return sorted(out, key=lambda c: c.t)


def replay(bag: str | Path, topics: list[str] | None = None, rate: float = 1.0,
           timeout: float = 30.0) -> int:
    """Replay the commands of ``bag`` into the running simulation; returns the exit status.

    Raises:
        BagError: unreadable bag or topics.
        ReplayError: no simulation subscribes to the command topics within ``timeout``.
    """
    schedule = command_schedule(bag, topics)
    replayer = _Replayer(sorted({c.topic for c in schedule}), timeout)
    try:
        replayer.spin_until(replayer.commands_followed,
                            f"a simulation subscribing to {', '.join(replayer.pubs)}")
        lockstep = replayer.lockstep_found()
        if lockstep:
            replayer.await_lockstep()
        replayer.log.info(f"replaying {len(schedule)} commands from {bag} "
                          f"({'lockstep with /clock' if lockstep else f'wall clock x{rate:g}'})")
        sent = _send(schedule, replayer.pubs, replayer.grant if lockstep else None,
                     replayer.clock, rate, replayer.spin_until)
        if lockstep:
            replayer.executor.spin_once(timeout_sec=0.1)
        replayer.log.info(f"replayed {sent} commands")
        return 0
    finally:
        replayer.close()


class _Replayer:
    """The replay node: command publishers, the lockstep grant, /clock and the ready words.

    A publisher per command topic; the grant on /boatsim/lockstep; the simulation's /clock;
    the lockstep simulations' word that their subscriptions have matched.

    Args:
        topics: the command topics.
        timeout: s, how long :meth:`spin_until` waits for anything.
    """

    def __init__(self, topics: list[str], timeout: float) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rosgraph_msgs.msg import Clock
        from std_msgs.msg import Float64, Float64MultiArray, String

        from boat_msgs_py.convert import time_to_seconds
        from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS

        self.timeout = timeout
        self.context = rclpy.Context()
        rclpy.init(context=self.context)
        self.node = rclpy.create_node(names.REPLAY_NODE, context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.log = self.node.get_logger()
        self.clock = [math.nan]  # the simulation's /clock, s
        self.node.create_subscription(
            Clock, names.CLOCK, lambda m: self.clock.__setitem__(0, time_to_seconds(m.clock)),
            CLOCK_QOS)
        self.pubs = {t: self.node.create_publisher(Float64, t, COMMAND_QOS) for t in topics}
        self.grant = self.node.create_publisher(Float64MultiArray, names.LOCKSTEP, COMMAND_QOS)
        self.ready: dict[str, set[str]] = {}  # node -> the command topics it has matched
        self.node.create_subscription(String, names.LOCKSTEP_READY, self._on_ready, COMMAND_QOS)

    def _on_ready(self, msg) -> None:
        if msg.data.strip():
            name, topics = parse_ready(msg.data)
            self.ready[name] = topics

    def spin_until(self, condition, what) -> None:
        """Serve callbacks until ``condition()``; ReplayError after the time-out.

        ``what``: the awaited thing, or a callable giving it (said as it stands at the
        time-out).
        """
        deadline = time.monotonic() + self.timeout
        while not condition():
            if time.monotonic() > deadline:
                clock = self.clock[0]
                where = "" if math.isnan(clock) else f" (its /clock: t = {clock:.3f} s)"
                what = what() if callable(what) else what
                raise ReplayError(f"timed out after {self.timeout:g} s waiting for {what}{where}")
            self.executor.spin_once(timeout_sec=0.01)

    def commands_followed(self) -> bool:
        """Every command topic has a subscriber."""
        return all(p.get_subscription_count() > 0 for p in self.pubs.values())

    def followers(self) -> tuple[set[str], bool]:
        """/boatsim/lockstep's followers (node names), and whether one is not named yet.

        An unnamed subscriber's node discovery has not arrived: ask again.
        """
        found = {i.node_name for i in self.node.get_subscriptions_info_by_topic(names.LOCKSTEP)}
        unnamed = bool(found & {"", names.UNKNOWN_NODE})
        return {n for n in found if follows_lockstep(n)}, unnamed

    def waiting_for(self) -> list[tuple[str, str]]:
        """(node, topic) of command subscriptions not yet announced as matched."""
        subscribers = {t: {i.node_name for i in self.node.get_subscriptions_info_by_topic(t)}
                       for t in self.pubs}
        return unannounced(subscribers, self.ready)

    def lockstep_found(self) -> bool:
        """Whether the simulation follows /boatsim/lockstep.

        A lockstep simulation subscribes to /boatsim/lockstep before its command topics
        (each dynamics process, DynamicsNode's ``lockstep``); a real-time one does not. So
        once the commands' subscribers are found, a follower is found too or is not
        coming: wait a little for it, and on while one is still unnamed. (Before, any
        follower counted and /clock had 2 s to come: on a loaded machine it came later,
        the replay went by the wall clock and the simulation waited at t = 0 for ever.)
        """
        start = time.monotonic()
        while True:
            found, unnamed = self.followers()
            waited = time.monotonic() - start
            if found or waited > self.timeout or (waited > _FOLLOWER_GRACE and not unnamed):
                return bool(found)
            self.executor.spin_once(timeout_sec=0.05)

    def await_lockstep(self) -> None:
        """Wait for the lockstep simulation's /clock and its word on every command topic."""
        self.spin_until(lambda: not math.isnan(self.clock[0]),
                        "/clock from the lockstep simulation "
                        f"({', '.join(sorted(self.followers()[0]))})")
        self.spin_until(lambda: not self.waiting_for(), lambda: (
            "the simulation's word that its subscriptions have matched the replayer's "
            f"publishers ({names.LOCKSTEP_READY}; still missing: "
            f"{', '.join(f'{n} {t}' for n, t in self.waiting_for()[:4])})"))

    def close(self) -> None:
        """Stop the executor, destroy the node, shut its context down."""
        import rclpy

        self.executor.shutdown(timeout_sec=0.1)
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)


def _send(schedule: list[Command], pubs: dict, grant, clock: list[float], rate: float,
          spin_until) -> int:
    """Publish every command at its time; returns how many were sent.

    Args:
        schedule: the commands, in time order.
        pubs: a Float64 publisher per command topic.
        grant: the lockstep publisher (grant "advance while t < T; n sent", wait on /clock),
            or None to follow the wall clock.
        clock: [the simulation's /clock, s], updated by its subscription.
        rate: speed factor against the wall clock.
        spin_until: serves callbacks until a condition holds (raises on a time-out).
    """
    from std_msgs.msg import Float64, Float64MultiArray

    sent = 0
    start = time.monotonic()
    for command in schedule:
        if grant is not None:
            spin_until(_granting(grant, Float64MultiArray(data=[command.t, float(sent)]),
                                 lambda t=command.t: clock[0] >= t - 1e-9),
                       f"the simulation to reach t = {command.t:.3f} s")
        else:
            spin_until(lambda t=command.t: (time.monotonic() - start) * rate >= t,
                       "the wall clock")
        pubs[command.topic].publish(Float64(data=command.value))
        sent += 1
    if grant is not None:
        grant.publish(Float64MultiArray(data=[_FOREVER, float(sent)]))
    return sent


def _granting(grant, message, reached):
    """A condition that publishes ``message`` now and again every _GRANT_REPEAT s till it holds.

    ``reached()`` is the condition itself. A grant lost to a follower that had not matched the
    replayer yet is given again (a follower keeps the largest grant: copies change nothing).
    """
    grant.publish(message)
    due = time.monotonic() + _GRANT_REPEAT

    def condition() -> bool:
        nonlocal due
        if reached():
            return True
        if time.monotonic() >= due:
            grant.publish(message)
            due = time.monotonic() + _GRANT_REPEAT
        return False

    return condition
