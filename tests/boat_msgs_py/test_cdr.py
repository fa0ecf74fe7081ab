"""The hand-packed messages are what rclpy serializes (no ROS graph needed).

rclpy leaves CDR alignment padding uninitialized, so serialized bytes are compared through
deserialization (every field) and length, not byte for byte.
"""

import math
import struct

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rclpy.serialization import deserialize_message, serialize_message

from boat_msgs_py.cdr import (
    CdrTemplate,
    TemplateError,
    clock_template,
    odometry_template,
    pose_template,
    stamp_parts,
    tf_template,
    twist_template,
    wrench_template,
)
from boat_msgs_py.convert import (
    odometry,
    pose_stamped,
    seconds_to_time,
    tf_message,
    twist_stamped,
)
from boat_msgs_py.convert import wrench_stamped as wrench_msg


def same(data: bytes, msg) -> None:
    """``data`` is ``msg`` serialized: equal after deserialization, and as long."""
    assert deserialize_message(data, type(msg)) == msg
    assert len(data) == len(serialize_message(msg))


finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
frames = st.sampled_from(["", "world", "alpha/base_link", "a_very_long_frame_name/base_link"])
seconds = st.floats(min_value=0.0, max_value=2.0e9, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(frames, frames, seconds, st.lists(finite, min_size=13, max_size=13))
def test_odometry_pose_twist_equal_rclpy_serialization(frame, child, t, v):
    sec, nanosec = stamp_parts(t)
    stamp = seconds_to_time(t)
    assert (stamp.sec, stamp.nanosec) == (sec, nanosec)
    msg = odometry(stamp, child, v[0:3], v[3:7], v[7:10], v[10:13])
    msg.header.frame_id = frame
    same(odometry_template(frame, child).pack(sec, nanosec, *v), msg)
    same(pose_template(frame).pack(sec, nanosec, *v[:7]), pose_stamped(msg))
    same(twist_template(child).pack(sec, nanosec, *v[7:]), twist_stamped(msg))


@settings(max_examples=60, deadline=None)
@given(frames, seconds, st.lists(finite, min_size=6, max_size=6))
def test_wrench_and_clock_equal_rclpy_serialization(frame, t, v):
    from geometry_msgs.msg import WrenchStamped
    from rosgraph_msgs.msg import Clock

    sec, nanosec = stamp_parts(t)
    msg = wrench_msg(seconds_to_time(t), frame, v[:3], v[3:])
    data = wrench_template(frame).pack(sec, nanosec, *v)
    same(data, msg)
    back = deserialize_message(data, WrenchStamped)
    assert [back.wrench.force.x, back.wrench.torque.z] == [v[0], v[5]]
    same(clock_template().pack(sec, nanosec), Clock(clock=seconds_to_time(t)))


@settings(max_examples=60, deadline=None)
@given(frames, frames, seconds, st.lists(finite, min_size=7, max_size=7))
def test_tf_equals_rclpy_serialization(parent, child, t, v):
    sec, nanosec = stamp_parts(t)
    msg = tf_message(seconds_to_time(t), [(parent, child, v[:3], v[3:])])
    same(tf_template(parent, child).pack(sec, nanosec, *v), msg)


names_ = st.text(alphabet="ab_/9", min_size=0, max_size=12)


@settings(max_examples=80, deadline=None)
@given(names_, names_, names_, names_, seconds, st.lists(finite, min_size=13, max_size=13))
def test_a_relabelled_template_packs_as_a_fresh_one(frame, child, frame2, child2, t, v):
    """Relabelling (same string lengths: fields kept in place; else located anew) is exact."""
    sec, nanosec = stamp_parts(t)
    assert odometry_template(frame2, child2, like=odometry_template(frame, child)).pack(
        sec, nanosec, *v) == odometry_template(frame2, child2).pack(sec, nanosec, *v)
    assert tf_template(frame2, child2, like=tf_template(frame, child)).pack(
        sec, nanosec, *v[:7]) == tf_template(frame2, child2).pack(sec, nanosec, *v[:7])
    assert wrench_template(child2, like=wrench_template(child)).pack(sec, nanosec, *v[:6]) == (
        wrench_template(child2).pack(sec, nanosec, *v[:6]))
    assert pose_template(frame2, like=pose_template(frame)).pack(sec, nanosec, *v[:7]) == (
        pose_template(frame2).pack(sec, nanosec, *v[:7]))
    assert twist_template(child2, like=twist_template(child)).pack(sec, nanosec, *v[:6]) == (
        twist_template(child2).pack(sec, nanosec, *v[:6]))

def test_stamp_parts_rounds_to_the_nanosecond():
    assert stamp_parts(1.5) == (1, 500_000_000)
    assert stamp_parts(2.9999999999) == (3, 0)
    assert stamp_parts(0.0) == (0, 0)


def test_a_field_that_is_not_there_or_of_another_kind_is_refused():
    from nav_msgs.msg import Odometry

    with pytest.raises(TemplateError, match=r"pose\.pose\.nowhere cannot hold a float64"):
        CdrTemplate(Odometry, (("pose.pose.nowhere", "float64"),))
    with pytest.raises(TemplateError, match=r"position\.x is not a int32"):
        CdrTemplate(Odometry, (("pose.pose.position.x", "int32"),))
    with pytest.raises(TemplateError, match="kind 'float16'"):
        CdrTemplate(Odometry, (("pose.pose.position.x", "float16"),))


def test_pack_writes_only_the_named_fields():
    t = wrench_template("b/base_link")
    zero = t.pack(0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    one = t.pack(0, 0, math.pi, 0.0, 0.0, 0.0, 0.0, 0.0)
    at = one.find(struct.pack("<d", math.pi))
    assert at > 0 and len(zero) == len(one) == t.size
    assert zero[at:at + 8] == bytes(8)
    assert zero[:at] == one[:at] and zero[at + 8:] == one[at + 8:]


texts = st.text(alphabet=st.characters(codec="utf-8", exclude_characters="\x00"), max_size=9)


@settings(max_examples=80, deadline=None)
@given(seconds, st.lists(st.tuples(texts, st.integers(0, 3), texts,
                                   st.lists(st.tuples(texts, texts), max_size=4)),
                         max_size=5))
def test_diagnostic_array_bytes_equal_rclpys_with_zeroed_padding(t, statuses):
    from diagnostic_msgs.msg import DiagnosticArray

    from boat_msgs_py.cdr import diagnostic_array_cdr
    from boat_msgs_py.convert import diagnostic_array
    from boat_msgs_py.typestore import zero_padding

    sec, nanosec = stamp_parts(t)
    msg = diagnostic_array(seconds_to_time(t), statuses)
    data = diagnostic_array_cdr(sec, nanosec, statuses)
    assert data == zero_padding(serialize_message(msg), "diagnostic_msgs/msg/DiagnosticArray")
    assert deserialize_message(data, DiagnosticArray) == msg


@settings(max_examples=40, deadline=None)
@given(st.lists(names_, min_size=1, max_size=6), seconds, st.data())
def test_a_fleet_template_packs_each_boat_as_its_own_template(boats, t, data):
    """Boats of several name lengths (several layouts) in one pass: the same bytes, bit for bit."""
    import numpy as np

    from boat_msgs_py.cdr import FleetTemplate

    sec, nanosec = stamp_parts(t)
    values = np.array(data.draw(st.lists(st.lists(finite, min_size=13, max_size=13),
                                         min_size=len(boats), max_size=len(boats))))
    for make, n in ((lambda b: odometry_template("world", f"{b}/base_link"), 13),
                    (lambda b: pose_template(f"{b}"), 7), (lambda b: twist_template(b), 6),
                    (lambda b: wrench_template(b), 6), (lambda b: tf_template("world", b), 7)):
        templates = [make(b) for b in boats]
        packed = FleetTemplate(templates).pack(sec, nanosec, values[:, :n])
        assert packed == [tp.pack(sec, nanosec, *row) for tp, row in
                          zip(templates, values[:, :n].tolist(), strict=True)]


def test_a_fleet_template_takes_only_a_stamp_then_doubles():
    from nav_msgs.msg import Odometry

    from boat_msgs_py.cdr import FleetTemplate

    unstamped = CdrTemplate(Odometry, [("pose.pose.position.x", "float64")])
    with pytest.raises(TemplateError, match="stamp then float64"):
        FleetTemplate([odometry_template("world", "a"), unstamped])


@settings(max_examples=60, deadline=None)
@given(st.lists(names_, max_size=5), frames, seconds, st.data())
def test_fleet_state_bytes_equal_rclpys_with_zeroed_padding(boats, frame, t, data):
    import numpy as np
    from boat_msgs.msg import FleetState
    from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3

    from boat_msgs_py.cdr import FleetStateTemplate
    from boat_msgs_py.typestore import zero_padding

    sec, nanosec = stamp_parts(t)
    v = np.array(data.draw(st.lists(st.lists(finite, min_size=13, max_size=13),
                                    min_size=len(boats), max_size=len(boats)))).reshape(-1, 13)
    msg = FleetState(names=boats, poses=[Pose(position=Point(x=r[0], y=r[1], z=r[2]),
                                              orientation=Quaternion(x=r[3], y=r[4], z=r[5],
                                                                     w=r[6])) for r in v],
                     twists=[Twist(linear=Vector3(x=r[7], y=r[8], z=r[9]),
                                   angular=Vector3(x=r[10], y=r[11], z=r[12])) for r in v])
    msg.header.stamp = seconds_to_time(t)
    msg.header.frame_id = frame
    packed = FleetStateTemplate(frame, boats).pack(sec, nanosec, v[:, :7], v[:, 7:])
    assert packed == zero_padding(serialize_message(msg), "boat_msgs/msg/FleetState")
    assert deserialize_message(packed, FleetState) == msg


@given(st.lists(st.integers(0, 2**64 - 1), min_size=1, max_size=6))  # reports: 4 values
def test_uint64_multi_array_bytes_equal_rclpys_with_zeroed_padding(values):
    from std_msgs.msg import UInt64MultiArray

    from boat_msgs_py.cdr import uint64_multi_array_cdr
    from boat_msgs_py.typestore import zero_padding

    data = uint64_multi_array_cdr(values)
    msg = UInt64MultiArray(data=values)
    assert data == zero_padding(serialize_message(msg), "std_msgs/msg/UInt64MultiArray")
    assert deserialize_message(data, UInt64MultiArray) == msg
