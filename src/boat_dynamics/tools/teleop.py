"""`boatsim teleop`: drive a boat from the keyboard by publishing its command topics.

Arrows or WASD: throttle steps of 0.1 (up/w more ahead, down/s more astern), rudder steps of
0.05 rad (left/a bow to port, right/d to starboard); space: stop (throttle and rudder 0); q
or Ctrl-C: quit. The commands are republished at 10 Hz (the dynamics node zeroes the thrust
after cmd_timeout without one); the line shows them with the boat's speed and heading from
``odom``. The terminal is restored on exit, whatever happens.
"""

from __future__ import annotations

import math
import os
import select
import sys
import termios
import time
import tty

__all__ = ["KEYS", "teleop"]

#: key sequence -> (throttle step, rudder step, stop)
KEYS = {
    "\x1b[A": (0.1, 0.0, False), "w": (0.1, 0.0, False),
    "\x1b[B": (-0.1, 0.0, False), "s": (-0.1, 0.0, False),
    "\x1b[D": (0.0, 0.05, False), "a": (0.0, 0.05, False),
    "\x1b[C": (0.0, -0.05, False), "d": (0.0, -0.05, False),
    " ": (0.0, 0.0, True),
}


def _keys(data: str) -> list[str]:
    out, i = [], 0
    while i < len(data):
        if data.startswith("\x1b[", i) and i + 2 < len(data):
            out.append(data[i:i + 3])
            i += 3
        else:
            out.append(data[i])
            i += 1
    return out


def _apply_keys(data: str, throttle: float, rudder: float, max_rudder: float
                ) -> tuple[float, float]:
    """(throttle, rudder rad) after the keys in ``data``, each within its range."""
    for key in _keys(data):
        if key in KEYS:
            dt, dr, stop = KEYS[key]
            throttle = 0.0 if stop else min(1.0, max(-1.0, round(throttle + dt, 2)))
            rudder = 0.0 if stop else min(max_rudder, max(-max_rudder, round(rudder + dr, 3)))
    return throttle, rudder


def _status(throttle: float, rudder: float, odom, odom_topic: str = "/odom") -> str:
    """The status line: the commands, and the boat's speed and heading from its odometry."""
    commands = f"\rthrottle {throttle:+.2f}  rudder {rudder:+.3f} rad  "
    if odom is None:
        return commands + f"(no {odom_topic} yet)   "
    speed = math.hypot(odom.twist.twist.linear.x, odom.twist.twist.linear.y)
    o = odom.pose.pose.orientation
    heading = math.degrees(math.atan2(2 * (o.w * o.z + o.x * o.y),
                                      1 - 2 * (o.y * o.y + o.z * o.z)))
    return commands + f"speed {speed:5.2f} m/s  heading {heading:6.1f} deg   "


#: Wall time without odometry after which teleop says which boats there are, s.
_ODOM_PATIENCE = 3.0


def _no_odometry(odom_topic: str, topics: list[str]) -> str:
    """The warning for a boat whose odometry does not come, naming the boats that publish."""
    from boat_msgs_py import names

    boats = sorted(b for t in topics if (b := names.boat_of(t, names.ODOM)) is not None)
    found = (", ".join(f"--ns {b}" if b else "(no --ns: the root boat)" for b in boats)
             if boats else "none: is `boatsim run` up, on this ROS_DOMAIN_ID?")
    return (f"\r\nboatsim teleop: warning: no {odom_topic} after {_ODOM_PATIENCE:g} s; the "
            f"commands go to a boat nobody simulates. Boats with odometry: {found}\r\n")


def teleop(namespace: str = "", max_rudder: float = math.radians(35.0)) -> int:
    """Run the keyboard driver until q or Ctrl-C; returns the exit status."""
    import rclpy
    from nav_msgs.msg import Odometry
    from std_msgs.msg import Float64

    from boat_msgs_py import names
    from boat_msgs_py.qos import COMMAND_QOS, STATE_QOS

    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        print("boatsim teleop: error: needs a terminal (stdin is not a tty)", file=sys.stderr)
        return 2
    rclpy.init()
    node = rclpy.create_node("boatsim_teleop")
    thrust_pub = node.create_publisher(Float64, names.boat_topic(namespace, names.CMD_THRUST),
                                       COMMAND_QOS)
    rudder_pub = node.create_publisher(Float64, names.boat_topic(namespace, names.CMD_RUDDER),
                                       COMMAND_QOS)
    odom: list[Odometry] = []
    node.create_subscription(Odometry, names.boat_topic(namespace, names.ODOM),
                             lambda m: odom.__setitem__(slice(None), [m]), STATE_QOS)
    throttle = rudder = 0.0
    odom_topic = names.boat_topic(namespace, names.ODOM)
    warn_at = time.monotonic() + _ODOM_PATIENCE  # once, if no odometry by then
    saved = termios.tcgetattr(fd)
    out = sys.stdout
    try:
        tty.setcbreak(fd)
        out.write("boatsim teleop: arrows/WASD throttle and rudder, space stop, q quit\r\n")
        next_send = 0.0
        while True:
            ready, _, _ = select.select([fd], [], [], 0.05)
            if ready:
                data = os.read(fd, 64).decode(errors="ignore")
                if "q" in data or "\x03" in data:
                    break
                throttle, rudder = _apply_keys(data, throttle, rudder, max_rudder)
                next_send = 0.0
            if time.monotonic() >= next_send:
                thrust_pub.publish(Float64(data=throttle))
                rudder_pub.publish(Float64(data=rudder))
                next_send = time.monotonic() + 0.1
                out.write(_status(throttle, rudder, odom[0] if odom else None, odom_topic))
                if not odom and time.monotonic() > warn_at:
                    warn_at = math.inf
                    out.write(_no_odometry(odom_topic, [
                        t for t, _ in node.get_topic_names_and_types()]))
                out.flush()
            rclpy.spin_once(node, timeout_sec=0.0)
    except KeyboardInterrupt:
        pass
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        out.write("\r\n")
        out.flush()
        thrust_pub.publish(Float64(data=0.0))
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
