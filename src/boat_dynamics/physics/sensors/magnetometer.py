"""A three-axis magnetometer: the Earth's field in the sensor's axes, with hard and soft iron.

The Earth's field at the datum is given as a world magnetic model states it (NOAA's WMM
calculator: declination D, east of true north positive; inclination I, below the horizontal
positive; total intensity F): north X = F cos I cos D, east Y = F cos I sin D, down
Z = F sin I (Chulliat et al. 2025, "The US/UK World Magnetic Model for 2025-2030", sec. 1.2).
In the world frame (ENU, REP-103) that is b_w = (Y, X, -Z), T. The field is taken as uniform
over the simulated area (it changes by about 5 nT per km).

A magnetometer at ``position`` (body frame; its axes along the body's FLU axes, as
``/tf_static`` mounts it) reads

    m = W R^T b_w + h + n,

R the body-to-world rotation, W the soft-iron matrix (3 x 3: ferrous material near the sensor
that bends and scales the field, plus the sensor's own scale factors and cross-axis
sensitivity), h the hard-iron vector (T: the boat's own permanent magnetism, fixed in the body)
and n white noise of ``sigma`` (T) per axis (Gebre-Egziabher et al. 2006, "Calibration of
strapdown magnetometers in magnetic field domain", J. Aerosp. Eng. 19(2), eq. 4). Defaults:
an ideal, calibrated unit (W = I, h = 0) with 0.1 uT of noise, about a MEMS magnetometer at
20 Hz. Its covariance is sigma^2 I (the hard and soft iron are systematic: a user calibrates
them away, they are not noise).

A level boat's heading follows from the reading: the field's horizontal part lies at
pi / 2 - D from east in the world, so at atan2(m_y, m_x) = pi / 2 - D - psi in the body
(psi: yaw, ENU, counter-clockwise from east), and psi = pi / 2 - D - atan2(m_y, m_x): a
compass heading (clockwise from true north) atan2(m_y, m_x) + D in these FLU axes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["EarthField", "MagnetometerReading", "MagnetometerSpec", "measure_magnetometer"]


@dataclass(frozen=True)
class EarthField:
    """The Earth's magnetic field at the datum, as a world magnetic model gives it.

    The defaults: WMM2025 at the default datum (45 N, 4 W, sea level) for 2026.0: D 0.31 deg,
    I 60.29 deg, F 46,841 nT.

    Attributes:
        declination: rad, of magnetic north from true north, east positive.
        inclination: rad, of the field below the horizontal (negative: above, south of the
            magnetic equator).
        intensity: T, the field's magnitude.
    """

    declination: float = math.radians(0.31)
    inclination: float = math.radians(60.29)
    intensity: float = 46841e-9

    def enu(self) -> np.ndarray:
        """(3,) T, the field in the world frame: east, north, up."""
        horizontal = self.intensity * math.cos(self.inclination)
        return np.array([horizontal * math.sin(self.declination),
                         horizontal * math.cos(self.declination),
                         -self.intensity * math.sin(self.inclination)])


@dataclass(frozen=True)
class MagnetometerSpec:
    """A magnetometer on a boat.

    Attributes:
        name: its name: topic ``<ns>/<name>/data``, frame ``<ns>/<name>_link``.
        rate_hz: readings per simulated second.
        position: (3,) m, body frame, from the hull reference point (the field is uniform:
            it only places the frame).
        sigma: T, white noise per axis, 1 sigma.
        hard_iron: (3,) T, sensor frame, added to every reading.
        soft_iron: (3, 3) the matrix W applied to the field in the sensor's axes.
        dropout: the probability that a reading is lost (not published).
        latency: s, from a reading (its stamp) to its publication.
    """

    name: str = "magnetometer"
    rate_hz: float = 20.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    sigma: float = 1e-7
    hard_iron: np.ndarray = field(default_factory=lambda: np.zeros(3))
    soft_iron: np.ndarray = field(default_factory=lambda: np.eye(3))
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class MagnetometerReading:
    """One reading, as ``sensor_msgs/MagneticField`` carries it.

    Attributes:
        field: (3,) T, sensor frame.
        covariance: (3, 3) T^2.
    """

    field: np.ndarray
    covariance: np.ndarray


def measure_magnetometer(spec: MagnetometerSpec, key: np.ndarray, sample: int,
                         earth: EarthField, orientation: np.ndarray) -> MagnetometerReading:
    """Reading number ``sample`` (no state: white noise only).

    Args:
        spec: the magnetometer.
        key: its noise stream (:func:`.noise.stream_key`).
        sample: the reading's index in that stream (>= 0).
        earth: the Earth's field at the datum.
        orientation: (4,) the boat's attitude (x, y, z, w), body to world.
    """
    true = rotation_matrix(orientation).T @ earth.enu()
    w = standard_normal(key, sample, 3)
    return MagnetometerReading(field=spec.soft_iron @ true + spec.hard_iron + spec.sigma * w,
                               covariance=np.eye(3) * spec.sigma ** 2)
