"""Messages to YAML (as `ros2 topic echo` prints) and back (as `topic pub` reads)."""

import pytest
import yaml
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from hypothesis import given, settings
from hypothesis import strategies as st
from nav_msgs.msg import Odometry
from sensor_msgs.msg import PointCloud2
from std_msgs.msg import Float64

from boat_msgs_py.fields import (
    TRUNCATE_LENGTH,
    FieldError,
    message_class,
    message_to_yaml,
    set_fields,
)

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
texts = st.text(alphabet=st.characters(codec="ascii", exclude_categories=("Cc",)), max_size=12)


@settings(max_examples=60, deadline=None)
@given(st.lists(finite, min_size=36, max_size=36), st.lists(finite, min_size=7, max_size=7),
       texts, texts)
def test_odometry_round_trips_through_the_yaml_echo_prints(cov, pose, frame, child):
    msg = Odometry(child_frame_id=child)
    msg.header.frame_id = frame
    msg.header.stamp.sec, msg.header.stamp.nanosec = 12, 345
    p = msg.pose.pose
    p.position.x, p.position.y, p.position.z = pose[:3]
    p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = pose[3:]
    msg.pose.covariance = cov
    text = message_to_yaml(msg, full_length=True)
    assert set_fields(Odometry(), yaml.safe_load(text)) == msg


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(texts, texts, st.integers(0, 3)), max_size=4))
def test_nested_sequences_round_trip(statuses):
    msg = DiagnosticArray(status=[
        DiagnosticStatus(name=n, level=bytes([lvl]), values=[KeyValue(key=n, value=v)])
        for n, v, lvl in statuses])
    assert set_fields(DiagnosticArray(), yaml.safe_load(message_to_yaml(msg))) == msg


def test_the_layout_is_ros2_echos():
    msg = DiagnosticArray(status=[DiagnosticStatus(name="boat", level=b"\x01",
                                                   values=[KeyValue(key="gm", value="0.9")])])
    assert message_to_yaml(msg) == (
        "header:\n  stamp:\n    sec: 0\n    nanosec: 0\n  frame_id: ''\nstatus:\n"
        "- level: 1\n  name: boat\n  message: ''\n  hardware_id: ''\n  values:\n"
        "  - key: gm\n    value: '0.9'\n")
    assert message_to_yaml(Float64(data=1e-300)) == "data: 1.0e-300\n"  # YAML 1.1 reads it
    long = message_to_yaml(PointCloud2(data=bytes(300)))
    assert f"- '...'  # {300 - TRUNCATE_LENGTH} more (--full-length)" in long


def test_bad_values_and_types_are_named():
    with pytest.raises(FieldError, match="dta: Float64 has no such field"):
        set_fields(Float64(), {"dta": 1.0})
    with pytest.raises(FieldError, match="data: 'fast' does not fit a double"):
        set_fields(Float64(), {"data": "fast"})
    with pytest.raises(FieldError, match="expected a mapping"):
        set_fields(Float64(), [1.0])
    with pytest.raises(FieldError, match="not installed"):
        message_class("nosuch_msgs/msg/Thing")
    with pytest.raises(FieldError, match="expected pkg/msg/Name"):
        message_class("Float64")
    assert message_class("std_msgs/Float64") is Float64
