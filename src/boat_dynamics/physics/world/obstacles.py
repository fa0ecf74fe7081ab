"""The world's fixed obstacles: vertical prisms (extruded polygons) and cylinders.

Docks, piers, breakwaters and stretches of shore are prisms over a polygon; pilings and
fixed marks are cylinders. Each stands from the sea floor up to its ``top`` (m above the
calm surface, world z). A point is inside one when it is inside its plan shape and below its
top; the way out is horizontal (a hull landing on top of a dock is not modelled).

Geometry in the world frame (REP-103 ENU: x east, y north, z up), metres.

A point inside leaves through the nearest side (a prism's nearest edge, a cylinder's radius):
an obstacle must be thicker than twice the deepest a hull goes in (at most one step's
travel, 0.1 m at 10 m/s and 100 steps a second, at the default contact), or a hull past
its middle is pushed through. Which side a point came in by cannot be told from its
velocity alone (deep in a pier, moving on, is also moving toward its far side).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

__all__ = ["MIN_RESTITUTION", "ContactParams", "Cylinder", "Obstacle", "Prism", "World",
           "floor_depth", "inside_polygon", "penetration", "restitution_of", "signed_area"]


@dataclass(frozen=True)
class Prism:
    """A vertical prism over a simple polygon (a dock, a pier, a stretch of shore).

    Attributes:
        name: the obstacle's name (its marker; contact events).
        points: (P, 2) m, world x, y of the polygon's corners,
            counter-clockwise (:meth:`make` orders them), P >= 3.
        top: m, world z of its top.
        slope: the sea floor's gradient (rise / run) up to its foot, where the water's depth
            is zero: a shelving shore or a beach (:func:`floor_depth`); inf: a wall standing
            on the sea floor (a quay, a pier).
    """

    name: str
    points: np.ndarray
    top: float
    slope: float = math.inf

    @classmethod
    def make(cls, name: str, points, top: float, slope: float = math.inf) -> Prism:
        """A prism with its corners made counter-clockwise (positive signed area)."""
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        if signed_area(p) < 0.0:
            p = p[::-1].copy()
        return cls(name, p, float(top), float(slope))

    @cached_property
    def edges(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(P, 2) edge starts, (P, 2) edge vectors, (P, 2) unit outward normals (once)."""
        a = self.points
        e = np.roll(a, -1, axis=0) - a
        n = np.stack([e[:, 1], -e[:, 0]], axis=1) / np.hypot(e[:, 0], e[:, 1])[:, None]
        return a, e, n


@dataclass(frozen=True)
class Cylinder:
    """A vertical cylinder (a piling, a fixed mark).

    Attributes:
        name: the obstacle's name.
        center: (2,) m, world x, y of its axis.
        radius: m, > 0.
        top: m, world z of its top.
    """

    name: str
    center: np.ndarray
    radius: float
    top: float


Obstacle = Prism | Cylinder


#: The least restitution allowed: zeta = 0.73, so the damping's 2 zeta omega dt stays below
#: 0.92 at the stiffest contact allowed (omega dt = 2 pi / 10), where one step's damping
#: would otherwise reverse a point's speed (restitution 0.14 asked for returned 0.42). A
#: spring that only pushes returns at least e^-2 = 0.135 when critically damped.
MIN_RESTITUTION = 0.2


@dataclass(frozen=True)
class ContactParams:
    """How a boat meets an obstacle (:mod:`boat_dynamics.physics.force_models.collision`).

    Attributes:
        frequency_hz: Hz, the natural frequency of a boat's rigid mass on the contact's
            spring: its stiffness is m (2 pi f)^2, shared by the points in contact.
        restitution: in [:data:`MIN_RESTITUTION`, 1], the ratio of the speeds after and
            before a contact.
        friction: >= 0, Coulomb's coefficient along the obstacle's face.
        damping_ratio: zeta, derived: the damping that returns ``restitution`` of the speed
            (:func:`restitution_of`).
    """

    frequency_hz: float
    restitution: float = 0.2
    friction: float = 0.3
    damping_ratio: float = field(init=False)

    def __post_init__(self) -> None:
        if not MIN_RESTITUTION <= self.restitution <= 1.0:
            raise ValueError(f"restitution: {self.restitution}, must be in "
                             f"[{MIN_RESTITUTION:.4f}, 1]")
        lo, hi = 0.0, 1.0  # restitution_of falls from 1 to e^-2 over zeta in [0, 1]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if restitution_of(mid) > self.restitution else (lo, mid)
        object.__setattr__(self, "damping_ratio", 0.5 * (lo + hi))


def restitution_of(zeta: float) -> float:
    """The restitution of a spring and damper that pushes only (zeta in [0, 1]).

    The contact ends when its force k x + c x' falls to zero, not when x does, so it returns
    more than the free oscillator's exp(-zeta pi / sqrt(1 - zeta^2)) (Schwager and Poeschel,
    "Coefficient of restitution and linear-dashpot model revisited", Granular Matter 9
    (2007) 465-469). With beta = zeta omega_0, omega = omega_0 sqrt(1 - zeta^2), the end
    omega t_e solves tan(omega t_e) = -2 beta omega / (omega^2 - beta^2) in (pi/2, pi], and
    e = -exp(-beta t_e) (cos omega t_e - beta / omega sin omega t_e); e(1) = e^-2.
    """
    if zeta >= 1.0:
        return math.exp(-2.0)
    w = math.sqrt(1.0 - zeta * zeta)  # omega / omega_0
    end = math.atan2(2.0 * zeta * w, -(w * w - zeta * zeta))  # omega t_e in (pi/2, pi]
    if zeta == 0.0:
        end = math.pi
    return -math.exp(-zeta * end / w) * (math.cos(end) - zeta / w * math.sin(end))


@dataclass(frozen=True)
class World:
    """The fixed obstacles of a scenario, and how boats meet them (None: no obstacles)."""

    obstacles: tuple[Obstacle, ...] = ()
    contact: ContactParams | None = None

    @cached_property
    def shelving(self) -> float:
        """The gentlest shore's slope (rise / run; inf: no shore shelves; computed once)."""
        return min((o.slope for o in self.obstacles if isinstance(o, Prism)), default=math.inf)

    @cached_property
    def bounds(self) -> np.ndarray:
        """(5,) m: x min, x max, y min, y max, the highest top (NaNs with no obstacles; once)."""
        if not self.obstacles:
            return np.full(5, np.nan)
        lo, hi, top = [], [], []
        for o in self.obstacles:
            if isinstance(o, Prism):
                lo.append(o.points.min(axis=0))
                hi.append(o.points.max(axis=0))
            else:
                lo.append(o.center - o.radius)
                hi.append(o.center + o.radius)
            top.append(o.top)
        lo, hi = np.min(lo, axis=0), np.max(hi, axis=0)
        return np.array([lo[0], hi[0], lo[1], hi[1], max(top)])


def signed_area(points: np.ndarray) -> float:
    """m^2, the shoelace area of a polygon (P, 2): positive when counter-clockwise."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def penetration(world: World, xy: np.ndarray, z: np.ndarray, velocity: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """How deep each point is inside the obstacles, which way is out, and which obstacle.

    Args:
        world: the obstacles.
        xy: (N, 2) m, world x, y of the points.
        z: (N,) m, their world z (a point above an obstacle's top is outside it).
        velocity: (N, 2) m/s, their horizontal world velocities (a point on a cylinder's
            axis leaves against its motion).

    A prism of finite ``slope`` s also has its shelving floor, z = -s r at a distance r from
    its edge (:func:`floor_depth`): a point under it is (z_f - z) / sqrt(1 + s^2) deep along
    the floor's normal (s a, 1) / sqrt(1 + s^2), a the unit horizontal way from the shore's
    nearest point; a hull runs aground on it.

    Returns:
        (N,) m, the depth (0 outside every obstacle; the deepest where several), (N, 3) the
        unit outward normal there, world frame (horizontal from a wall, up and seaward from a
        shelving floor; zeros outside), and (N,) int the obstacle's index in
        ``world.obstacles`` (-1 outside).
    """
    depth = np.zeros(xy.shape[0])
    normal = np.zeros((xy.shape[0], 3))
    which = np.full(xy.shape[0], -1, dtype=np.intp)
    for k, o in enumerate(world.obstacles):
        d, n = (_in_prism(o, xy) if isinstance(o, Prism) else _in_cylinder(o, xy, velocity))
        found = [(np.where(z <= o.top, d, 0.0), np.pad(n, ((0, 0), (0, 1))))]
        if isinstance(o, Prism) and math.isfinite(o.slope):
            found.append(_under_floor(o, xy, z))
        for d, n in found:
            deeper = d > depth
            depth = np.where(deeper, d, depth)
            normal[deeper] = n[deeper]
            which[deeper] = k
    return depth, normal, which


def _under_floor(prism: Prism, xy: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N,) depth under ``prism``'s shelving floor (0 above it) and (N, 3) its unit normal."""
    off = _edge_offsets(prism, xy)  # from each edge's nearest point
    dist = np.hypot(off[..., 0], off[..., 1])
    way = np.argmin(dist, axis=1)
    rows = np.arange(xy.shape[0])
    r, away = dist[rows, way], off[rows, way]
    outside = ~inside_polygon(prism.points, xy) & (r > 0.0)
    s = prism.slope
    scale = math.sqrt(1.0 + s * s)
    depth = np.where(outside, (-s * r - z) / scale, 0.0)
    depth = np.maximum(depth, 0.0)
    normal = np.zeros((xy.shape[0], 3))
    with np.errstate(invalid="ignore", divide="ignore"):
        normal[:, :2] = np.where(outside[:, None], s * away / r[:, None], 0.0)
    normal[:, 2] = 1.0
    return depth, normal / scale


def floor_depth(world: World, xy: np.ndarray, depth: float) -> np.ndarray:
    """(N,) m: the water's depth at ``xy`` (N, 2) m, world x, y, over a floor shelving to shore.

    The sea floor is at ``depth`` (m, the ocean's; inf: deep) but rises towards each prism of
    finite ``slope`` s: at a distance r from its edge the water is s r deep (0 at its foot
    and inside it), the shallowest where several meet.
    """
    out = np.full(xy.shape[0], float(depth))
    for o in world.obstacles:
        if isinstance(o, Prism) and math.isfinite(o.slope):
            dist = _edge_distances(o, xy).min(axis=1)
            out = np.minimum(out, np.where(inside_polygon(o.points, xy), 0.0, o.slope * dist))
    return out


def _edge_offsets(prism: Prism, xy: np.ndarray) -> np.ndarray:
    """(N, P, 2) m: each point less its nearest point on each edge of ``prism``."""
    a, e, _ = prism.edges
    rel = xy[:, None, :] - a[None, :, :]  # (N, P, 2)
    t = np.clip(np.einsum("npk,pk->np", rel, e) / np.einsum("pk,pk->p", e, e), 0.0, 1.0)
    return rel - t[..., None] * e[None]


def _edge_distances(prism: Prism, xy: np.ndarray) -> np.ndarray:
    """(N, P) m: each point's distance to each edge of ``prism``."""
    return np.hypot(*np.moveaxis(_edge_offsets(prism, xy), -1, 0))


def _in_prism(prism: Prism, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N,) depth inside ``prism`` (0 outside) and (N, 2) the outward normal of the way out."""
    _, _, n = prism.edges
    inside = inside_polygon(prism.points, xy)
    dist = _edge_distances(prism, xy)
    way = np.argmin(dist, axis=1)
    depth = np.where(inside, dist[np.arange(xy.shape[0]), way], 0.0)
    return depth, np.where(inside[:, None], n[way], 0.0)


def inside_polygon(points: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """(N,) bool: each of ``xy`` (N, 2) inside the polygon ``points`` (P, 2).

    The crossing number: the edges straddling the point's y that cross its line to its right.
    """
    a, e = points, np.roll(points, -1, axis=0) - points
    y0, y1 = a[None, :, 1], a[None, :, 1] + e[None, :, 1]
    straddle = (y0 <= xy[:, None, 1]) != (y1 <= xy[:, None, 1])
    with np.errstate(divide="ignore", invalid="ignore"):  # level edges: never straddle
        cross_x = a[None, :, 0] + (xy[:, None, 1] - y0) / e[None, :, 1] * e[None, :, 0]
    return np.count_nonzero(straddle & (xy[:, None, 0] < cross_x), axis=1) % 2 == 1


def _in_cylinder(cylinder: Cylinder, xy: np.ndarray, velocity: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(N,) depth inside ``cylinder`` (0 outside) and (N, 2) the outward radial normal."""
    rel = xy - cylinder.center
    r = np.hypot(rel[:, 0], rel[:, 1])
    inside = r < cylinder.radius
    speed = np.hypot(velocity[:, 0], velocity[:, 1])
    # on the axis: out against the velocity (or along x at rest)
    back = np.where(speed[:, None] > 0.0, -velocity / np.maximum(speed, 1e-300)[:, None],
                    np.array([1.0, 0.0]))
    with np.errstate(invalid="ignore", divide="ignore"):
        radial = np.where(r[:, None] > 0.0, rel / r[:, None], back)
    return (np.where(inside, cylinder.radius - r, 0.0),
            np.where(inside[:, None], radial, 0.0))
