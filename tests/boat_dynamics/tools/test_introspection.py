"""`boatsim topic hz`'s figures, from arrival times given by the test (no wall clock)."""

from boat_dynamics.tools.introspection import TopicRate


def test_the_rate_and_its_spread_over_the_window():
    rate = TopicRate(window=4)
    assert rate.report() is None
    for t in (0.0, 0.02, 0.04, 0.06, 0.10, 0.12):  # the first two fall out of the window
        rate.arrived(t)
    # intervals kept: 0.02, 0.02, 0.04, 0.02 -> mean 0.025 s, 40 Hz
    assert rate.report() == ("average rate: 40.000\n\tmin: 0.020s max: 0.040s "
                             "std dev: 0.00866s window: 5")


class _Info:
    def __init__(self, qos) -> None:
        self.qos_profile = qos


class _Graph:
    """A node whose topic's publisher is discovered only at the third look."""

    def __init__(self, qos) -> None:
        self.looks, self._qos = 0, qos

    def get_publishers_info_by_topic(self, topic):
        self.looks += 1
        return [_Info(self._qos)] if self.looks >= 3 else []


class _NoWaitExecutor:
    def spin_once(self, timeout_sec):
        pass


def test_a_latched_topic_seen_first_by_its_subscriptions_gets_a_latched_subscription():
    """CI: `echo /ocean/wave_field --once` chose QoS before the ocean's publisher was known."""
    from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

    from boat_dynamics.tools.introspection import Session, _matching_qos
    from boat_msgs_py.qos import WAVE_FIELD_QOS

    graph = _Graph(WAVE_FIELD_QOS)
    qos = _matching_qos(Session(graph, _NoWaitExecutor()), "/ocean/wave_field", wait=5.0)
    assert graph.looks >= 3
    assert qos.durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert qos.reliability == ReliabilityPolicy.RELIABLE


def test_a_topic_without_publishers_is_waited_for_then_subscribed_best_effort():
    from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

    from boat_dynamics.tools.introspection import Session, _matching_qos

    class Empty:
        def get_publishers_info_by_topic(self, topic):
            return []

    qos = _matching_qos(Session(Empty(), _NoWaitExecutor()), "/nobody", wait=0.05)
    assert qos.durability == DurabilityPolicy.VOLATILE
    assert qos.reliability == ReliabilityPolicy.BEST_EFFORT


def test_topic_pub_refuses_values_nested_deeper_than_a_scenario_may_be():
    """100,000 levels of YAML in VALUES: RecursionError in PyYAML's composer before."""
    import io

    import pytest

    from boat_dynamics.tools.introspection import IntrospectionError, Session, topic_pub

    deep = "{data: " + "[" * 100_000 + "]" * 100_000 + "}"
    with pytest.raises(IntrospectionError, match="VALUES must nest at most 32 levels deep"):
        topic_pub(Session(None, _NoWaitExecutor()), "/x", "std_msgs/msg/Float64", deep,
                  io.StringIO())


def test_topic_pub_refuses_an_alias_fan_out():
    """8 kB of YAML aliases expanding to 9^8 values: 60-99 s in set_fields before."""
    import io

    import pytest

    from boat_dynamics.tools.introspection import IntrospectionError, Session, topic_pub

    rows = ["a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1]"]
    rows += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 9)]
    values = "{" + ", ".join(rows) + ", data: 1.0}"
    with pytest.raises(IntrospectionError, match="VALUES must hold at most 200000 values"):
        topic_pub(Session(None, _NoWaitExecutor()), "/x", "std_msgs/msg/Float64", values,
                  io.StringIO())
