"""A noisy odometry: the true pose and twist with white noise, for stacks that consume one.

``/odom`` stays ground truth (covariances zero). This sensor publishes the hull reference
point's pose (world) and twist (body) as ``odom`` does, each component with white Gaussian
noise of its sigma (position m, attitude rad as a small rotation, velocity m/s, angular
velocity rad/s), the covariances filled from those sigmas (row-major 6 x 6, x y z then
rotations about x y z, as nav_msgs/Odometry defines them).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_from_rotation_vector, quat_multiply
from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["OdometryNoise", "OdometryReading", "OdometrySpec", "measure_odometry"]


@dataclass(frozen=True)
class OdometryNoise:
    """White noise, 1 sigma: m, rad, m/s, rad/s."""

    position_sigma: float = 0.5
    orientation_sigma: float = 0.01
    velocity_sigma: float = 0.05
    angular_velocity_sigma: float = 0.005


@dataclass(frozen=True)
class OdometrySpec:
    """A noisy odometry of a boat: topic ``<ns>/<name>``, child frame ``<ns>/base_link``.

    ``dropout``: the probability that a reading is lost (not published); ``latency``: s, from
    a reading (its stamp) to its publication.
    """

    name: str = "odometry"
    rate_hz: float = 50.0
    noise: OdometryNoise = OdometryNoise()
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class OdometryReading:
    """A noisy pose and twist, and their (6, 6) covariances.

    Pose (3,) m and (4,) quaternion, world frame; twist (3,) m/s and (3,) rad/s, body frame.
    """

    position: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    pose_covariance: np.ndarray
    twist_covariance: np.ndarray


def measure_odometry(spec: OdometrySpec, key: np.ndarray, sample: int, position: np.ndarray,
                     orientation: np.ndarray, velocity: np.ndarray,
                     angular_velocity: np.ndarray) -> OdometryReading:
    """Reading number ``sample`` of the true pose and twist (no state: white noise only)."""
    n = spec.noise
    w = standard_normal(key, sample, 12).reshape(4, 3)
    pose = np.diag([n.position_sigma**2] * 3 + [n.orientation_sigma**2] * 3)
    twist = np.diag([n.velocity_sigma**2] * 3 + [n.angular_velocity_sigma**2] * 3)
    return OdometryReading(
        position + n.position_sigma * w[0],
        quat_multiply(orientation, quat_from_rotation_vector(n.orientation_sigma * w[1])),
        velocity + n.velocity_sigma * w[2], angular_velocity + n.angular_velocity_sigma * w[3],
        pose, twist)
