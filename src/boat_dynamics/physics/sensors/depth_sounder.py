"""A depth sounder (echo sounder): the range from its transducer to the sea floor, with noise.

The transducer at ``position`` (body frame, from the hull reference point) looks along the
body's -z axis, so its beam tilts with the boat's roll and pitch. The floor is flat, at the
ocean's depth h below the mean water level (z = -h, world frame; ``ocean.depth``). With p the
transducer's world position and d = R (0, 0, -1) the beam's world direction, the beam meets
the floor at the range

    r = (p_z + h) / (-d_z)

(a level boat: h minus the transducer's depth below the mean level; tilted by theta:
(p_z + h) / cos(theta), cos(theta) = -d_z). The reading is r plus white noise of
``range_sigma`` (m). The beam's axis alone is traced: the cone of ``field_of_view`` is reported
(as ``sensor_msgs/Range`` carries it), not searched for a nearer echo; the water column is not
checked either (a transducer lifted clear of the water by a wave still reads).

As REP-117 and ``sensor_msgs/Range`` ask: no echo within ``max_range`` (deep water, the beam
at or above the horizontal, a reading beyond the range) is +inf; a reading nearer than
``min_range`` (the floor inside the transducer's blanking distance) is -inf. Defaults: a
200 kHz recreational sounder, 10 deg cone, 0.5-200 m, 0.05 m of noise, 10 Hz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["DepthReading", "DepthSounderSpec", "measure_depth", "slant_range"]


@dataclass(frozen=True)
class DepthSounderSpec:
    """A depth sounder on a boat.

    Attributes:
        name: its name: topic ``<ns>/<name>/data``, frame ``<ns>/<name>_link``.
        rate_hz: readings per simulated second.
        position: (3,) m, body frame, the transducer's point from the hull reference point.
        field_of_view: rad, the beam's full cone angle (reported, not traced).
        min_range: m, the nearest range it reads (nearer: -inf).
        max_range: m, the farthest range it reads (farther, or no echo: +inf).
        range_sigma: m, white noise, 1 sigma.
        dropout: the probability that a reading is lost (not published).
        latency: s, from a reading (its stamp) to its publication.
    """

    name: str = "depth_sounder"
    rate_hz: float = 10.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    field_of_view: float = math.radians(10.0)
    min_range: float = 0.5
    max_range: float = 200.0
    range_sigma: float = 0.05
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class DepthReading:
    """One reading, as ``sensor_msgs/Range`` carries it.

    Attributes:
        range: m, along the beam; +inf: no echo within max_range; -inf: nearer than min_range.
        variance: m^2, of the noise.
    """

    range: float
    variance: float


def slant_range(transducer: np.ndarray, orientation: np.ndarray, depth: float) -> float:
    """m, from the transducer along the body's -z axis to the floor at z = -``depth``.

    Args:
        transducer: (3,) m, its world position.
        orientation: (4,) the boat's attitude (x, y, z, w), body to world.
        depth: m, the ocean's depth below the mean water level (inf: deep water).

    Returns:
        The range, m (0 when the transducer is at or below the floor); inf when the beam never
        meets the floor (deep water, or pointing at or above the horizontal).
    """
    down = rotation_matrix(orientation)[2, 2]  # -d_z = R_zz: cos of the beam's tilt
    if math.isinf(depth) or down <= 0.0:
        return math.inf
    return max(0.0, float(transducer[2]) + depth) / down


def measure_depth(spec: DepthSounderSpec, key: np.ndarray, sample: int, transducer: np.ndarray,
                  orientation: np.ndarray, depth: float) -> DepthReading:
    """Reading number ``sample`` (no state: white noise only); arguments as :func:`slant_range`.

    ``key``: its noise stream (:func:`.noise.stream_key`).
    """
    value = slant_range(transducer, orientation, depth) + spec.range_sigma * float(
        standard_normal(key, sample, 1)[0])
    if value > spec.max_range:
        value = math.inf
    elif value < spec.min_range:
        value = -math.inf
    return DepthReading(range=value, variance=spec.range_sigma ** 2)
