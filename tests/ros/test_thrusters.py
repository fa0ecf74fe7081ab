"""Named thrusters over ROS 2: per-thruster topics steer by differential thrust, and
/cmd_thrust still drives every thruster. Real time (commands are paced in wall time, well
inside cmd_timeout of simulation time: 5 s, so a probe stalled on a busy machine does not cut
the thrust); every measurement is in simulation time."""

import time

import yaml
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64

from boat_msgs_py.convert import time_to_seconds

# A 2 x 1 x 1 m box of 1025 kg (half draft, GM 0.22 m), thrusters 0.4 m either side of the
# centre line at 100 N, linear damping only: surge 1000 N s/m, yaw 400 N m s (time constants
# of about 1 s). Flat water.
TWIN = {"simulation": {"cmd_timeout": 5.0},
        "boats": [{"name": "twin", "hull": {"type": "box", "length": 2.0, "beam": 1.0,
                                             "height": 1.0},
                   "mass": 1025.0, "center_of_mass": [0.0, 0.0, -0.3],
                   "propulsion": [
                       {"name": "left", "max_thrust": 100.0, "position": [-1.0, 0.4, -0.2]},
                       {"name": "right", "max_thrust": 100.0, "position": [-1.0, -0.4, -0.2]}],
                   "rudder": {"model": "none"},
                   "damping": {"linear": [1000, 2000, 0, 0, 0, 400], "quadratic": [0] * 6}}]}


def test_differential_thrust_turns_on_the_spot_and_cmd_thrust_drives_both(boatsim, probe,
                                                                          tmp_path):
    path = tmp_path / "twin.yaml"
    path.write_text(yaml.safe_dump(TWIN))
    sim = boatsim("run", str(path))
    odom = []
    probe.node.create_subscription(Odometry, "/twin/odom", odom.append, 10)
    left = probe.node.create_publisher(Float64, "/twin/thrusters/left/thrust", 10)
    right = probe.node.create_publisher(Float64, "/twin/thrusters/right/thrust", 10)
    both = probe.node.create_publisher(Float64, "/twin/cmd_thrust", 10)
    probe.spin_until(lambda: len(odom) > 5, 30.0, "/twin/odom")

    def drive(commands, seconds):
        t0 = time_to_seconds(odom[-1].header.stamp)
        end = time.monotonic() + 10 * seconds + 30
        while time_to_seconds(odom[-1].header.stamp) - t0 < seconds:
            assert time.monotonic() < end, f"{seconds} s of simulation did not pass"
            for pub, value in commands:
                pub.publish(Float64(data=value))
            probe.spin_for(0.05)
        return odom[-1].twist.twist

    # right ahead, left astern: N = 2 x 0.4 x 100 = 80 N m to port, r = 80 / 400 = 0.2 rad/s
    turning = drive([(left, -1.0), (right, 1.0)], 8.0)
    assert abs(turning.angular.z - 0.2) < 0.2 * 0.03
    assert abs(turning.linear.x) < 0.02
    # /cmd_thrust drives both alike: straight, 200 N / 1000 N s/m = 0.2 m/s
    straight = drive([(both, 1.0)], 8.0)
    assert abs(straight.linear.x - 0.2) < 0.2 * 0.03
    assert abs(straight.angular.z) < 0.005
    assert sim.stop() == 0
    assert "Traceback" not in sim.output()
