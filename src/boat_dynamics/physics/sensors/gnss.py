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

Multipath jumps (``multipath``: :class:`Multipath`; none by default): near a quay wall, a
hull or a bridge a receiver tracks a reflected signal (or only the reflection, NLOS) and its
fix jumps by metres to tens of metres for seconds, then comes back (Groves, "Principles of
GNSS, Inertial, and Multisensor Integrated Navigation Systems", 2nd ed. 2013, sec. 10.4).
Here a jump starts at each fix with probability 1 - exp(-rate dt) while none is under way (a
Poisson process of ``rate_hz`` in the time without one), moves the fix east and north by
N(0, ``sigma``^2) each, and lasts an exponential time of mean ``duration`` (the fixes while
the time left is > 0; a new one may start at the fix the last one ends). The receiver does
not know: the fix keeps its status and its covariance, as a real receiver's (its error
estimate comes from the signals' strength and geometry, which a reflection does not
change) -- this is what makes multipath hard for a filter, which must find the jump from
the innovations. The draws are apart from the fix's (:data:`MULTIPATH_SAMPLES`), so a
receiver without jumps reads as before, and one with them has the same white noise.

Heading (a dual-antenna receiver, ``heading_baseline`` b: body frame, from this antenna to
the second one): the receiver measures the baseline's direction in the world, w = R b, and
gives the boat's yaw (ENU, counter-clockwise from east) as the baseline's minus its mounting
angle, psi = atan2(w_y, w_x) - atan2(b_y, b_x), plus white noise of ``heading_sigma`` (rad;
default 0.2 deg, an RTK heading over a 1 m baseline: its error scales about as 1 / the
baseline's length). Rolled or pitched, the baseline's horizontal projection turns a little
from the body's heading, as a real receiver's does. A baseline within about 84 deg of the
vertical (its horizontal part under a tenth of its length) gives no heading. The draws are
apart from the fix's (:data:`HEADING_SAMPLES`), so a heading leaves the fixes as they were.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pymap3d

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.sensors.noise import gauss_markov, standard_normal

__all__ = ["HEADING_SAMPLES", "MULTIPATH_SAMPLES", "Datum", "GnssNoise", "GnssReading",
           "GnssSpec", "GnssState", "Multipath", "enu_to_geodetic", "geodetic_to_enu",
           "gnss_start", "has_fix", "measure_gnss", "measure_heading", "multipath_jump"]

#: Where a stream's heading draws start: past every fix's own counter, before the dropouts'.
HEADING_SAMPLES = 2**60
#: Where a stream's multipath draws start: past the headings', before the dropouts'.
MULTIPATH_SAMPLES = 2**60 + 2**59
#: The shortest horizontal part of a heading baseline, as a fraction of its length.
MIN_HORIZONTAL = 0.1


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
    """A receiver's noise: m and m/s, 1 sigma; the correlation time in s; heading: rad."""

    horizontal_sigma: float = 1.5
    vertical_sigma: float = 3.0
    bias_sigma: float = 0.5
    bias_correlation_time: float = 60.0
    velocity_sigma: float = 0.05
    heading_sigma: float = math.radians(0.2)


@dataclass(frozen=True)
class Multipath:
    """A receiver's multipath jumps.

    Attributes:
        rate_hz: jumps a second while none is under way.
        sigma: m, a jump's east and north offsets, 1 sigma each.
        duration: s, a jump's mean duration (exponentially distributed).
    """

    rate_hz: float = 0.01
    sigma: float = 5.0
    duration: float = 10.0


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
        heading_baseline: (3,) m, body frame, from this antenna to a second one (a
            dual-antenna receiver's heading), or None: no heading.
        multipath: its jumps, or None: none.
    """

    name: str = "gnss"
    rate_hz: float = 5.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    noise: GnssNoise = GnssNoise()
    outages: tuple[tuple[float, float], ...] = ()
    dropout: float = 0.0
    latency: float = 0.0
    heading_baseline: np.ndarray | None = None
    multipath: Multipath | None = None


@dataclass(frozen=True)
class GnssState:
    """After ``sample`` fixes: the correlated error (3,) m, ENU; the multipath jump.

    ``jump``: (2,) m, east and north, the jump under way (zeros: none); ``jump_left``: s it
    has left after the last fix (<= 0: none under way).
    """

    sample: int
    bias: np.ndarray
    jump: np.ndarray = field(default_factory=lambda: np.zeros(2))
    jump_left: float = 0.0


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
    jump, left = multipath_jump(spec, key, state)
    error = bias + white * w[1] + np.array([jump[0], jump[1], 0.0])
    lat, lon, alt = enu_to_geodetic(datum, antenna + error)
    return GnssReading(
        latitude=lat, longitude=lon, altitude=alt,
        position_covariance=np.diag(white ** 2 + _bias_sigma(n) ** 2),  # jumps untold
        velocity=velocity + n.velocity_sigma * w[2],
        velocity_covariance=np.eye(3) * n.velocity_sigma ** 2,
    ), GnssState(state.sample + 1, bias, jump, left)


def multipath_jump(spec: GnssSpec, key: np.ndarray, state: GnssState
                   ) -> tuple[np.ndarray, float]:
    """The jump on fix number ``state.sample``: ((2,) m east, north; s it has left after).

    The one under way goes on while its time left, less the fix interval, is > 0; else a new
    one starts with probability 1 - exp(-rate_hz dt) (draws at :data:`MULTIPATH_SAMPLES` +
    the fix's index: a uniform to start, a uniform for its duration, two normals).
    """
    m = spec.multipath
    if m is None:
        return np.zeros(2), 0.0
    dt = 1.0 / spec.rate_hz
    left = (state.jump_left or 0.0) - dt  # None: a snapshot from before jumps existed
    if left > 0.0 and state.jump is not None:
        return state.jump, left
    counter = np.array([0, MULTIPATH_SAMPLES + state.sample, 0, 0], dtype=np.uint64)
    g = np.random.Generator(np.random.Philox(key=key, counter=counter))
    u = g.random(2)
    offset = m.sigma * g.standard_normal(2)
    if u[0] >= -math.expm1(-m.rate_hz * dt):
        return np.zeros(2), 0.0
    return offset, -m.duration * math.log1p(-u[1])


def measure_heading(spec: GnssSpec, key: np.ndarray, sample: int,
                    orientation: np.ndarray) -> float | None:
    """The yaw (rad, ENU, in (-pi, pi]) of fix number ``sample`` from the heading baseline.

    None when the receiver has no baseline, or it is too steep for a heading (its horizontal
    part under :data:`MIN_HORIZONTAL` of its length).

    Args:
        spec: the receiver (its ``heading_baseline`` and ``noise.heading_sigma``).
        key: its noise stream (:func:`.noise.stream_key`).
        sample: the fix's index (the state's ``sample`` before the fix).
        orientation: (4,) the boat's attitude (x, y, z, w), body to world.
    """
    b = spec.heading_baseline
    if b is None:
        return None
    w = rotation_matrix(orientation) @ b
    if math.hypot(w[0], w[1]) < MIN_HORIZONTAL * float(np.linalg.norm(b)):
        return None
    noise = spec.noise.heading_sigma * float(standard_normal(key, HEADING_SAMPLES + sample,
                                                             1)[0])
    yaw = math.atan2(w[1], w[0]) - math.atan2(b[1], b[0]) + noise
    return math.remainder(yaw, 2.0 * math.pi)
