"""tf2_msgs built from the upstream definitions, and the sensor and transform messages."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import tf2_msgs
from rosbags.typesys import Stores, get_typestore

from boat_dynamics.physics.sensors import (
    DepthReading,
    DepthSounderSpec,
    GnssReading,
    ImuReading,
    MagnetometerReading,
)
from boat_msgs_py.convert import (
    UNMEASURED_VARIANCE,
    depth_range,
    gnss_heading,
    gnss_velocity,
    imu,
    magnetic_field,
    nav_sat_fix,
    seconds_to_time,
    tf_message,
)


@pytest.mark.parametrize("name", ["TFMessage", "TF2Error"])
def test_tf2_msgs_has_the_type_hashes_of_ros_2_jazzy(name):
    # ros2_ws/src/tf2_msgs holds the upstream definitions (ros2/geometry2, jazzy): its type
    # hashes, as rosidl generated them, equal those of the Jazzy release (rosbags' store, made
    # from the released packages), so RViz, Foxglove and tf2 on a ROS install take our /tf
    share = Path(tf2_msgs.__file__).resolve().parents[4] / "share" / "tf2_msgs" / "msg"
    described = json.loads((share / f"{name}.json").read_text())
    ours = {h["type_name"]: h["hash_string"] for h in described["type_hashes"]}
    store = get_typestore(Stores.ROS2_JAZZY)
    assert ours[f"tf2_msgs/msg/{name}"] == store.hash_rihs01(f"tf2_msgs/msg/{name}")


def test_transforms_imu_and_fix_carry_the_readings():
    stamp = seconds_to_time(1.5)
    tf = tf_message(stamp, [("world", "alpha/base_link", [1.0, 2.0, 3.0], [0, 0, 0.6, 0.8])])
    (t,) = tf.transforms
    assert (t.header.frame_id, t.child_frame_id, t.header.stamp) == ("world", "alpha/base_link",
                                                                       stamp)
    assert (t.transform.translation.y, t.transform.rotation.z) == (2.0, 0.6)
    reading = ImuReading(np.array([0, 0, 0, 1.0]), np.array([0.1, 0.2, 0.3]),
                         np.array([0, 0, 9.81]), np.eye(3) * 1e-6, np.eye(3) * 2e-6,
                         np.eye(3) * 3e-6)
    m = imu(stamp, "alpha/imu_link", reading)
    assert m.header.frame_id == "alpha/imu_link"
    assert (m.angular_velocity.z, m.linear_acceleration.z) == (0.3, 9.81)
    assert list(m.linear_acceleration_covariance)[::4] == [3e-6] * 3
    fix = GnssReading(math.radians(45.0), math.radians(-4.0), 12.0, np.diag([1.0, 2.0, 3.0]),
                      np.array([1.0, -2.0, 0.5]), np.eye(3) * 0.01)
    f = nav_sat_fix(stamp, "alpha/gnss_link", fix)
    assert (f.latitude, f.longitude, f.altitude) == pytest.approx((45.0, -4.0, 12.0))
    assert f.status.status == 0 and f.position_covariance_type == 2  # FIX, DIAGONAL_KNOWN
    assert list(f.position_covariance)[::4] == [1.0, 2.0, 3.0]
    v = gnss_velocity(stamp, fix)
    assert (v.twist.twist.linear.x, v.twist.twist.linear.y) == (1.0, -2.0)
    assert v.header.frame_id == "world"  # the frame the ENU twist is in, not the antenna's
    assert list(v.twist.covariance)[::7] == [0.01, 0.01, 0.01] + [UNMEASURED_VARIANCE] * 3
    assert np.linalg.eigvalsh(np.reshape(v.twist.covariance, (6, 6))).min() >= 0.0
    lost = nav_sat_fix(stamp, "alpha/gnss_link", fix, fix=False)  # an outage
    assert lost.status.status == -1 and lost.position_covariance_type == 0  # NO_FIX, UNKNOWN
    assert math.isnan(lost.latitude) and math.isnan(lost.longitude)


def test_a_magnetic_field_message_carries_tesla_in_the_sensor_frame():
    reading = MagnetometerReading(np.array([2.3e-5, 1e-7, -4.1e-5]), np.eye(3) * 1e-14)
    m = magnetic_field(seconds_to_time(2.0), "alpha/compass_link", reading)
    assert m.header.frame_id == "alpha/compass_link" and m.header.stamp.sec == 2
    assert (m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z) == (2.3e-5, 1e-7, -4.1e-5)
    assert list(m.magnetic_field_covariance) == [1e-14, 0, 0, 0, 1e-14, 0, 0, 0, 1e-14]


def test_a_range_message_carries_the_sounder_s_cone_limits_and_reading():
    spec = DepthSounderSpec(field_of_view=0.2, min_range=0.5, max_range=100.0, range_sigma=0.1)
    m = depth_range(seconds_to_time(1.0), "alpha/echo_link", spec, DepthReading(12.25, 0.01))
    assert (m.header.frame_id, m.radiation_type) == ("alpha/echo_link", 0)  # ULTRASOUND
    assert (m.field_of_view, m.min_range, m.max_range, m.range) == pytest.approx(
        (0.2, 0.5, 100.0, 12.25))
    assert m.variance == pytest.approx(0.01)
    deep = depth_range(seconds_to_time(1.0), "alpha/echo_link", spec,
                       DepthReading(math.inf, 0.01))
    assert deep.range == math.inf  # REP-117: no echo within max_range


def test_a_gnss_heading_is_an_imu_message_of_yaw_alone():
    m = gnss_heading(seconds_to_time(1.0), "alpha/gnss_link", math.radians(30.0), 0.01)
    assert m.header.frame_id == "alpha/gnss_link"
    q = m.orientation
    assert (q.x, q.y) == (0.0, 0.0)
    assert 2 * math.atan2(q.z, q.w) == pytest.approx(math.radians(30.0))
    assert list(m.orientation_covariance)[::4] == [UNMEASURED_VARIANCE, UNMEASURED_VARIANCE,
                                                   pytest.approx(1e-4)]
    # REP-145 / sensor_msgs/Imu: -1 first: no angular velocity, no acceleration
    assert m.angular_velocity_covariance[0] == m.linear_acceleration_covariance[0] == -1.0


def test_thruster_topics_are_commands_a_replay_republishes():
    from boat_msgs_py import names

    assert names.thruster_topic("otter", "left", names.THRUSTER_THRUST) == (
        "/otter/thrusters/left/thrust")
    assert names.thruster_topic("", "jet", names.THRUSTER_ANGLE) == "/thrusters/jet/angle"
    for topic in ("/cmd_thrust", "/a/cmd_rudder", "/otter/thrusters/left/thrust",
                  "/thrusters/jet/angle"):
        assert names.is_command_topic(topic)
    for topic in ("/odom", "/a/thrusters/left", "/a/thrusters//thrust", "/a/thrust"):
        assert not names.is_command_topic(topic)
