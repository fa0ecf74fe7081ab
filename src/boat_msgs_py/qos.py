"""Named QoS profiles of the boatsim interface.

Publishers are RELIABLE so that subscribers created with the rclpy default (reliable, depth
10) and best-effort ones (RViz, sensor-data QoS) both connect.
"""

from __future__ import annotations

from rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    QoSProfile,
    ReliabilityPolicy,
    qos_profile_parameter_events,
)

__all__ = [
    "CLOCK_QOS",
    "COLLISION_QOS",
    "COMMAND_QOS",
    "DIAGNOSTICS_QOS",
    "ENVIRONMENT_QOS",
    "PARAMETER_EVENTS_QOS",
    "RECORD_QOS",
    "SENSOR_QOS",
    "STATE_QOS",
    "STEP_DONE_QOS",
    "STEP_GRANT_QOS",
    "SURFACE_QOS",
    "TF_QOS",
    "TF_STATIC_QOS",
    "WAVE_FIELD_QOS",
    "WORLD_QOS",
    "latched",
    "serving",
]

#: cmd_thrust / cmd_rudder subscriptions: reliable, last 10; matches a plain
#: ``create_publisher(Float64, "/cmd_thrust", 10)``.
COMMAND_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=10,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)

#: odom / pose / twist: reliable, last 10, volatile.
STATE_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=10,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)

#: wrench/* topics: reliable, last 10, volatile.
DIAGNOSTICS_QOS = STATE_QOS

#: /ocean/wave_field: reliable and transient-local, so late joiners get the current sea.
WAVE_FIELD_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL,
)

#: /ocean/environment: as /ocean/wave_field (a late joiner gets the current and wind).
ENVIRONMENT_QOS = WAVE_FIELD_QOS
#: /clock: reliable, last 1 (serves rclpy's best-effort time source subscription too).
CLOCK_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)

#: /ocean/surface point clouds: reliable, last 1 (a viewer wants the latest surface only).
SURFACE_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)

#: /tf: reliable, last 100, volatile: tf2_ros's ``DynamicBroadcasterQoS`` and listener.
TF_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=100,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)
#: /tf_static: reliable, transient-local, last 1: tf2_ros's ``StaticBroadcasterQoS`` (a late
#: listener gets the sensors' mounting transforms).
TF_STATIC_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
#: <ns>/collision events: reliable, last 100, volatile (a bounce makes two a step apart).
COLLISION_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=100,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)
#: /world/markers: as /tf_static (reliable, transient-local, last 1): the obstacles, once.
WORLD_QOS = TF_STATIC_QOS
#: <ns>/<imu>/data, <ns>/<gnss>/fix and vel: reliable, last 10, volatile (best-effort
#: sensor-data subscribers connect too).
SENSOR_QOS = STATE_QOS
#: /parameter_events, as rclpy publishes it (reliable, last 1000, volatile).
PARAMETER_EVENTS_QOS = qos_profile_parameter_events
#: /boatsim/step_grant: reliable, transient-local, last 1 (a late dynamics process gets the
#: current grant; each grant replaces the one before).
STEP_GRANT_QOS = WAVE_FIELD_QOS
#: /boatsim/step_done: reliable, last 100 (reports are cumulative: the latest is what counts).
STEP_DONE_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=100,
    reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
)
#: A recorder's subscriptions: reliable, a deep queue (a busy recorder must not drop).
RECORD_QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)


def latched(qos: QoSProfile) -> QoSProfile:
    """``qos`` made transient-local: a late subscriber to a latched topic gets its last message."""
    return QoSProfile(depth=qos.depth, reliability=qos.reliability,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL)


def serving(offered: list[QoSProfile], depth: int = 10) -> QoSProfile:
    """A subscription QoS every one of ``offered`` (the publishers') can serve.

    As ``ros2 topic echo`` chooses it: reliable if every publisher is, transient-local if
    every one is (a latched topic then reaches a late subscriber), else best effort and
    volatile.
    """
    reliable = bool(offered) and all(q.reliability == ReliabilityPolicy.RELIABLE
                                     for q in offered)
    latched_all = bool(offered) and all(q.durability == DurabilityPolicy.TRANSIENT_LOCAL
                                        for q in offered)
    return QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE if reliable
                      else ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL if latched_all
                      else DurabilityPolicy.VOLATILE)
