"""The ``world`` section: fixed obstacles (polygons extruded upward, cylinders) and contact."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from boat_dynamics.physics.scenario.read import (
    ROS_NAME_RULE,
    choice,
    describe,
    is_ros_name,
    mapping,
    number,
    only,
    vector,
)
from boat_dynamics.physics.scenario.specs import ScenarioError, SimulationSettings
from boat_dynamics.physics.world.obstacles import (
    MIN_RESTITUTION,
    ContactParams,
    Cylinder,
    Obstacle,
    Prism,
    World,
    signed_area,
)

__all__ = ["MAX_CORNERS", "MAX_OBSTACLES", "OBSTACLE_TYPES", "world_block"]

#: The obstacle types a scenario may name.
OBSTACLE_TYPES = ("polygon", "cylinder")
#: At most this many obstacles, and corners per polygon (the contact tests every corner).
MAX_OBSTACLES = 1000
MAX_CORNERS = 1000
#: m: every coordinate within this of the world origin (the datum).
MAX_COORDINATE = 1e7
#: The stiffest contact: 2 pi f dt <= 2 pi / 10, where the step keeps a bounce's restitution
#: within 0.04 of the one asked for (:mod:`boat_dynamics.physics.force_models.collision`).
MAX_FREQUENCY_SHARE = 1.0 / 10.0


def world_block(raw: Any, sim: SimulationSettings) -> World:
    """The ``world:`` block: ``obstacles`` (a list) and ``contact`` (how boats meet them)."""
    key = "world"
    d = mapping(raw, key)
    only(d, key, ("obstacles", "contact"))
    describe(f"{key}.obstacles", None, "a list of obstacles {name, type, ...}",
             default_doc="none")
    items = d.get("obstacles") or []
    if not isinstance(items, list) or len(items) > MAX_OBSTACLES:
        raise ScenarioError(f"{key}.obstacles", items,
                            f"must be a list of at most {MAX_OBSTACLES} obstacles")
    obstacles = tuple(_obstacle(o, f"{key}.obstacles[{i}]") for i, o in enumerate(items))
    names = [o.name for o in obstacles]
    for i, n in enumerate(names):
        if names.index(n) != i:
            raise ScenarioError(f"{key}.obstacles[{i}].name", n,
                                "must be unique among the obstacles")
    return World(obstacles, _contact(d.get("contact"), f"{key}.contact", sim.rate_hz))


def _obstacle(raw: Any, key: str) -> Obstacle:
    """One obstacle: ``{name, type: polygon, points, top}`` or ``{name, type: cylinder, ...}``."""
    d = mapping(raw, key)
    kind = choice(d, "type", key, "polygon", OBSTACLE_TYPES)
    only(d, key, ("name", "type", "top")
         + (("points",) if kind == "polygon" else ("center", "radius")))
    describe(f"{key}.name", None, f"{ROS_NAME_RULE}; unique among the obstacles",
             default_doc="required")
    name = d.get("name")
    if not is_ros_name(name):
        raise ScenarioError(f"{key}.name", name, f"must be {ROS_NAME_RULE}")
    top = number(d, "top", key, 2.0, -1000.0, 1000.0, unit="m (world z of its top)")
    if kind == "cylinder":
        center = vector(d, "center", key, 2, [0.0, 0.0], unit="m, world x, y",
                        bound=MAX_COORDINATE)
        radius = number(d, "radius", key, 0.5, 0.0, 1000.0, low_open=True, unit="m")
        return Cylinder(name, center, radius, top)
    return Prism.make(name, _corners(d.get("points"), f"{key}.points"), top)


def _corners(raw: Any, key: str) -> np.ndarray:
    """(P, 2) m: a simple polygon's corners (3 to :data:`MAX_CORNERS`, no edges crossing)."""
    describe(key, None, f"a list of 3 to {MAX_CORNERS} [x, y] m, world frame, within "
             f"+-{MAX_COORDINATE:g}: a simple polygon (no edges crossing; a corner repeated "
             "next to itself, as a closing first corner, counts once)", default_doc="required")
    ok = (isinstance(raw, list) and 3 <= len(raw) <= MAX_CORNERS
          and all(isinstance(p, list) and len(p) == 2
                  and all(isinstance(v, int | float) and not isinstance(v, bool) for v in p)
                  for p in raw))
    if not ok:
        raise ScenarioError(key, raw, f"must be a list of 3 to {MAX_CORNERS} [x, y] pairs of "
                                      "numbers")
    try:
        p = np.array(raw, dtype=float)
    except OverflowError:  # an integer of hundreds of digits
        p = np.array([[math.inf]])
    if not np.all(np.isfinite(p)) or np.any(np.abs(p) > MAX_COORDINATE):
        raise ScenarioError(key, raw, f"every coordinate must be finite and within "
                                      f"+-{MAX_COORDINATE:g} m")
    p = p[np.any(p != np.roll(p, -1, axis=0), axis=1)]  # a corner repeated (closing) once
    if p.shape[0] < 3:
        raise ScenarioError(key, raw, "must have 3 distinct corners")
    crossing = _crossing_edges(p)
    if crossing is not None:
        raise ScenarioError(key, raw, f"must be a simple polygon: edges {crossing[0]} and "
                                      f"{crossing[1]} cross")
    if abs(signed_area(p)) < 1e-6:
        raise ScenarioError(key, raw, "must enclose an area (its corners are not on one line)")
    return p


def _crossing_edges(p: np.ndarray) -> tuple[int, int] | None:
    """The first two non-adjacent edges of the closed polygon ``p`` (P, 2) that cross, or None."""
    a, b = p, np.roll(p, -1, axis=0)
    n = p.shape[0]

    def side(o, q, r):  # sign of the turn o -> q -> r, broadcast
        return np.sign((q[..., 0] - o[..., 0]) * (r[..., 1] - o[..., 1])
                       - (q[..., 1] - o[..., 1]) * (r[..., 0] - o[..., 0]))

    ai, bi, aj, bj = a[:, None], b[:, None], a[None, :], b[None, :]
    cross = ((side(ai, bi, aj) * side(ai, bi, bj) < 0)
             & (side(aj, bj, ai) * side(aj, bj, bi) < 0))
    i, j = np.nonzero(np.triu(cross, k=2))
    for u, v in zip(i, j, strict=True):
        if not (u == 0 and v == n - 1):  # the last edge meets the first at a corner
            return int(u), int(v)
    return None


def _contact(raw: Any, key: str, rate_hz: float) -> ContactParams:
    """``contact: {frequency_hz, restitution, friction}``; the frequency bounded by the rate."""
    d = mapping(raw, key)
    only(d, key, ("frequency_hz", "restitution", "friction"))
    high = rate_hz * MAX_FREQUENCY_SHARE
    frequency = number(d, "frequency_hz", key, rate_hz / 10.0, 0.0, high, low_open=True,
                       unit="Hz", default_doc="simulation.rate_hz / 10",
                       range_doc="(0, simulation.rate_hz / 10] Hz")
    restitution = number(d, "restitution", key, 0.2, MIN_RESTITUTION, 1.0)
    friction = number(d, "friction", key, 0.3, 0.0, 2.0)
    return ContactParams(frequency, restitution, friction)
