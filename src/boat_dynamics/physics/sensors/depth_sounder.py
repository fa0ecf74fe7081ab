"""A depth sounder (echo sounder): the range from its transducer to the sea floor, with noise.

The transducer at ``position`` (body frame, from the hull reference point) looks along the
body's -z axis, so its beam tilts with the boat's roll and pitch. The floor lies level at the
ocean's depth h below the mean water level (z = -h, world frame; ``ocean.depth``), or shelving
up to a shore (a polygon obstacle's ``slope``: :func:`slant_range`). With p the
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
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["FLOOR_ROUNDS", "FLOOR_TOLERANCE", "DepthReading", "DepthSounderSpec",
           "measure_depth", "slant_range"]


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


#: Fixed-point rounds of a beam against a shelving floor, and the range they settle to, m.
FLOOR_ROUNDS = 50
FLOOR_TOLERANCE = 1e-9


def slant_range(transducer: np.ndarray, orientation: np.ndarray, depth: float,
                floor: Callable[[np.ndarray], float] | None = None) -> float:
    """m, from the transducer along the body's -z axis to the floor at z = -``depth``.

    With ``floor`` (the water's depth at a world x, y: a floor shelving to a shore,
    :func:`boat_dynamics.physics.world.obstacles.floor_depth`), the beam p + r d meets
    z = -floor(p_xy + r d_xy): r is the fixed point of r = (p_z + floor(p_xy + r d_xy)) / -d_z,
    which converges while the floor's slope times the beam's tilt, tan(theta), is under 1.

    Args:
        transducer: (3,) m, its world position.
        orientation: (4,) the boat's attitude (x, y, z, w), body to world.
        depth: m, the ocean's depth below the mean water level (inf: deep water).
        floor: the water's depth (m) at a world (2,) x, y, or None: ``depth`` everywhere.

    Returns:
        The range, m (0 when the transducer is at or below the floor); inf when the beam never
        meets the floor (deep water, or pointing at or above the horizontal).
    """
    beam = -rotation_matrix(orientation)[:, 2]  # the body's -z axis, world frame
    down = -beam[2]  # cos of the beam's tilt
    here = depth if floor is None else floor(transducer[:2])
    if down <= 0.0 or math.isinf(here):
        return math.inf
    r = max(0.0, float(transducer[2]) + here) / down
    if floor is None:
        return r
    for _ in range(FLOOR_ROUNDS):
        below = floor(transducer[:2] + r * beam[:2])
        if math.isinf(below):
            return math.inf
        after = max(0.0, float(transducer[2]) + below) / down
        if abs(after - r) <= FLOOR_TOLERANCE:
            return after
        r = after
    return r


def measure_depth(spec: DepthSounderSpec, key: np.ndarray, sample: int, transducer: np.ndarray,
                  orientation: np.ndarray, depth: float,
                  floor: Callable[[np.ndarray], float] | None = None) -> DepthReading:
    """Reading number ``sample`` (no state: white noise only); arguments as :func:`slant_range`.

    ``key``: its noise stream (:func:`.noise.stream_key`).
    """
    value = slant_range(transducer, orientation, depth, floor) + spec.range_sigma * float(
        standard_normal(key, sample, 1)[0])
    if value > spec.max_range:
        value = math.inf
    elif value < spec.min_range:
        value = -math.inf
    return DepthReading(range=value, variance=spec.range_sigma ** 2)
