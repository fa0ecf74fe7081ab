"""A GNSS receiver: WGS-84 fix and ENU velocity of the antenna, with noise.

The simulation's world frame is a local ENU tangent plane (REP-105 ``world``) at the datum
(latitude, longitude, ellipsoidal altitude on WGS-84). The antenna at ``position`` (body
frame, from the hull reference point) is at p = p_ref + R position in that plane; its fix is
p (plus noise) converted to geodetic coordinates by pymap3d's ``enu2geodetic`` (Hirsch 2018,
"pymap3d: Python 3-D coordinate conversions", JOSS 3(23) 580), and its velocity is
v = R (v_cm + omega x (position - centre of mass)), ENU.

Noise per axis, ENU (:mod:`.noise`): white noise of ``horizontal_sigma`` (east, north) and
``vertical_sigma`` (up), a slow correlated error (multipath, atmosphere: a Gauss-Markov process
of stationary sigma ``bias_sigma`` horizontally, twice that vertically, and correlation time
``bias_correlation_time``; Rankin 1994, "An error model for sensor simulation GPS and
differential GPS"), and white velocity noise of ``velocity_sigma``. The defaults are a
single-frequency standalone receiver: 1.5 m horizontal and 3 m vertical white, 0.5 m
correlated over 60 s, 0.05 m/s. The fix's covariance is their sum, per axis
(``COVARIANCE_TYPE_DIAGONAL_KNOWN``).

Outages (``outages``: intervals of simulation time: under a bridge, beside a quay wall): the
receiver has no fix (:func:`has_fix`); its noise runs on, so the fixes after an outage are
those it would have had.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pymap3d

from boat_dynamics.physics.sensors.noise import gauss_markov, standard_normal

__all__ = ["Datum", "GnssNoise", "GnssReading", "GnssSpec", "GnssState", "enu_to_geodetic",
           "geodetic_to_enu", "gnss_start", "has_fix", "measure_gnss"]


@dataclass(frozen=True)
class Datum:
    """Where the world frame's origin is on the WGS-84 ellipsoid.

    Attributes:
        latitude: rad, geodetic, north positive.
        longitude: rad, east positive.
        altitude: m above the ellipsoid.
    """

    latitude: float = float(np.radians(45.0))
    longitude: float = float(np.radians(-4.0))
    altitude: float = 0.0


@dataclass(frozen=True)
class GnssNoise:
    """A receiver's noise: m and m/s, 1 sigma; the correlation time in s."""

    horizontal_sigma: float = 1.5
    vertical_sigma: float = 3.0
    bias_sigma: float = 0.5
    bias_correlation_time: float = 60.0
    velocity_sigma: float = 0.05


@dataclass(frozen=True)
class GnssSpec:
    """A GNSS receiver on a boat.

    Attributes:
        name: its name: topics ``<ns>/<name>/fix`` and ``<ns>/<name>/vel``, frame
            ``<ns>/<name>_link``.
        rate_hz: fixes per simulated second.
        position: (3,) m, body frame, the antenna's point from the hull reference point.
        noise: its noise.
        outages: ((start, end), ...) s of simulation time, start <= t < end, without a fix.
        dropout: the probability that a fix is lost (neither it nor its velocity published).
        latency: s, from a fix (its stamp) to its publication (and its velocity's).
    """

    name: str = "gnss"
    rate_hz: float = 5.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    noise: GnssNoise = GnssNoise()
    outages: tuple[tuple[float, float], ...] = ()
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class GnssState:
    """After ``sample`` fixes: the correlated error (3,) m, ENU."""

    sample: int
    bias: np.ndarray


@dataclass(frozen=True)
class GnssReading:
    """One fix.

    Attributes:
        latitude, longitude: rad; altitude: m (WGS-84 ellipsoid).
        position_covariance: (3, 3) m^2, ENU.
        velocity: (3,) m/s, ENU.
        velocity_covariance: (3, 3) (m/s)^2.
    """

    latitude: float
    longitude: float
    altitude: float
    position_covariance: np.ndarray
    velocity: np.ndarray
    velocity_covariance: np.ndarray


def enu_to_geodetic(datum: Datum, enu: np.ndarray) -> tuple[float, float, float]:
    """(latitude rad, longitude rad, altitude m) of a world point ``enu`` (3,) m."""
    lat, lon, alt = pymap3d.enu2geodetic(float(enu[0]), float(enu[1]), float(enu[2]),
                                         datum.latitude, datum.longitude, datum.altitude,
                                         deg=False)
    return float(lat), float(lon), float(alt)


def geodetic_to_enu(datum: Datum, latitude: float, longitude: float,
                    altitude: float) -> np.ndarray:
    """(3,) m, the world point of a geodetic position (rad, rad, m)."""
    return np.array(pymap3d.geodetic2enu(latitude, longitude, altitude, datum.latitude,
                                         datum.longitude, datum.altitude, deg=False),
                    dtype=float)


def has_fix(spec: GnssSpec, t: float) -> bool:
    """Whether the receiver has a fix at simulation time ``t`` (s): not in an outage."""
    return not any(start <= t < end for start, end in spec.outages)


def _bias_sigma(noise: GnssNoise) -> np.ndarray:
    return noise.bias_sigma * np.array([1.0, 1.0, 2.0])


def gnss_start(spec: GnssSpec, key: np.ndarray) -> GnssState:
    """The state before the first fix: the correlated error from its stationary law."""
    return GnssState(sample=1, bias=_bias_sigma(spec.noise) * standard_normal(key, 0, 3))


def measure_gnss(spec: GnssSpec, key: np.ndarray, state: GnssState, datum: Datum,
                 antenna: np.ndarray, velocity: np.ndarray) -> tuple[GnssReading, GnssState]:
    """One fix of the antenna at ``antenna`` (3,) m, ENU, moving at ``velocity`` (3,) m/s."""
    n = spec.noise
    w = standard_normal(key, state.sample, 9).reshape(3, 3)  # bias, position, velocity
    bias = gauss_markov(state.bias, _bias_sigma(n), n.bias_correlation_time,
                        1.0 / spec.rate_hz, w[0])
    white = np.array([n.horizontal_sigma, n.horizontal_sigma, n.vertical_sigma])
    lat, lon, alt = enu_to_geodetic(datum, antenna + bias + white * w[1])
    return GnssReading(
        latitude=lat, longitude=lon, altitude=alt,
        position_covariance=np.diag(white ** 2 + _bias_sigma(n) ** 2),
        velocity=velocity + n.velocity_sigma * w[2],
        velocity_covariance=np.eye(3) * n.velocity_sigma ** 2,
    ), GnssState(state.sample + 1, bias)
