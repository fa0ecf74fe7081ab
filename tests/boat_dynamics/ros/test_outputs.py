"""The fleet publisher packs every boat's messages of a kind at once: each boat gets its own.

An in-process node stepped by the test, its messages read from its tap (no ROS graph).
"""

from geometry_msgs.msg import WrenchStamped
from rclpy.serialization import deserialize_message

from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.ros.node import DynamicsNode, SimClock
from boat_msgs_py import names
from boat_msgs_py.tap import Tap

# names of several lengths: their messages have several layouts (FleetTemplate groups)
SCENARIO = {
    "ocean": {"spectrum": {"significant_height": 0.8, "peak_period": 5.0, "components": 8}},
    "boats": [{"name": name, "initial_pose": {"position": [20.0 * i, 0.0, 0.0]}}
              for i, name in enumerate(("a", "bravo", "c", "delta2"))],
}


def test_every_boats_wrench_of_every_source_is_its_own(ros_context):
    """wrench/<source>: every source of every boat packed in one pass, each to its topic."""
    scenario = init_scenario(parse_scenario(SCENARIO))
    clock, sent = SimClock(rate_hz=100.0), {}
    node = DynamicsNode(scenario, clock, context=ros_context, name="outputs_test",
                        tap=Tap(lambda topic, _type, data: sent.__setitem__(topic, data)))
    node.sea = scenario.sea
    try:
        for _ in range(10):  # to the first step /diagnostics and the wrenches are due at
            node.advance()
        for b, spec in enumerate(scenario.boats):
            for source in names.WRENCH_SOURCES:
                msg = deserialize_message(sent[names.wrench_topic(spec.name, source)],
                                          WrenchStamped)
                wrench = getattr(node._forces, source)
                force, torque = msg.wrench.force, msg.wrench.torque
                assert [force.x, force.y, force.z, torque.x, torque.y, torque.z] == [
                    *wrench.force[b].tolist(), *wrench.torque[b].tolist()], (spec.name, source)
                assert msg.header.frame_id == names.child_frame(spec.name)
                assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (0, 100_000_000)
    finally:
        node.destroy_node()
