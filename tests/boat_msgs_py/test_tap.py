"""Tapped publishers: what is recorded, and the messages built only while someone listens."""

import os
import time

import pytest
import rclpy
from std_msgs.msg import Float64

from boat_msgs_py.qos import STATE_QOS
from boat_msgs_py.tap import SUBSCRIBER_CHECK_PERIOD, GraphWatch, Tap, TappedPublisher


@pytest.fixture
def node(ros_context):
    """A node of the test's own context (a domain of this xdist worker's own)."""
    made = rclpy.create_node("tap_test", context=ros_context)
    yield made
    made.destroy_node()


def test_an_optional_topic_is_wanted_once_someone_subscribes(node):
    topic = f"/tap_test_{os.getpid()}"
    pub = TappedPublisher(node, Float64, topic, STATE_QOS)
    now = 1000.0
    assert not pub.wanted(now)  # nobody listens: nothing to build
    node.create_subscription(Float64, topic, lambda msg: None, 10)
    assert not pub.wanted(now + 0.5 * SUBSCRIBER_CHECK_PERIOD)  # asked once a period only
    deadline = time.monotonic() + 10
    while not pub.wanted(now := now + SUBSCRIBER_CHECK_PERIOD):  # once it has matched
        assert time.monotonic() < deadline, "the subscription never matched"
        time.sleep(0.01)

def test_a_recorded_topic_is_always_wanted_and_tapped(node):
    seen = []
    tap = Tap(lambda topic, msgtype, data: seen.append((topic, msgtype, len(data))))
    pub = TappedPublisher(node, Float64, f"/tap_rec_{os.getpid()}", STATE_QOS, tap)
    assert pub.wanted(0.0)
    pub.publish(Float64(data=1.5))
    assert seen == [(f"/tap_rec_{os.getpid()}", "std_msgs/msg/Float64", 12)]


def test_a_publisher_made_on_subscription_is_advertised_once_someone_subscribes(node):
    topic = f"/tap_lazy_{os.getpid()}"
    seen = []
    tap = Tap(lambda topic, msgtype, data: seen.append(topic))
    pub = TappedPublisher(node, Float64, topic, STATE_QOS, tap, graph=GraphWatch(node))
    now = 1000.0
    assert pub.wanted(now)  # recorded all the same
    pub.publish(Float64(data=2.0))
    pub.publish_untapped(Float64(data=2.0))
    assert seen == [topic]
    assert node.count_publishers(topic) == 0  # not advertised: no DDS endpoint yet
    node.create_subscription(Float64, topic, lambda msg: None, 10)
    deadline = time.monotonic() + 10
    while node.count_publishers(topic) == 0:  # made once the graph shows the subscriber
        assert time.monotonic() < deadline, "the publisher was never made"
        pub.wanted(now := now + SUBSCRIBER_CHECK_PERIOD)
        time.sleep(0.01)
    assert node.count_publishers(topic) == 1
    untapped = TappedPublisher(node, Float64, f"{topic}_b", STATE_QOS,
                               graph=GraphWatch(node))
    assert not untapped.wanted(now)  # neither recorded nor subscribed: nothing to build
    assert node.count_publishers(f"{topic}_b") == 0
