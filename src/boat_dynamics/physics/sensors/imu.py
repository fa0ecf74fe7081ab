"""An inertial measurement unit: attitude, angular rate and specific force, with noise.

What a strapdown IMU fixed to the hull at ``position`` (body frame, axes along the body's FLU
axes) measures, as REP-145 asks of ``sensor_msgs/Imu``:

- angular velocity omega, body frame;
- specific force f = R^T (a_s - g), a_s the world acceleration of the sensor's point and
  g = (0, 0, -g) (so a level IMU at rest reads +g up; Titterton & Weston 2004, "Strapdown
  inertial navigation technology", sec. 3.2). With r the sensor's offset from the centre of
  mass, a_s = a_cm + R (alpha x r + omega x (omega x r)) (rigid body; Fossen 2021, "Handbook
  of marine craft hydrodynamics and motion control", sec. 14.4). The accelerations are those of
  the simulation's own step (``true_motion``: the change of velocity over the step, divided by
  dt), so an integration of the readings retraces the simulated motion;
- orientation (an AHRS's attitude), body to world (ENU).

Noise per axis (:mod:`.noise`): white noise of ``noise_density``, a Gauss-Markov bias of
stationary sigma ``bias_instability`` and time ``bias_correlation_time`` (started from its
stationary law: a turn-on bias), and a bias random walk of ``random_walk``; the attitude
gets white noise of ``orientation_sigma`` (rad, a small rotation). The defaults are an
ADIS16448-class MEMS unit, as in the RotorS IMU model (Furrer et al. 2016; noise densities
gyro 3.39e-4 rad/s/sqrt(Hz), accel 4e-3 m/s^2/sqrt(Hz); random walks 3.88e-5 rad/s^2/sqrt(Hz)
and 6e-3 m/s^3/sqrt(Hz); correlation times 1000 s and 300 s), with the datasheet's in-run
bias stability (14.5 deg/h, 0.25 mg).

A triad's own errors, drawn once at turn-on from the sensor's noise stream (a unit's
calibration residuals; IEEE Std 1293-2018 for accelerometers, Titterton & Weston sec. 8.3):
a scale-factor error per axis of sigma ``scale_factor`` (a fraction) and a misalignment of
each axis toward each other of sigma ``misalignment`` (rad), so that it reads
(I + S + M) x + bias + noise (S diagonal, M off-diagonal; zero by default: an ideal triad);
then clipped to +-``range`` (saturation; the ADIS16448's +-1000 deg/s and +-18 g by default).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.body.rigid_body import (
    quat_from_rotation_vector,
    quat_multiply,
    rotation_matrix,
)
from boat_dynamics.physics.core.model import BoatState
from boat_dynamics.physics.sensors.noise import gauss_markov, random_walk, standard_normal

__all__ = ["ACCELEROMETER", "GYROSCOPE", "TURN_ON_SAMPLE", "ImuReading", "ImuSpec", "ImuState",
           "InertialNoise", "imu_start", "measure_imu", "true_motion", "turn_on_transform"]


@dataclass(frozen=True)
class InertialNoise:
    """One triad's noise (gyroscope: rad/s based; accelerometer: m/s^2 based).

    Attributes:
        noise_density: white noise, unit/sqrt(Hz) (rad/s/sqrt(Hz), m/s^2/sqrt(Hz)).
        random_walk: bias random walk, unit/s/sqrt(Hz).
        bias_instability: stationary sigma of the Gauss-Markov bias, unit.
        bias_correlation_time: s, of that bias.
        scale_factor: 1 sigma of each axis's scale-factor error, a fraction (0.001 = 0.1 %).
        misalignment: rad, 1 sigma of each axis's misalignment toward each other axis.
        range: unit, the largest reading in magnitude (readings beyond it are clipped).
    """

    noise_density: float
    random_walk: float
    bias_instability: float
    bias_correlation_time: float
    scale_factor: float = 0.0
    misalignment: float = 0.0
    range: float = math.inf


GYROSCOPE = InertialNoise(3.39e-4, 3.88e-5, 7.0e-5, 1000.0, range=math.radians(1000.0))
ACCELEROMETER = InertialNoise(4.0e-3, 6.0e-3, 2.45e-3, 300.0, range=18.0 * 9.80665)
#: The noise stream's sample index of the turn-on errors (readings never reach it).
TURN_ON_SAMPLE = 2**62


@dataclass(frozen=True)
class ImuSpec:
    """An IMU on a boat.

    Attributes:
        name: its name: topics ``<ns>/<name>/data``, frame ``<ns>/<name>_link``.
        rate_hz: readings per simulated second.
        position: (3,) m, body frame, from the hull reference point.
        gyroscope: angular-rate noise.
        accelerometer: specific-force noise.
        orientation_sigma: rad, white attitude noise per axis.
        dropout: the probability that a reading is lost (not published).
        latency: s, from a reading (its stamp) to its publication.
    """

    name: str = "imu"
    rate_hz: float = 100.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    gyroscope: InertialNoise = GYROSCOPE
    accelerometer: InertialNoise = ACCELEROMETER
    orientation_sigma: float = math.radians(0.1)
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class ImuState:
    """An IMU's noise state after ``sample`` readings (the next reading is number ``sample``).

    Attributes:
        sample: readings taken.
        bias: (2, 3) the Gauss-Markov biases, gyroscope (rad/s) and accelerometer (m/s^2).
        walk: (2, 3) the random-walk biases, same units.
        transform: (2, 3, 3) I + S + M of each triad (its scale factors and misalignments,
            drawn at turn-on), or None when both triads are ideal.
    """

    sample: int
    bias: np.ndarray
    walk: np.ndarray
    transform: np.ndarray | None = None


@dataclass(frozen=True)
class ImuReading:
    """One reading, as ``sensor_msgs/Imu`` carries it.

    Attributes:
        orientation: (4,) unit quaternion (x, y, z, w), body to world.
        angular_velocity: (3,) rad/s, body frame.
        linear_acceleration: (3,) m/s^2, specific force, body frame.
        orientation_covariance, angular_velocity_covariance, linear_acceleration_covariance:
            (3, 3) rad^2, (rad/s)^2, (m/s^2)^2.
    """

    orientation: np.ndarray
    angular_velocity: np.ndarray
    linear_acceleration: np.ndarray
    orientation_covariance: np.ndarray
    angular_velocity_covariance: np.ndarray
    linear_acceleration_covariance: np.ndarray


def true_motion(center_of_mass: np.ndarray, before: BoatState, after: BoatState,
                position: np.ndarray, gravity: float) -> tuple[np.ndarray, np.ndarray]:
    """(angular velocity (3,) rad/s, specific force (3,) m/s^2), body frame, at ``after``.

    Args:
        center_of_mass: (3,) m, body frame, from the hull reference point.
        before: the boat's state at the start of one step.
        after: its state at the end of that step (dt = after.t - before.t > 0).
        position: (3,) m, body frame, the sensor's point (from the hull reference point).
        gravity: m/s^2.
    """
    dt = after.t - before.t
    r0, r1 = rotation_matrix(before.orientation), rotation_matrix(after.orientation)
    a_cm = (r1 @ after.velocity - r0 @ before.velocity) / dt
    omega = after.angular_velocity
    alpha = (after.angular_velocity - before.angular_velocity) / dt
    r = np.asarray(position, dtype=float) - center_of_mass
    a_sensor = a_cm + r1 @ (np.cross(alpha, r) + np.cross(omega, np.cross(omega, r)))
    return omega.copy(), r1.T @ (a_sensor + np.array([0.0, 0.0, gravity]))


def imu_start(spec: ImuSpec, key: np.ndarray) -> ImuState:
    """The state before the first reading.

    Gauss-Markov biases from their stationary law, and each triad's scale factors and
    misalignments (:func:`turn_on_transform`).
    """
    draws = standard_normal(key, 0, 6).reshape(2, 3)
    sigma = np.array([[spec.gyroscope.bias_instability], [spec.accelerometer.bias_instability]])
    return ImuState(sample=1, bias=sigma * draws, walk=np.zeros((2, 3)),
                    transform=turn_on_transform(spec, key))


def turn_on_transform(spec: ImuSpec, key: np.ndarray) -> np.ndarray | None:
    """(2, 3, 3) I + S + M of the gyroscope and the accelerometer, or None when both are ideal.

    S = diag(scale_factor w), M = misalignment w off the diagonal, w N(0, 1) draws at the
    stream's :data:`TURN_ON_SAMPLE` (the same unit whatever it has read).
    """
    triads = (spec.gyroscope, spec.accelerometer)
    if all(t.scale_factor == 0.0 and t.misalignment == 0.0 for t in triads):
        return None
    w = standard_normal(key, TURN_ON_SAMPLE, 18).reshape(2, 3, 3)
    off = ~np.eye(3, dtype=bool)
    out = np.empty((2, 3, 3))
    for i, t in enumerate(triads):
        out[i] = np.eye(3) + np.diag(t.scale_factor * np.diagonal(w[i]))
        out[i][off] += t.misalignment * w[i][off]
    return out


def measure_imu(spec: ImuSpec, key: np.ndarray, state: ImuState, orientation: np.ndarray,
                angular_velocity: np.ndarray, specific_force: np.ndarray
                ) -> tuple[ImuReading, ImuState]:
    """One reading of the true motion, and the noise state after it.

    Args:
        spec: the IMU.
        key: its noise stream (:func:`.noise.stream_key`).
        state: its state (:func:`imu_start`, then each reading's).
        orientation: (4,) true attitude, body to world.
        angular_velocity: (3,) rad/s, the true body rate (:func:`true_motion`).
        specific_force: (3,) m/s^2, the true specific force (:func:`true_motion`).
    """
    dt = 1.0 / spec.rate_hz
    w = standard_normal(key, state.sample, 21).reshape(7, 3)  # per triad: bias, walk, white
    triads = (spec.gyroscope, spec.accelerometer)
    bias = np.stack([gauss_markov(state.bias[i], t.bias_instability, t.bias_correlation_time,
                                  dt, w[i]) for i, t in enumerate(triads)])
    walk = np.stack([random_walk(state.walk[i], t.random_walk, dt, w[2 + i])
                     for i, t in enumerate(triads)])
    white = [t.noise_density / np.sqrt(dt) for t in triads]
    elapsed = state.sample * dt
    cov = [np.eye(3) * (white[i] ** 2 + t.bias_instability ** 2 + t.random_walk ** 2 * elapsed)
           for i, t in enumerate(triads)]
    rate, force = angular_velocity, specific_force
    if state.transform is not None:  # the unit's scale factors and misalignments
        rate, force = state.transform[0] @ rate, state.transform[1] @ force
    reading = ImuReading(
        orientation=quat_multiply(orientation,
                                  quat_from_rotation_vector(spec.orientation_sigma * w[6])),
        angular_velocity=np.clip(rate + bias[0] + walk[0] + white[0] * w[4],
                                 -spec.gyroscope.range, spec.gyroscope.range),
        linear_acceleration=np.clip(force + bias[1] + walk[1] + white[1] * w[5],
                                    -spec.accelerometer.range, spec.accelerometer.range),
        orientation_covariance=np.eye(3) * spec.orientation_sigma ** 2,
        angular_velocity_covariance=cov[0], linear_acceleration_covariance=cov[1])
    return reading, ImuState(state.sample + 1, bias, walk, state.transform)
