"""`boatsim plot`: a readable PNG per boat, into a folder made if missing."""

import math
import re
import struct

import numpy as np
import pytest
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.serialization import serialize_message
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from std_msgs.msg import Float64

from boat_dynamics.cli import main


def _fleet_bag(path, boats=("alpha", "bravo", "charlie"), seconds=10.0, start=0.0):
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conns = {}

        def put(topic, msgtype, msg, t):
            if topic not in conns:
                conns[topic] = writer.add_connection(topic, msgtype, typestore=store)
            t += start
            if hasattr(msg, "header"):
                msg.header.stamp.sec, msg.header.stamp.nanosec = int(t), int(t % 1 * 1e9)
            writer.write(conns[topic], round(t * 1e9), serialize_message(msg))

        for boat in boats:
            put(f"/{boat}/cmd_thrust", "std_msgs/msg/Float64", Float64(data=0.8), 0.0)
            put(f"/{boat}/cmd_rudder", "std_msgs/msg/Float64", Float64(data=0.3), 2.0)
        for i in range(int(seconds * 10)):
            t = i / 10
            for k, boat in enumerate(boats):
                yaw = 0.1 * t * (k + 1)
                odom = Odometry()
                odom.pose.pose.position.x, odom.pose.pose.position.y = 2.0 * t, 5.0 * k
                odom.pose.pose.position.z = 0.2 * math.sin(t)
                odom.pose.pose.orientation.z, odom.pose.pose.orientation.w = (
                    math.sin(yaw / 2), math.cos(yaw / 2))
                odom.twist.twist.linear.x, odom.twist.twist.angular.z = 2.0, 0.1 * (k + 1)
                put(f"/{boat}/odom", "nav_msgs/msg/Odometry", odom, t)
                for source, fx in (("thrust", 1500.0), ("buoyancy", 40.0 * math.sin(t)),
                                   ("slamming", 0.0)):
                    w = WrenchStamped()
                    w.wrench.force.x, w.wrench.force.z = fx, 40e3 if source == "buoyancy" else 0
                    put(f"/{boat}/wrench/{source}", "geometry_msgs/msg/WrenchStamped", w, t)
    return path


def _png(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_three_boats_give_three_figures_in_a_folder_made_for_them(tmp_path, capsys):
    bag = _fleet_bag(tmp_path / "fleet")
    target = tmp_path / "new" / "folder" / "run.png"  # the folder does not exist yet
    assert main(["plot", str(bag), "-o", str(target)]) == 0
    out = capsys.readouterr().out
    for boat in ("alpha", "bravo", "charlie"):
        path = target.with_name(f"run_{boat}.png")
        assert f"boatsim: wrote {path}" in out
        assert _png(path) == (1200, 1500)
    import matplotlib.image

    pixels = matplotlib.image.imread(target.with_name("run_bravo.png"))
    assert pixels.std() > 0.05  # drawn on, not blank
    assert len(np.unique(pixels.reshape(-1, pixels.shape[-1]), axis=0)) > 50


def _odd_bag(path, odom_type):
    """/good/odom twice per stamp; /bad/odom a Float64 (or an Odometry, as asked)."""
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        good = writer.add_connection("/good/odom", "nav_msgs/msg/Odometry", typestore=store)
        bad = writer.add_connection("/bad/odom", odom_type, typestore=store)
        for i in range(50):
            odom = Odometry()
            odom.header.stamp.nanosec = i * 20_000_000
            odom.pose.pose.orientation.w = 1.0
            for _ in range(2):  # a repeated stamp
                writer.write(good, i * 20_000_000, serialize_message(odom))
            writer.write(bad, i * 20_000_000, serialize_message(
                Float64(data=1.0) if odom_type.startswith("std_msgs") else odom))
    return path


def test_plot_and_view_draw_odometry_and_skip_an_odom_of_another_type(tmp_path, capsys):
    """Before: an AttributeError traceback on the Float64, and a ValueError on the repeated
    stamps in the view (sorting compared the messages)."""
    from boat_dynamics.tools.bags import BagError
    from boat_dynamics.tools.plot import plot_bag
    from boat_dynamics.tools.view import ViewError, ViewOptions, view_bag

    bag = _odd_bag(tmp_path / "odd", "std_msgs/msg/Float64")
    assert plot_bag(bag, tmp_path / "p.png") == [tmp_path / "p.png"]  # /good only
    assert view_bag(bag, ViewOptions(save=str(tmp_path / "v.rrd"))) == 0
    assert (tmp_path / "v.rrd").stat().st_size > 0
    only_bad = tmp_path / "bad"
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(only_bad, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/odom", "std_msgs/msg/Float64", typestore=store)
        writer.write(conn, 0, serialize_message(Float64(data=1.0)))
    message = "no */odom topic of type nav_msgs/msg/Odometry (/odom is std_msgs/msg/Float64)"
    with pytest.raises(BagError, match=re.escape(message)):
        plot_bag(only_bad)
    with pytest.raises(ViewError, match=re.escape(message)):
        view_bag(only_bad, ViewOptions(save=str(tmp_path / "w.rrd")))
    assert main(["plot", str(only_bad)]) == 2
    assert message in capsys.readouterr().err


def test_a_real_time_bag_is_drawn_from_its_start_and_a_held_rudder_with_zero_in_view(tmp_path):
    """Before: a real-time run's bag on an axis of epoch seconds (+1.796e9), and the rudder
    held at 0.3 rad on an axis a few millionths of a degree wide."""
    from boat_dynamics.tools.bags import read_bag
    from boat_dynamics.tools.plot import _figure, _since_start

    bag = _fleet_bag(tmp_path / "wall", boats=("alpha",), seconds=5.0, start=1.796e9)
    fig = _figure(_since_start(read_bag(bag)), "alpha", "t")
    for ax in fig.axes[1:]:  # every panel but the trajectory: time from the first message
        for line in ax.lines:
            assert 0.0 <= float(np.min(line.get_xdata())) <= 2.0, ax.get_title()
            assert float(np.max(line.get_xdata())) < 6.0
    speed = next(ax for ax in fig.axes if ax.get_ylabel() == "speed [m/s]")
    assert float(np.min(speed.lines[0].get_xdata())) == 0.0
    rudder = next(ax for ax in fig.axes if ax.get_ylabel().startswith("angle"))
    low, high = rudder.get_ylim()
    assert low <= 0.0 and 17.2 < high < 25.0, (low, high)  # 0.3 rad = 17.19 deg, zero in view
    for ax in fig.axes:
        assert ax.yaxis.get_major_formatter().get_offset() == ""


def test_a_figure_it_cannot_write_is_a_clear_error(tmp_path, capsys):
    """Before: a FileExistsError traceback for ``-o FILE/x.png`` where FILE is a file."""
    bag = _fleet_bag(tmp_path / "fleet", boats=("alpha",), seconds=1.0)
    blocker = tmp_path / "FILE"
    blocker.write_text("a regular file")
    assert main(["plot", str(bag), "-o", str(blocker / "x.png")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"boatsim plot: error: cannot make the folder {blocker} for x.png: ")
    assert "Traceback" not in err and blocker.read_text() == "a regular file"


def test_a_scripted_boats_commands_are_drawn_from_its_scenario(tmp_path, capsys):
    """Scripted commands are on no topic: before, a scripted boat's command panel was empty."""
    from boat_dynamics.tools.bags import read_bag
    from boat_dynamics.tools.plot import _figure, _since_start

    bag = _fleet_bag(tmp_path / "run", boats=("alpha",), seconds=5.0)
    scenario = tmp_path / "s.yaml"
    scenario.write_text("boats:\n  - name: alpha\n    commands:\n"
                        "      - {t: 0.0, thrust: 0.5, rudder: 0.0}\n"
                        "      - {t: 3.0, thrust: 1.0, rudder: -0.2}\n")
    assert main(["plot", str(bag), "-o", str(tmp_path / "p.png"), "--scenario",
                 str(scenario)]) == 0
    assert _png(tmp_path / "p.png") == (1200, 1500)
    from boat_dynamics.physics.scenario import load_scenario

    script = load_scenario(scenario).boats[0].commands
    fig = _figure(_since_start(read_bag(bag)), "alpha", "t", script)
    lines = {line.get_label(): line for ax in fig.axes for line in ax.lines}
    throttle, rudder = lines["scripted throttle"], lines["scripted rudder [deg]"]
    assert list(throttle.get_xdata()) == pytest.approx([0.0, 3.0, 4.9])
    assert list(throttle.get_ydata()) == [0.5, 1.0, 1.0]
    assert list(rudder.get_ydata()) == pytest.approx([0.0, -11.459, -11.459], abs=1e-3)
    assert main(["plot", str(bag), "--scenario", str(tmp_path / "missing.yaml")]) == 2
    assert "missing.yaml" in capsys.readouterr().err
