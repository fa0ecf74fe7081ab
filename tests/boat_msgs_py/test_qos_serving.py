"""The subscription QoS `topic echo` and `hz` choose: one every publisher can serve."""

from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

from boat_msgs_py.qos import STATE_QOS, WAVE_FIELD_QOS, serving


def test_reliable_and_latched_only_when_every_publisher_is():
    latched = serving([WAVE_FIELD_QOS])  # /ocean/wave_field: a late subscriber gets it
    assert (latched.reliability, latched.durability) == (ReliabilityPolicy.RELIABLE,
                                                         DurabilityPolicy.TRANSIENT_LOCAL)
    mixed = serving([WAVE_FIELD_QOS, STATE_QOS])
    assert (mixed.reliability, mixed.durability) == (ReliabilityPolicy.RELIABLE,
                                                     DurabilityPolicy.VOLATILE)
    none = serving([])
    assert (none.reliability, none.durability) == (ReliabilityPolicy.BEST_EFFORT,
                                                   DurabilityPolicy.VOLATILE)
