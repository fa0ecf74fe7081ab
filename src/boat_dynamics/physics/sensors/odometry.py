"""A noisy odometry: the true pose and twist with white noise, or a drifting dead reckoning.

``/odom`` stays ground truth (covariances zero). This sensor publishes the hull reference
point's pose (world) and twist (body) as ``odom`` does, each component with white Gaussian
noise of its sigma (position m, attitude rad as a small rotation, velocity m/s, angular
velocity rad/s), the covariances filled from those sigmas (row-major 6 x 6, x y z then
rotations about x y z, as nav_msgs/Odometry defines them).

With ``drift``, it is a dead reckoning instead (wheel or DVL odometry, REP-105's ``odom``
frame): its pose starts at the true one at its first reading and then integrates its own
noisy body velocity and angular velocity over each interval dt = 1 / rate (x' = x + R v dt,
q' = q exp(w dt / 2)), so it drifts as a random walk: after n readings each horizontal
coordinate is off by sigma_v dt sqrt(n) (1 sigma, heading held), which its pose covariance
says.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.rigid_body import (
    quat_from_rotation_vector,
    quat_multiply,
    rotation_matrix,
)
from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["DeadReckoning", "OdometryNoise", "OdometryReading", "OdometrySpec",
           "dead_reckon", "measure_odometry"]


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
    a reading (its stamp) to its publication; ``drift``: a dead reckoning (module docs) instead
    of white noise on the true pose.
    """

    name: str = "odometry"
    rate_hz: float = 50.0
    noise: OdometryNoise = OdometryNoise()
    dropout: float = 0.0
    latency: float = 0.0
    drift: bool = False


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


@dataclass(frozen=True)
class DeadReckoning:
    """A drifting odometry's state: its reading count and its pose (None before the first).

    Attributes:
        sample: the readings taken.
        position: (3,) m, world frame, the estimated hull reference point.
        orientation: (4,) x, y, z, w, the estimated attitude (body to world).
    """

    sample: int = 0
    position: np.ndarray | None = None
    orientation: np.ndarray | None = None


def dead_reckon(spec: OdometrySpec, key: np.ndarray, state: DeadReckoning,
                position: np.ndarray, orientation: np.ndarray, velocity: np.ndarray,
                angular_velocity: np.ndarray) -> tuple[OdometryReading, DeadReckoning]:
    """The next reading of a drifting odometry (module docs), and its state after it.

    Args:
        spec: the sensor (``drift``).
        key: its noise stream.
        state: its state before this reading.
        position: (3,) m, the true reference point, world frame (the first reading's start).
        orientation: (4,) the true attitude.
        velocity: (3,) m/s, the true reference point's velocity, body frame.
        angular_velocity: (3,) rad/s, body frame.
    """
    n, dt = spec.noise, 1.0 / spec.rate_hz
    w = standard_normal(key, state.sample, 6).reshape(2, 3)
    v = velocity + n.velocity_sigma * w[0]
    omega = angular_velocity + n.angular_velocity_sigma * w[1]
    if state.position is None:
        p, q = np.asarray(position, dtype=float), np.asarray(orientation, dtype=float)
    else:
        p = state.position + rotation_matrix(state.orientation[None])[0] @ v * dt
        q = quat_multiply(state.orientation, quat_from_rotation_vector(omega * dt))
        q = q / np.linalg.norm(q)
    steps = state.sample  # the intervals integrated so far, each adding its variance
    pose = np.diag([steps * (n.velocity_sigma * dt) ** 2] * 3
                   + [steps * (n.angular_velocity_sigma * dt) ** 2] * 3)
    twist = np.diag([n.velocity_sigma**2] * 3 + [n.angular_velocity_sigma**2] * 3)
    return (OdometryReading(p, q, v, omega, pose, twist),
            DeadReckoning(state.sample + 1, p, q))
