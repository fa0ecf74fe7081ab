"""`compare`: every field that moved, farthest outside first; arrays and clouds as numbers."""

import struct

import numpy as np
import pytest
from nav_msgs.msg import Odometry
from rclpy.serialization import serialize_message
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from sensor_msgs.msg import PointCloud2, PointField

from boat_dynamics.cli import main
from boat_dynamics.tools.bags import compare_bags, flatten


def _bag(path, topic, msgtype, msgs, seconds=None):
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection(topic, msgtype, typestore=store)
        for i, msg in enumerate(msgs):
            msg.header.stamp.sec = i if seconds is None else seconds[i]
            writer.write(conn, i * 1_000_000_000, serialize_message(msg))
    return path


def _odom(x=0.0, vx=0.0, child="base_link", covariance=None):
    msg = Odometry(child_frame_id=child)
    msg.header.frame_id = "world"
    msg.pose.pose.position.x, msg.twist.twist.linear.x = x, vx
    if covariance is not None:
        msg.pose.covariance = covariance
    return msg


def test_every_moved_field_is_reported_farthest_outside_its_tolerance_first(tmp_path):
    a = _bag(tmp_path / "a", "/odom", "nav_msgs/msg/Odometry", [_odom() for _ in range(4)])
    b = _bag(tmp_path / "b", "/odom", "nav_msgs/msg/Odometry",
             [_odom(), _odom(x=3.3), _odom(vx=1e-3, child="alpha/base_link"), _odom()])
    result = compare_bags(a, b, tolerances={"*.position.*": 0.01})
    assert not result.ok
    fields = [f for f in result.topics[0].fields if f.max_abs > 0]
    # text: inf outside; twist: 1e-3 against 1e-9 (1e6 x); position: 3.3 against 0.01 (330 x)
    assert [f.field for f in fields] == ["child_frame_id", "twist.twist.linear.x",
                                         "pose.pose.position.x"]
    assert fields[0].texts == ("base_link", "alpha/base_link") and fields[0].stamp_ns == 2e9
    assert fields[2].max_abs == pytest.approx(3.3) and fields[2].stamp_ns == 1e9
    report = result.report()
    assert "child_frame_id: differs at t = 2.000 s: A 'base_link', B 'alpha/base_link'" in report
    assert "pose.pose.position.x: max |a - b| = 3.3 at t = 1.000 s (tolerance 0.01)" in report
    assert "inf" not in report
    short = result.report(max_fields=1)
    assert "pose.pose.position.x" not in short
    assert "... 2 more fields moved (2 outside their tolerance)" in short


def test_numeric_arrays_are_compared_element_by_element(tmp_path):
    cov = [0.0] * 36
    moved = list(cov)
    moved[7] = 0.25
    a = _bag(tmp_path / "a", "/odom", "nav_msgs/msg/Odometry", [_odom(covariance=cov)])
    b = _bag(tmp_path / "b", "/odom", "nav_msgs/msg/Odometry", [_odom(covariance=moved)])
    (worst,) = [f for f in compare_bags(a, b).topics[0].fields if f.max_abs > 0]
    assert (worst.field, worst.index, worst.max_abs) == ("pose.covariance", 7, 0.25)
    assert "pose.covariance[7]: max |a - b| = 0.25" in compare_bags(a, b).report()


def _cloud(z, padding=b"\x00" * 4):
    """Two float32 fields x, z at offsets 0 and 8 of a 12-byte point; bytes 4..8 unused."""
    msg = PointCloud2(height=1, width=len(z), point_step=12, row_step=12 * len(z),
                      fields=[PointField(name="x", offset=0, datatype=7, count=1),
                              PointField(name="z", offset=8, datatype=7, count=1)])
    msg.data = b"".join(struct.pack("<f", float(i)) + padding + struct.pack("<f", v)
                        for i, v in enumerate(z))
    return msg


def test_a_point_cloud_is_compared_by_its_points_not_its_bytes(tmp_path):
    store = get_typestore(Stores.ROS2_JAZZY)  # as compare reads them: rosbags' messages
    flat = flatten(store.deserialize_cdr(serialize_message(_cloud([0.5, -1.0, 2.0])),
                                         "sensor_msgs/msg/PointCloud2"))
    np.testing.assert_array_equal(flat["points.z"], [0.5, -1.0, 2.0])
    np.testing.assert_array_equal(flat["points.x"], [0.0, 1.0, 2.0])
    a = _bag(tmp_path / "a", "/cloud", "sensor_msgs/msg/PointCloud2", [_cloud([0.5, -1.0, 2.0])])
    b = _bag(tmp_path / "b", "/cloud", "sensor_msgs/msg/PointCloud2",
             [_cloud([0.5, -0.5, 2.0], padding=b"\xff" * 4)])  # other padding: not a change
    moved = [f for f in compare_bags(a, b).topics[0].fields if f.max_abs > 0]
    assert [(f.field, f.index, f.max_abs) for f in moved] == [("points.z", 1, 0.5)]
    same = _bag(tmp_path / "c", "/cloud", "sensor_msgs/msg/PointCloud2",
                [_cloud([0.5, -1.0, 2.0], padding=b"\xff" * 4)])
    assert compare_bags(a, same).ok
    assert "all " in compare_bags(a, same).report()


def test_arrays_of_another_length_differ(tmp_path):
    a = _bag(tmp_path / "a", "/cloud", "sensor_msgs/msg/PointCloud2", [_cloud([1.0, 2.0])])
    b = _bag(tmp_path / "b", "/cloud", "sensor_msgs/msg/PointCloud2", [_cloud([1.0])])
    result = compare_bags(a, b)
    assert not result.ok
    assert any(f.field == "points.z" and f.max_abs == float("inf")
               for f in result.topics[0].fields)


def test_max_fields_must_be_a_whole_number_at_least_zero(tmp_path, capsys):
    a = _bag(tmp_path / "a", "/odom", "nav_msgs/msg/Odometry", [_odom()])
    b = _bag(tmp_path / "b", "/odom", "nav_msgs/msg/Odometry", [_odom(x=1.0, vx=1.0)])
    assert main(["compare", str(a), str(b), "--max-fields", "0"]) == 1
    out = capsys.readouterr().out
    assert "pose.pose.position.x" in out and "twist.twist.linear.x" in out
    with pytest.raises(SystemExit) as exit_:
        main(["compare", str(a), str(b), "--max-fields", "-1"])
    assert exit_.value.code == 2
    assert "'-1': must be at least 0" in capsys.readouterr().err


def test_a_message_with_a_repeated_stamp_is_a_message_too(tmp_path, capsys):
    # B has an extra /odom with the stamp of the one before and x + 100 m: compare said "ok,
    # all 16 fields equal" (exit 0); messages of one stamp are now matched in order
    a = _bag(tmp_path / "a", "/odom", "nav_msgs/msg/Odometry", [_odom() for _ in range(3)])
    b = _bag(tmp_path / "b", "/odom", "nav_msgs/msg/Odometry",
             [_odom(), _odom(), _odom(x=100.0), _odom()], seconds=[0, 1, 1, 2])
    result = compare_bags(a, b)
    (topic,) = result.topics
    assert not result.ok
    assert (topic.matched, topic.only_a, topic.only_b, topic.repeated) == (3, 0, 1, (0, 1))
    assert main(["compare", str(a), str(b)]) == 1
    assert ("/odom: DIFFERENT: 3 messages matched, 1 only in B (repeated stamps: 0 in A, 1 "
            "in B)") in capsys.readouterr().out
    # the same repeats on both sides, in the same order, compare equal
    assert compare_bags(b, b).ok
