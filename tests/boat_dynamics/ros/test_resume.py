"""A dynamics node resumed from another's snapshot continues it bit for bit (shard restarts).

In-process nodes, stepped by the test: no ROS graph is needed (commands go through the nodes'
own callbacks, messages are read from their taps).
"""


import numpy as np
import pytest
import rclpy
from std_msgs.msg import Float64

from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.core.snapshot import SnapshotError, load, save
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.ros.node import DynamicsNode, SimClock
from boat_msgs_py.tap import Tap

SCENARIO = {
    "simulation": {"seed": 3},
    "ocean": {"spectrum": {"significant_height": 0.8, "peak_period": 5.0, "components": 8}},
    "boats": [
        {"name": "plain"},
        {"name": "twin", "initial_pose": {"position": [20.0, 0.0, 0.0]},
         "propulsion": [{"name": "left", "max_thrust": 300.0, "position": [-1.5, 0.6, -0.3]},
                        {"name": "right", "max_thrust": 300.0, "position": [-1.5, -0.6, -0.3],
                         "steerable": True, "max_angle_deg": 30.0}]},
        {"name": "sensed", "initial_pose": {"position": [0.0, 20.0, 0.0]},
         "sensors": [{"type": "imu"}, {"type": "gnss"}, {"type": "odometry"}]},
    ],
}


@pytest.fixture
def ros(ros_context):
    """The test's own context (tests/conftest.py: a domain of this xdist worker's own)."""
    return ros_context


def _node(context, scenario, sink):
    """A dynamics node whose tap appends (simulation time, topic, bytes) to ``sink``."""
    clock = SimClock(rate_hz=100.0)
    node = DynamicsNode(scenario, clock, context=context, name="resumed_test",
                        tap=Tap(lambda topic, _type, data: sink.append((clock.t, topic, data))))
    node.sea = scenario.sea
    return node, node.advance


def _send(node, topic: str, value: float) -> None:
    """A command as a subscriber receives it: the node's own subscription callback."""
    sub, = (s for s in node.subscriptions if s.topic_name == topic)
    sub.callback(Float64(data=value))


def _commands(node, k):
    """The same commands to both nodes at step k: thrust, a thruster, a steering angle."""
    if k == 20:
        _send(node, "/plain/cmd_thrust", 0.6)
        _send(node, "/plain/cmd_rudder", 0.2)
    if k == 130:  # just before the snapshot: must survive it
        _send(node, "/twin/thrusters/right/thrust", 0.9)
        _send(node, "/twin/thrusters/right/angle", 0.3)
    if k == 170:
        _send(node, "/twin/cmd_thrust", -0.4)


def test_a_resumed_node_publishes_what_the_first_one_would_have(ros, tmp_path):
    scenario = init_scenario(parse_scenario(SCENARIO))
    first, resumed = [], []
    a, step_a = _node(ros, scenario, first)
    b = None
    try:
        for k in range(1, 251):
            _commands(a, k)
            step_a()
            if k == 150:
                save(tmp_path / "shard.npz", a.snapshot())
                assert a.set_parameters([rclpy.parameter.Parameter(
                    "sensed.control_mode", value="kinematic")])[0].successful
                save(tmp_path / "shard.npz", a.snapshot())  # the mode is part of it
                b, step_b = _node(ros, scenario, resumed)
                b.restore(load(tmp_path / "shard.npz"))
                assert b.get_parameter("sensed.control_mode").value == "kinematic"
                assert b.commands_received == a.commands_received == 4
            elif k > 150:
                _commands(b, k)
                step_b()
        after = [m for m in first if m[0] > 1.5]
        assert len(after) > 1000 and after == [m for m in resumed if m[0] > 1.5]
        topics = {topic for _, topic, _ in after}
        assert {"/plain/odom", "/twin/odom", "/sensed/imu/data", "/sensed/gnss/fix",
                "/sensed/odometry", "/diagnostics"} <= topics
    finally:
        a.destroy_node()
        if b is not None:
            b.destroy_node()


def test_a_snapshot_of_other_boats_or_no_snapshot_at_all_is_refused(ros, tmp_path):
    scenario = init_scenario(parse_scenario(SCENARIO))
    other = init_scenario(parse_scenario({**SCENARIO, "boats": SCENARIO["boats"][:2]}))
    node, _ = _node(ros, scenario, [])
    small, _ = _node(ros, other, [])
    try:
        save(tmp_path / "two.npz", small.snapshot())
        with pytest.raises(SnapshotError, match="boats: the snapshot's are"):
            node.restore(load(tmp_path / "two.npz"))
        (tmp_path / "junk.npz").write_bytes(b"\x00not a zip" * 10)
        with pytest.raises(SnapshotError, match=r"junk\.npz: not a boatsim snapshot"):
            load(tmp_path / "junk.npz")
        with pytest.raises(SnapshotError, match="no snapshot there"):
            load(tmp_path / "missing.npz")
        snapshot = node.snapshot()
        snapshot["state.position"] = np.zeros((2, 3))
        with pytest.raises(SnapshotError, match=r"state.position: f\[2, 3\] in the snapshot"):
            node.restore(snapshot)
    finally:
        node.destroy_node()
        small.destroy_node()
