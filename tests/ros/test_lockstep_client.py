"""Lockstep for any client (docs/DESIGN.md, "Lockstep: the client's recipe").

A node of the test's own, named neither `boatsim_replay` nor anything of boatsim's, drives
`boatsim run --fast --lockstep` by the documented recipe: the simulation answers its
handshake on /boatsim/lockstep_ready, holds at each granted time, and takes each command at
the step it was sent at.
"""

import math

import pytest
from rosbags.highlevel import AnyReader
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64, Float64MultiArray, String

from boat_dynamics.tools.replay import follows_lockstep, parse_ready
from boat_msgs_py import names
from boat_msgs_py.convert import time_to_seconds
from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS

COMMANDS = ("/cmd_thrust", "/cmd_rudder")


class Client:
    """The recipe's client: grant and command publishers, /clock and the ready words."""

    def __init__(self, probe, name: str) -> None:
        self.probe, self.node = probe, probe.other_node(name)
        # 1. the publishers, and the subscriptions to /clock and the ready words
        self.grant = self.node.create_publisher(Float64MultiArray, names.LOCKSTEP, COMMAND_QOS)
        self.pubs = {t: self.node.create_publisher(Float64, t, COMMAND_QOS) for t in COMMANDS}
        self.clock, self.ready, self.sent = math.nan, {}, 0
        self.node.create_subscription(Clock, names.CLOCK, self._on_clock, CLOCK_QOS)
        self.node.create_subscription(String, names.LOCKSTEP_READY, self._on_ready,
                                      COMMAND_QOS)

    def _on_clock(self, msg) -> None:
        self.clock = time_to_seconds(msg.clock)

    def _on_ready(self, msg) -> None:
        node, topics = parse_ready(msg.data)
        self.ready[node] = topics

    def followers(self) -> set[str]:
        return {i.node_name for i in self.node.get_subscriptions_info_by_topic(names.LOCKSTEP)
                if follows_lockstep(i.node_name)}

    def announced(self) -> bool:
        """Every dynamics node subscribing to a command topic has said it matched it."""
        for topic in COMMANDS:
            nodes = {i.node_name for i in self.node.get_subscriptions_info_by_topic(topic)}
            if not nodes or nodes & {"", names.UNKNOWN_NODE}:  # not discovered yet: again
                return False
            if any(topic not in self.ready.get(n, set()) for n in nodes if follows_lockstep(n)):
                return False
        return True

    def connect(self, timeout: float) -> None:
        # 2. the command topics' subscribers and a lockstep follower; 3. its /clock
        self.probe.spin_until(lambda: all(p.get_subscription_count() for p in
                                          self.pubs.values()) and self.followers(),
                              timeout, "the simulation's subscriptions")
        self.probe.spin_until(lambda: not math.isnan(self.clock), timeout, "/clock")
        # 4. every dynamics node's word that it has matched the client's command publishers
        self.probe.spin_until(self.announced, timeout, names.LOCKSTEP_READY)

    def advance(self, until: float, timeout: float) -> None:
        # 5. grant [T, n], repeated every 0.1 s, until /clock says the simulation holds at T
        while True:
            self.grant.publish(Float64MultiArray(data=[until, float(self.sent)]))
            try:
                self.probe.spin_until(lambda: self.clock >= until - 1e-9, 0.1)
                return
            except AssertionError:
                timeout -= 0.1
                if timeout < 0:
                    raise

    def send(self, topic: str, value: float) -> None:
        self.pubs[topic].publish(Float64(data=value))
        self.sent += 1


def test_a_client_of_any_name_drives_a_lockstep_run(boatsim, probe, tmp_path):
    client = Client(probe, "learning_harness")
    sim = boatsim("run", "--fast", "--lockstep", "--duration", "3", "--record",
                  str(tmp_path / "bag"))
    client.connect(timeout=90.0)
    assert client.ready[names.DYNAMICS_NODE] >= set(COMMANDS)
    plan = [(0.0, "/cmd_thrust", 1.0), (1.0, "/cmd_rudder", 0.3), (2.0, "/cmd_thrust", -0.5)]
    for t, topic, value in plan:
        client.advance(t, timeout=60.0)
        assert client.clock == pytest.approx(t, abs=1e-9)
        if t == 1.0:  # it holds there (a free --fast run makes 20 simulated s a second)
            probe.spin_for(0.3)
            assert client.clock == pytest.approx(1.0, abs=1e-9)
        client.send(topic, value)
    # 6. the last grant: on to the run's --duration
    client.grant.publish(Float64MultiArray(data=[1e18, float(client.sent)]))
    probe.spin_until(lambda: sim.proc.poll() is not None, 60.0, "the end of the run")
    assert sim.wait(timeout=5) == 0, sim.output()
    with AnyReader([tmp_path / "bag"]) as reader:
        conns = [c for c in reader.connections if c.topic in (*COMMANDS, "/wrench/thrust")]
        seen = {t: [] for t in (*COMMANDS, "/wrench/thrust")}
        for conn, stamp, raw in reader.messages(connections=conns):
            seen[conn.topic].append((stamp / 1e9, reader.deserialize(raw, conn.msgtype)))
    # each command taken at the step it was sent at
    assert [(round(s, 9), m.data) for s, m in seen["/cmd_thrust"]] == [(0.0, 1.0), (2.0, -0.5)]
    assert [(round(s, 9), m.data) for s, m in seen["/cmd_rudder"]] == [(1.0, 0.3)]
    thrust = {round(s, 3): math.copysign(math.hypot(m.wrench.force.x, m.wrench.force.y),
                                         m.wrench.force.x) for s, m in seen["/wrench/thrust"]}
    # a wrench is stamped at the end of the step it acted in: the thrust of 0 s from the first
    # step on, none past cmd_timeout (1 s), and the astern thrust from the step at 2 s
    assert thrust[0.1] == pytest.approx(2000.0) and thrust[1.0] == pytest.approx(2000.0)
    assert thrust[1.1] == 0.0 and thrust[2.0] == 0.0
    assert thrust[2.1] == pytest.approx(-1000.0)
