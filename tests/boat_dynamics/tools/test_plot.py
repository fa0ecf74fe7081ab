"""`boatsim plot`: a readable PNG per boat, into a folder made if missing."""

import math
import struct

import numpy as np
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.serialization import serialize_message
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from std_msgs.msg import Float64

from boat_dynamics.cli import main


def _fleet_bag(path, boats=("alpha", "bravo", "charlie"), seconds=10.0):
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conns = {}

        def put(topic, msgtype, msg, t):
            if topic not in conns:
                conns[topic] = writer.add_connection(topic, msgtype, typestore=store)
            if hasattr(msg, "header"):
                msg.header.stamp.sec, msg.header.stamp.nanosec = int(t), int(t % 1 * 1e9)
            writer.write(conns[topic], int(t * 1e9), serialize_message(msg))

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
