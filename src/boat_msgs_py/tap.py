"""Publishers whose serialized messages are also handed to a recorder (a "tap").

Recording at the publisher, in the publishing thread, means nothing the simulation publishes
can be lost by a slow subscriber, and the bag's timestamps are simulation time. Tapped
messages have their CDR padding zeroed, so identical runs give identical bytes.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from rclpy.node import Node
from rclpy.qos import QoSProfile
from rclpy.serialization import serialize_message

from boat_msgs_py.typestore import zero_padding

__all__ = ["SUBSCRIBER_CHECK_PERIOD", "GraphWatch", "Tap", "TappedPublisher", "type_name"]

#: How often a publisher whose messages are optional asks whether anyone subscribes, s (wall).
SUBSCRIBER_CHECK_PERIOD = 1.0


def type_name(msg_class: type) -> str:
    """ROS type string of a message class, e.g. ``nav_msgs/msg/Odometry``."""
    pkg = msg_class.__module__.split(".")[0]
    return f"{pkg}/msg/{msg_class.__name__}"


class Tap:
    """Where tapped publishers send their serialized messages.

    Args:
        sink: called with (topic, type string, serialized CDR bytes) for every message.
    """

    def __init__(self, sink: Callable[[str, str, bytes], None]) -> None:
        self.sink = sink
        self.topics: set[str] = set()
        self.qos: dict[str, QoSProfile] = {}  # offered QoS per tapped topic


class GraphWatch:
    """The topics the ROS graph knows, asked at most every :data:`SUBSCRIBER_CHECK_PERIOD` s.

    For publishers made only once someone subscribes (:class:`TappedPublisher` ``graph``):
    one graph query a period for all of them.

    Args:
        node: the node whose view of the graph to ask.
    """

    def __init__(self, node: Node) -> None:
        self._node = node
        self._topics: frozenset[str] = frozenset()
        self._next_check = -math.inf

    def has(self, topic: str, now: float) -> bool:
        """Whether any endpoint (a subscriber, say) is on ``topic``.

        Args:
            topic: absolute topic name.
            now: s, the wall clock (time.monotonic()).
        """
        if now >= self._next_check:
            self._topics = frozenset(name for name, _ in self._node.get_topic_names_and_types())
            self._next_check = now + SUBSCRIBER_CHECK_PERIOD
        return topic in self._topics


class TappedPublisher:
    """A publisher that also hands each serialized message to a :class:`Tap`.

    Args:
        node: the owning node.
        msg_class: message type.
        topic: absolute topic name.
        qos: QoS profile.
        tap: where to send messages, or None for a plain publisher.
        graph: make the DDS publisher only once this sees an endpoint on ``topic`` (a
            subscriber); until then messages go to the tap alone. None = make it now.
    """

    def __init__(self, node: Node, msg_class: type, topic: str, qos: QoSProfile,
                 tap: Tap | None = None, graph: GraphWatch | None = None) -> None:
        self.topic = topic
        self._subscribed = True  # until first asked
        self._next_check = -math.inf
        self._graph = graph
        self._make = lambda: node.create_publisher(msg_class, topic, qos)
        self._pub = self._make() if graph is None else None
        self._type = type_name(msg_class)
        self._tap = tap
        if tap is not None:
            tap.topics.add(topic)
            tap.qos[topic] = qos

    def wanted(self, now: float) -> bool:
        """Whether a message on this topic is worth building now.

        True when the tap records it or a subscriber has matched. The subscriber count is
        asked at most every :data:`SUBSCRIBER_CHECK_PERIOD` s, so a new subscriber may wait
        that long for its first message.

        Args:
            now: s, the wall clock (time.monotonic()).
        """
        if self._pub is None:  # not advertised yet: is anyone on the topic now?
            if not self._graph.has(self.topic, now):
                return self._tap is not None
            self._pub = self._make()
        if self._tap is not None:
            return True
        if now >= self._next_check:
            self._subscribed = self._pub.get_subscription_count() > 0
            self._next_check = now + SUBSCRIBER_CHECK_PERIOD
        return self._subscribed

    def publish(self, msg: object) -> None:
        """Publish ``msg``, a message or its serialized bytes (and hand it to the tap)."""
        if self._tap is None:
            if self._pub is not None:
                self._pub.publish(msg)
            return
        # bytes come from a CdrTemplate, whose padding is zero; a bag holds the same bytes for
        # the same values (byte-identical bags of identical runs)
        data = msg if isinstance(msg, bytes) else zero_padding(serialize_message(msg),
                                                                self._type)
        if self._pub is not None:
            self._pub.publish(data)
        self._tap.sink(self.topic, self._type, data)

    def publish_untapped(self, msg: object) -> None:
        """Publish ``msg`` without handing it to the tap (a repeat the bag must not hold)."""
        if self._pub is not None:
            self._pub.publish(msg)
