"""teleop's status line and its warning for a boat nobody simulates."""

from nav_msgs.msg import Odometry

from boat_dynamics.tools.teleop import _no_odometry, _status


def test_the_status_line_says_when_there_is_no_odometry_instead_of_nan():
    line = _status(0.5, -0.1, None, "/nosuchboat/odom")
    assert "nan" not in line and "(no /nosuchboat/odom yet)" in line
    odom = Odometry()
    odom.twist.twist.linear.x = 1.5
    odom.pose.pose.orientation.w = 1.0
    assert "speed  1.50 m/s  heading    0.0 deg" in _status(0.5, -0.1, odom)


def test_a_missing_boat_is_named_with_the_boats_there_are():
    text = _no_odometry("/nosuchboat/odom", ["/alpha/odom", "/bravo/odom", "/alpha/pose",
                                             "/odom", "/clock"])
    assert "no /nosuchboat/odom after 3 s" in text
    assert "--ns alpha, --ns bravo" in text and "(no --ns: the root boat)" in text
    assert "is `boatsim run` up" in _no_odometry("/x/odom", ["/clock"])
