"""Canonical CDR bytes: zero_padding keeps every value and the length, and zeroes padding.

rclpy leaves CDR alignment padding uninitialized; two identical runs gave bags that differed
in those bytes. Every message type boatsim publishes goes through zero_padding when recorded,
and the high-rate templates are zeroed once.
"""

import pytest
from boat_msgs.msg import Environment, WaveComponent, WaveField
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import TransformStamped, TwistWithCovarianceStamped, WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.serialization import deserialize_message, serialize_message
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, NavSatFix, PointCloud2, PointField
from tf2_msgs.msg import TFMessage

from boat_msgs_py.cdr import (
    clock_template,
    odometry_template,
    pose_template,
    tf_template,
    twist_template,
    wrench_template,
)
from boat_msgs_py.tap import type_name
from boat_msgs_py.typestore import zero_padding


def _odometry() -> Odometry:
    msg = Odometry()
    msg.header.frame_id = "world"
    msg.child_frame_id = "alpha/base_link"
    msg.pose.pose.position.x = 1.5
    msg.twist.covariance[7] = 0.25
    return msg


MESSAGES = [
    _odometry(),
    TFMessage(transforms=[TransformStamped(child_frame_id="a/base_link")] * 3),
    DiagnosticArray(status=[DiagnosticStatus(level=b"\x01", name="alpha", message="ok",
                                             values=[KeyValue(key="k", value="v")])]),
    Imu(), NavSatFix(), TwistWithCovarianceStamped(), WrenchStamped(), Clock(),
    PointCloud2(height=1, width=3, point_step=4, row_step=12, data=bytes(range(12)),
                fields=[PointField(name="z", offset=0, datatype=7, count=1)]),
    WaveField(components=[WaveComponent(amplitude=0.3, wavelength=20.0)]),
    Environment(),
]


@pytest.mark.parametrize("msg", MESSAGES, ids=lambda m: type(m).__name__)
def test_zero_padding_keeps_every_value_and_the_length(msg):
    data = serialize_message(msg)
    canonical = zero_padding(data, type_name(type(msg)))
    assert deserialize_message(canonical, type(msg)) == msg
    assert len(canonical) == len(data)
    assert zero_padding(canonical, type_name(type(msg))) == canonical


def test_the_padding_after_odometry_frame_ids_is_zero():
    # CDR (little endian, 4-byte encapsulation header, alignment counted after it):
    # header.stamp at 4..12, frame_id "world\0" as length 12..16 and text 16..22, padding
    # 22..24 before child_frame_id's length (4-aligned); its text "alpha/base_link\0" at
    # 28..44, then padding 44..48 before the 8-aligned pose doubles.
    data = zero_padding(serialize_message(_odometry()), "nav_msgs/msg/Odometry")
    assert data[16:22] == b"world\0" and data[28:44] == b"alpha/base_link\0"
    assert data[22:24] == b"\0\0" and data[44:48] == b"\0\0\0\0"


@pytest.mark.parametrize(("make", "msgtype"), [
    (lambda: odometry_template("world", "alpha/base_link"), "nav_msgs/msg/Odometry"),
    (lambda: pose_template("world"), "geometry_msgs/msg/PoseStamped"),
    (lambda: twist_template("world"), "geometry_msgs/msg/TwistStamped"),
    (lambda: wrench_template("alpha/base_link"), "geometry_msgs/msg/WrenchStamped"),
    (clock_template, "rosgraph_msgs/msg/Clock"),
    (lambda: tf_template("world", "alpha/base_link"), "tf2_msgs/msg/TFMessage"),
], ids=lambda v: v if isinstance(v, str) else "")
def test_template_bytes_are_already_canonical(make, msgtype):
    template = make()
    n = sum(count for _, _, count in template._runs)
    data = template.pack(3, 4, *[0.1 * k for k in range(n - 2)])
    assert zero_padding(data, msgtype) == data
