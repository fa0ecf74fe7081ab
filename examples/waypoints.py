#!/usr/bin/env python3
"""Steer a twin-thruster boat through waypoints from its GNSS fix and IMU only.

A minimal guidance loop of the kind an autonomy stack runs, against boatsim's sensor topics
(no ground truth): position from ``<ns>/gnss/fix`` (WGS-84, converted with pymap3d to a local
east-north plane at the mean of the first five fixes), heading and yaw rate from
``<ns>/imu/data``. It follows the straight legs between waypoints by line-of-sight guidance
(Fossen 2021, "Handbook of marine craft hydrodynamics and motion control", sec. 12.4.2:
desired heading chi_leg - atan(e / Delta), e the cross-track error, Delta a look-ahead
distance) and steers by differential thrust on ``<ns>/thrusters/left/thrust`` and
``.../right/thrust``:

    heading error h = wrap(chi_leg - atan(e / Delta) - yaw)
    turn = clip(K_p h - K_d r, -1, 1),  ahead = speed * slow-down * max(0, cos h)
    left = ahead - turn,  right = ahead + turn        (right ahead turns the bow to port)

slowing down over the last 8 m of a leg. A waypoint counts as reached when less than
``--radius`` metres of its leg remain; waypoints are east, north metres from the start. Exit
status 0 once the last one is reached (thrust then set to 0), 1 on ``--timeout`` seconds of
message time. Run with the shipped catamaran:

    .venv/bin/boatsim run scenarios/otter.yaml &
    .venv/bin/python examples/waypoints.py --ns otter --waypoints "15,0;15,15;0,15"
"""

from __future__ import annotations

import argparse
import math
import sys

import pymap3d
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from sensor_msgs.msg import Imu, NavSatFix
from std_msgs.msg import Float64

#: m, the look-ahead distance Delta of the line-of-sight guidance.
LOOK_AHEAD = 4.0


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def _yaw(q) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class Waypoints(Node):
    """The guidance node: sensors in, per-thruster throttles out."""

    def __init__(self, ns: str, waypoints: list[tuple[float, float]], speed: float,
                 radius: float, timeout: float) -> None:
        super().__init__("waypoints")
        self.waypoints, self.speed, self.radius, self.timeout = waypoints, speed, radius, timeout
        self.index = 0
        self.origin: tuple[float, float, float] | None = None
        self.leg_start: tuple[float, float] | None = None  # where the current leg begins
        self.first: list[tuple[float, float, float]] = []  # fixes before the origin
        self.position: tuple[float, float] | None = None
        self.start_t: float | None = None
        self.status: int | None = None  # exit status once done
        prefix = f"/{ns}" if ns else ""
        self.left = self.create_publisher(Float64, f"{prefix}/thrusters/left/thrust", 10)
        self.right = self.create_publisher(Float64, f"{prefix}/thrusters/right/thrust", 10)
        # the latest reading only (depth 1): a guidance that falls behind steers on the boat's
        # state now, not on a queue of old ones (with 10, a loaded machine left it 0.1 s late
        # and slewing about its legs)
        self.create_subscription(NavSatFix, f"{prefix}/gnss/fix", self.on_fix, 1)
        self.create_subscription(Imu, f"{prefix}/imu/data", self.on_imu, 1)

    def on_fix(self, msg: NavSatFix) -> None:
        """Position in the local east-north plane of the mean of the first five fixes."""
        if self.origin is None:
            self.first.append((msg.latitude, msg.longitude, msg.altitude))
            if len(self.first) < 5:
                return
            self.origin = tuple(sum(v) / len(v) for v in zip(*self.first, strict=True))
            self.get_logger().info(f"origin {self.origin[0]:.8f}, {self.origin[1]:.8f}, "
                                   f"{self.origin[2]:.3f}; {len(self.waypoints)} waypoints")
        e, n, _ = pymap3d.geodetic2enu(msg.latitude, msg.longitude, msg.altitude, *self.origin)
        self.position = (float(e), float(n))

    def on_imu(self, msg: Imu) -> None:
        """One guidance step per IMU reading: next waypoint, heading error, throttles."""
        t = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        if self.start_t is None:
            self.start_t = t
        if self.status is not None or self.position is None:
            return
        if t - self.start_t > self.timeout:
            self.finish(1, f"timed out after {self.timeout:g} s at waypoint {self.index}")
            return
        if self.leg_start is None:
            self.leg_start = self.position
        remaining, cross = self.leg_errors()
        if remaining < self.radius:
            wx, wy = self.waypoints[self.index]
            self.get_logger().info(f"reached waypoint {self.index} ({wx:g}, {wy:g}) at "
                                   f"t = {t - self.start_t:.1f} s")
            self.leg_start = self.waypoints[self.index]
            self.index += 1
            if self.index == len(self.waypoints):
                self.finish(0, f"reached all {len(self.waypoints)} waypoints in "
                               f"{t - self.start_t:.1f} s")
                return
            remaining, cross = self.leg_errors()
        (ax, ay), (wx, wy) = self.leg_start, self.waypoints[self.index]
        desired = math.atan2(wy - ay, wx - ax) - math.atan(cross / LOOK_AHEAD)
        error = _wrap(desired - _yaw(msg.orientation))
        turn = max(-1.0, min(1.0, 1.2 * error - 0.8 * msg.angular_velocity.z))
        ahead = self.speed * max(0.3, min(1.0, remaining / 8.0)) * max(0.0, math.cos(error))
        self.command(ahead - turn, ahead + turn)

    def leg_errors(self) -> tuple[float, float]:
        """(m of the leg still ahead, cross-track error m, + to the left of the leg)."""
        (ax, ay), (wx, wy) = self.leg_start, self.waypoints[self.index]
        x, y = self.position
        length = math.hypot(wx - ax, wy - ay) or 1e-9
        ux, uy = (wx - ax) / length, (wy - ay) / length
        along = (x - ax) * ux + (y - ay) * uy
        return length - along, -(x - ax) * uy + (y - ay) * ux

    def command(self, left: float, right: float) -> None:
        """Publish the two throttles, clipped to -1..1."""
        self.left.publish(Float64(data=max(-1.0, min(1.0, left))))
        self.right.publish(Float64(data=max(-1.0, min(1.0, right))))

    def finish(self, status: int, text: str) -> None:
        """Stop the thrusters and keep the exit status."""
        self.command(0.0, 0.0)
        self.status = status
        (self.get_logger().info if status == 0 else self.get_logger().error)(text)


def _waypoints(text: str) -> list[tuple[float, float]]:
    out = []
    for pair in text.split(";"):
        x, y = (float(v) for v in pair.split(","))
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(pair)
        out.append((x, y))
    return out


def main(argv: list[str] | None = None) -> int:
    """Run the guidance until the last waypoint, a timeout or Ctrl-C; the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ns", default="otter", help="the boat's namespace")
    parser.add_argument("--waypoints", type=_waypoints, default=_waypoints("15,0;15,15;0,15"),
                        help="'east,north;east,north;...' m from the start")
    parser.add_argument("--speed", type=float, default=0.6, help="throttle ahead, 0..1")
    parser.add_argument("--radius", type=float, default=2.0, help="acceptance radius, m")
    parser.add_argument("--timeout", type=float, default=120.0, help="s of message time")
    args = parser.parse_args(argv)
    rclpy.init()
    node = Waypoints(args.ns, args.waypoints, args.speed, args.radius, args.timeout)
    try:
        while rclpy.ok() and node.status is None:
            rclpy.spin_once(node, timeout_sec=0.1)
        for _ in range(5):  # let the zero-thrust commands out
            rclpy.spin_once(node, timeout_sec=0.02)
    except (KeyboardInterrupt, ExternalShutdownException):
        return 130
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 1 if node.status is None else node.status


if __name__ == "__main__":
    sys.exit(main())
