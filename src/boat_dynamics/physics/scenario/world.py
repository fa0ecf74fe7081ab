"""The ``world`` section: fixed obstacles (polygons extruded upward, cylinders) and contact."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from boat_dynamics.physics.body.hull import cylinder_mesh
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

__all__ = ["BUOY_BALLAST", "BUOY_SCOPE", "MAX_BUOYS", "MAX_CORNERS", "MAX_OBSTACLES",
           "OBSTACLE_TYPES", "buoy_boats", "world_block"]

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
    only(d, key, ("obstacles", "buoys", "contact"))
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


#: At most this many buoys (each is a body the step moves, as a boat).
MAX_BUOYS = 1000
#: A buoy's default line: this many times the depth from its bottom to the anchor (a watch
#: circle of radius sqrt(1.05^2 - 1) = 0.32 of that depth).
BUOY_SCOPE = 1.05
#: A buoy's centre of mass above its bottom, in drafts: ballast low, so it floats upright
#: (GM = 0.2 draft + radius^2 / (4 draft) > 0).
BUOY_BALLAST = 0.3


def buoy_boats(raw: Any, depth: float, water_density: float) -> list[tuple[str, dict]]:
    """``world.buoys``: each buoy checked, and written as the boat block that makes it.

    A buoy is a body of the fleet like a boat (:class:`~.specs.BoatSpec` of kind ``buoy``): an
    upright cylinder hull floating at ``draft`` under the waves' Froude-Krylov pressure, held
    by an elastic anchor line (:mod:`boat_dynamics.physics.force_models.anchor_line`) from its
    bottom to an anchor ``anchor_depth`` under ``position``; no thrust, no rudder, no command
    topics. Boats meet it, lidars see it, AIS does not report it.

    Returns:
        (key, boat block) per buoy: read by :func:`.boat.boat_block` under the buoy's key.
    """
    key = "world.buoys"
    describe(key, None, "a list of buoys {name, position, radius, height, draft, "
             "anchor_depth, line_length}", default_doc="none")
    items = raw or []
    if not isinstance(items, list) or len(items) > MAX_BUOYS:
        raise ScenarioError(key, raw, f"must be a list of at most {MAX_BUOYS} buoys")
    return [(f"{key}[{i}]", _buoy(b, f"{key}[{i}]", depth, water_density))
            for i, b in enumerate(items)]


def _buoy(raw: Any, key: str, depth: float, water_density: float) -> dict:
    """One buoy's boat block (its keys checked here, by their own names)."""
    d = mapping(raw, key)
    only(d, key, ("name", "position", "radius", "height", "draft", "anchor_depth",
                  "line_length"))
    describe(f"{key}.name", None, f"{ROS_NAME_RULE}; unique among the boats and buoys",
             default_doc="required")
    if not is_ros_name(d.get("name")):
        raise ScenarioError(f"{key}.name", d.get("name"), f"must be {ROS_NAME_RULE}")
    x, y = vector(d, "position", key, 2, [0.0, 0.0], unit="m, world x, y: the anchor's and "
                  "where it floats at rest", bound=MAX_COORDINATE)
    radius = number(d, "radius", key, 0.4, 0.05, 50.0, unit="m")
    height = number(d, "height", key, 1.5, 0.1, 100.0, unit="m")
    draft = number(d, "draft", key, 0.5 * height, 0.0, height, low_open=True, unit="m",
                   default_doc="height / 2", range_doc="(0, height) m")
    if draft >= height:
        raise ScenarioError(f"{key}.draft", draft, f"must be less than the height ({height:g} m)"
                            ": a buoy floats")
    anchor_depth = number(d, "anchor_depth", key, min(10.0, depth), draft, depth,
                          low_open=True, unit="m under the surface",
                          default_doc="min(10, ocean.depth)",
                          range_doc="(draft, ocean.depth] m")
    reach = anchor_depth - draft  # the bottom's depth to the anchor, at rest
    length = number(d, "line_length", key, BUOY_SCOPE * reach, reach, 10.0 * reach,
                    unit="m, unstretched", default_doc=f"{BUOY_SCOPE:g} x (anchor_depth - "
                    "draft)", range_doc="[anchor_depth - draft, 10 (anchor_depth - draft)] m")
    mass = water_density * cylinder_mesh(radius, height).volume * draft / height
    return {"name": d["name"],
            "hull": {"type": "cylinder", "radius": radius, "height": height,
                     "subdivisions": 4},
            "mass": mass, "center_of_mass": [0.0, 0.0, -height / 2 + BUOY_BALLAST * draft],
            "buoyancy": {"model": "mesh", "pressure": "froude_krylov"},
            "hydrodynamics": {"coefficients": "none"},
            "rudder": {"model": "none"}, "commands": [{"t": 0.0, "thrust": 0.0, "rudder": 0.0}],
            "initial_pose": {"position": [x, y, height / 2 - draft]},
            "anchor_line": {"anchor": [x, y, -anchor_depth], "length": length}}


def _obstacle(raw: Any, key: str) -> Obstacle:
    """One obstacle: ``{name, type: polygon, points, top}`` or ``{name, type: cylinder, ...}``."""
    d = mapping(raw, key)
    kind = choice(d, "type", key, "polygon", OBSTACLE_TYPES)
    only(d, key, ("name", "type", "top")
         + (("points", "slope") if kind == "polygon" else ("center", "radius")))
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
    slope = number(d, "slope", key, 10.0, 0.0, 10.0, low_open=True,
                   unit="(the sea floor's rise / run up to the polygon's edge, where the water "
                   "is 0 m deep: a shelving shore, a beach)",
                   default_doc="none: a wall standing on the sea floor")
    slope = slope if "slope" in d else math.inf
    return Prism.make(name, _corners(d.get("points"), f"{key}.points"), top, slope)


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
