"""The ocean's current and wind over ROS 2: set at run time, checked, followed by the boats."""

import math

import pytest
import yaml
from boat_msgs.msg import Environment as EnvironmentMsg
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry
from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.msg import ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters

from boat_msgs_py.convert import time_to_seconds
from boat_msgs_py.qos import ENVIRONMENT_QOS

FLAT = {"boats": [{"damping": {"linear": [2000, 2000, 0, 0, 0, 4000], "quadratic": [0] * 6}}]}


def _param(name, value):
    if isinstance(value, str):
        return ParameterMsg(name=name, value=ParameterValue(
            type=ParameterType.PARAMETER_STRING, string_value=value))
    return ParameterMsg(name=name, value=ParameterValue(
        type=ParameterType.PARAMETER_DOUBLE, double_value=float(value)))


def test_a_current_set_at_run_time_carries_the_boat_and_bad_values_are_refused(
        boatsim, probe, tmp_path):
    path = tmp_path / "flat.yaml"
    path.write_text(yaml.safe_dump(FLAT))
    sim = boatsim("run", str(path), "--fast")
    odoms, envs, winds = [], [], []
    probe.node.create_subscription(Odometry, "/odom", odoms.append, 100)
    probe.node.create_subscription(EnvironmentMsg, "/ocean/environment", envs.append,
                                   ENVIRONMENT_QOS)
    probe.node.create_subscription(WrenchStamped, "/wrench/wind", winds.append, 100)
    probe.spin_until(lambda: len(odoms) > 5 and envs, 30.0, "/odom and /ocean/environment")
    assert envs[-1].current_speed == 0.0 and envs[-1].gusts == "none"
    client = probe.node.create_client(SetParameters, "/ocean/set_parameters")
    refused = probe.call(client, SetParameters.Request(parameters=[
        _param("wind.gusts", "harris")])).results[0]
    assert not refused.successful and "one of none, norsok" in refused.reason
    refused = probe.call(client, SetParameters.Request(parameters=[
        _param("current.speed", -1.0)])).results[0]
    assert not refused.successful
    result = probe.call(client, SetParameters.Request(parameters=[
        _param("current.speed", 0.5), _param("current.direction_deg", 90.0),
        _param("wind.speed", 8.0)])).results[0]
    assert result.successful, result.reason
    probe.spin_until(lambda: envs[-1].current_speed == 0.5, 10.0, "the new environment")
    assert envs[-1].current_direction == math.radians(90.0) and envs[-1].wind_speed == 8.0

    def stamp(o):
        return time_to_seconds(o.header.stamp)

    t_set = stamp(odoms[-1])
    probe.spin_until(lambda: stamp(odoms[-1]) > t_set + 30.0, 60.0, "30 s of simulation")
    v = odoms[-1].twist.twist.linear  # body frame; the boat keeps (nearly) heading 0
    speed = math.hypot(v.x, v.y)
    # the current's 0.5 m/s north, plus the wind's push east: 8 m/s on 1 m^2 of frontal area
    # at c_x 0.7 against 2000 N s/m, about 0.014 m/s
    assert speed == pytest.approx(math.hypot(0.5, 0.014), abs=0.01)
    # /wrench/wind is advertised once the graph shows the probe's subscription and sent once
    # they have matched (each looked at every 1 s of wall time): in --fast mode 30 s of
    # simulation may pass before that (a failure with two tests at once)
    probe.spin_until(lambda: winds and stamp(winds[-1]) > t_set, 30.0,
                     "/wrench/wind after the wind was set")
    assert winds[-1].wrench.force.x != 0.0
    assert sim.stop() == 0
    assert "new environment: current 0.5 m/s toward 90 deg" in sim.output()
