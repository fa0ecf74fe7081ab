"""Contact with the world's obstacles: a spring and damper at each hull point inside one.

A penalty contact (the discrete-element model of Cundall and Strack, Geotechnique 29 (1979)
47-65; Hunt and Crossley's linear limit): a hull point (a mesh vertex or a sample point)
``d`` m inside an obstacle (:func:`boat_dynamics.physics.world.obstacles.penetration`) is
pushed out along the obstacle's outward normal n with

    f_n = max(0, k d - c v_n) / N,    k = m (2 pi f)^2,    c = 2 zeta sqrt(k m),

v_n = n . u the point's normal velocity (u its world velocity), m the boat's rigid mass, f
the contact's natural frequency, zeta from the restitution (for a spring that only pushes:
:func:`~boat_dynamics.physics.world.obstacles.restitution_of`), and N the
number of the boat's points in contact: the boat meets an obstacle as one mass on one
spring, however fine its mesh. Along the face, Coulomb friction mu f_n against the point's
sliding velocity, regularised below :data:`SLIP` m/s.

Two boats meet the same way (:func:`hull_contact_wrench`): a point of one inside the other's
footprint prism (:mod:`boat_dynamics.physics.world.footprints`) is pushed out through the
nearest side, m the pair's reduced mass m_a m_b / (m_a + m_b), v_n the point's velocity
relative to the other hull's material point there; the other boat takes the opposite force
at the same point, so the contact conserves the pair's momentum and angular momentum.

A free mass at speed U stops within U / (2 pi f) m undamped (0.16 m at 10 m/s at the default
f = simulation.rate_hz / 10 = 10 Hz), and within one step's travel at the default
restitution; f <= rate / 10 keeps the step's bounce within 0.04 of the restitution asked
for (tests/boat_dynamics/physics/force_models/test_collision.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.wrench import sum_by_owner
from boat_dynamics.physics.world.footprints import Footprints, near_pairs
from boat_dynamics.physics.world.obstacles import ContactParams, World, penetration

__all__ = ["FLOOR_SOFTNESS", "SLIP", "BoatKinematics", "Touches", "collision_wrench",
           "hull_contact_wrench", "hull_touches", "touches"]

#: m/s: below this sliding speed the friction force grows linearly (regularised Coulomb).
SLIP = 0.05
#: A shelving floor's contact frequency, as a share of ``contact.frequency_hz``.
FLOOR_SOFTNESS = 0.25


@dataclass(frozen=True)
class Touches:
    """Each boat's deepest point in an obstacle (the contact events' content).

    Attributes:
        other: (G,) int, the obstacle's index in ``world.obstacles`` (-1: touching none).
        point: (G, 3) m, world frame, the boat's deepest point inside it.
        normal: (G, 3) the obstacle's unit outward normal there, world frame (horizontal
            from a wall, up and seaward from a shelving floor).
        depth: (G,) m, how deep it is.
        approach_speed: (G,) m/s, its speed into the obstacle (> 0 approaching).
    """

    other: np.ndarray
    point: np.ndarray
    normal: np.ndarray
    depth: np.ndarray
    approach_speed: np.ndarray

    @classmethod
    def empty(cls, count: int) -> Touches:
        """``count`` boats touching nothing."""
        return cls(np.full(count, -1, dtype=np.intp), np.zeros((count, 3)),
                   np.zeros((count, 3)), np.zeros(count), np.zeros(count))


@dataclass(frozen=True)
class _Inside:
    """The hull points inside an obstacle, and what the push needs of them."""

    who: np.ndarray  # (C,) int, their boats
    points: np.ndarray  # (C, 3) m, world
    arm: np.ndarray  # (C, 3) m, body frames, from the centre of mass
    rotation: np.ndarray  # (C, 3, 3) their boats' body to world
    velocity: np.ndarray  # (C, 3) m/s, world
    depth: np.ndarray  # (C,) m
    normal: np.ndarray  # (C, 3) unit, outward, world frame
    which: np.ndarray  # (C,) int, the obstacle


def collision_wrench(world: World, points: np.ndarray, body: np.ndarray, owner: np.ndarray,
                     count: int, rotation: np.ndarray, center_of_mass: np.ndarray,
                     velocity: np.ndarray, angular_velocity: np.ndarray, mass: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The obstacles' push on each boat of a group.

    Args:
        world: the obstacles and the contact's parameters.
        points: (E, 3) m, the hull points, world frame.
        body: (E, 3) m, the same points in their boats' body frames (from the reference point).
        owner: (E,) int, each point's boat in [0, count).
        count: G, the group's boats.
        rotation: (G, 3, 3) body to world.
        center_of_mass: (G, 3) m, body frames, from the reference point.
        velocity: (G, 3) m/s, body frames.
        angular_velocity: (G, 3) rad/s, body frames.
        mass: (G,) kg, rigid-body masses.

    Returns:
        (G, 3) N force and (G, 3) N m torque about the centres of mass, body frames (zero
        for a boat touching nothing).
    """
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    c = _inside(world, points, body, owner, rotation, center_of_mass, velocity,
                angular_velocity)
    if c is None or world.contact is None:
        return force, torque
    touching = np.bincount(c.who, minlength=count)
    share = mass[c.who] / touching[c.who]  # kg: each point's share of the boat
    # a shelving floor (its normal up) is softer: a sand or mud bottom, and a push under the
    # hull's ends, whose pitch and heave the step must resolve
    soft = np.where(c.normal[:, 2] > 0.0, FLOOR_SOFTNESS, 1.0)
    world_force = _point_forces(world.contact, share, c.depth, c.normal, c.velocity, soft)
    body_force = np.einsum("eji,ej->ei", c.rotation, world_force)
    force = sum_by_owner(body_force, c.who, count)
    torque = sum_by_owner(np.cross(c.arm, body_force), c.who, count)
    return force, torque


def _point_forces(params: ContactParams, share: np.ndarray, depth: np.ndarray,
                  normal: np.ndarray, velocity: np.ndarray, soft: np.ndarray | float = 1.0
                  ) -> np.ndarray:
    """(C, 3) N, world frame: the push on C points in contact (module docs).

    Args:
        params: the contact.
        share: (C,) kg, each point's share of the mass on the spring.
        depth: (C,) m, how deep each is.
        normal: (C, 3) the unit outward normals, world frame.
        velocity: (C, 3) m/s, their velocities relative to what they are in, world frame.
        soft: (C,) or a number, each contact's frequency as a share of the contact's.
    """
    omega = 2.0 * math.pi * params.frequency_hz * soft
    v_n = np.einsum("ek,ek->e", normal, velocity)
    f_n = np.maximum(0.0, share * omega * (omega * depth - 2.0 * params.damping_ratio * v_n))
    slide = velocity - v_n[:, None] * normal
    speed = np.sqrt(np.einsum("ek,ek->e", slide, slide))
    friction = -params.friction * f_n[:, None] * slide / np.maximum(speed, SLIP)[:, None]
    return f_n[:, None] * normal + friction


def touches(world: World, points: np.ndarray, body: np.ndarray, owner: np.ndarray,
            count: int, rotation: np.ndarray, center_of_mass: np.ndarray,
            velocity: np.ndarray, angular_velocity: np.ndarray) -> Touches:
    """Each boat's deepest point in an obstacle: arguments as :func:`collision_wrench`'s."""
    out = Touches.empty(count)
    c = _inside(world, points, body, owner, rotation, center_of_mass, velocity,
                angular_velocity)
    if c is None:
        return out
    order = np.lexsort((-c.depth, c.who))  # by boat, deepest first
    first = order[np.r_[True, c.who[order][1:] != c.who[order][:-1]]]
    b = c.who[first]
    out.other[b] = c.which[first]
    out.point[b] = c.points[first]
    out.normal[b] = c.normal[first]
    out.depth[b] = c.depth[first]
    out.approach_speed[b] = -np.einsum("ek,ek->e", c.normal[first], c.velocity[first])
    return out


def _inside(world: World, points: np.ndarray, body: np.ndarray, owner: np.ndarray,
            rotation: np.ndarray, center_of_mass: np.ndarray, velocity: np.ndarray,
            angular_velocity: np.ndarray) -> _Inside | None:
    """The hull points inside an obstacle (None: none is)."""
    near = _near(world, points)
    if not near.any():
        return None
    e, who = np.flatnonzero(near), owner[near]
    arm = body[e] - center_of_mass[who]  # body frame, from the centre of mass
    rot = rotation[who]
    u = np.einsum("eij,ej->ei", rot, velocity[who] + np.cross(angular_velocity[who], arm))
    depth, normal, which = penetration(world, points[e, :2], points[e, 2], u[:, :2])
    inside = depth > 0.0
    if not inside.any():
        return None
    return _Inside(who[inside], points[e[inside]], arm[inside], rot[inside], u[inside],
                   depth[inside], normal[inside], which[inside])


def _near(world: World, points: np.ndarray) -> np.ndarray:
    """(E,) bool: the points within the obstacles' bounding box (the only ones that can touch).

    The box reaches out past a shelving shore as far as its floor is as deep as the point.
    """
    if not world.obstacles:
        return np.zeros(points.shape[0], dtype=bool)
    x0, x1, y0, y1, top = world.bounds
    reach = np.maximum(-points[:, 2], 0.0) / world.shelving  # 0 without a shelving shore
    return ((points[:, 0] >= x0 - reach) & (points[:, 0] <= x1 + reach)
            & (points[:, 1] >= y0 - reach) & (points[:, 1] <= y1 + reach)
            & (points[:, 2] <= top))


@dataclass(frozen=True)
class BoatKinematics:
    """Every boat's pose and motion, and where its contact points are.

    Attributes:
        rotation: (B, 3, 3) body to world.
        reference: (B, 3) m, the hull reference points, world frame.
        center_of_mass: (B, 3) m, body frames, from the reference points.
        velocity: (B, 3) m/s, body frames.
        angular_velocity: (B, 3) rad/s, body frames.
        mass: (B,) kg, rigid-body masses.
        body: (E, 3) m, the contact points (:attr:`Footprints.points`), body frames.
        starts: (B + 1,) int, boat b's points are rows starts[b] to starts[b + 1].
    """

    rotation: np.ndarray
    reference: np.ndarray
    center_of_mass: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    mass: np.ndarray
    body: np.ndarray
    starts: np.ndarray

    def points(self, boat: int) -> tuple[np.ndarray, np.ndarray]:
        """(n, 3) m world and (n, 3) m body positions of ``boat``'s contact points."""
        body = self.body[self.starts[boat]:self.starts[boat + 1]]
        return self.reference[boat] + body @ self.rotation[boat].T, body


@dataclass(frozen=True)
class _Overlap:
    """Boat a's points inside boat b's footprint prism."""

    a: int
    b: int
    points: np.ndarray  # (C, 3) m, world
    arm_a: np.ndarray  # (C, 3) m, a's body frame, from a's centre of mass
    arm_b: np.ndarray  # (C, 3) m, b's body frame, from b's centre of mass
    depth: np.ndarray  # (C,) m
    normal: np.ndarray  # (C, 3) b's outward normal, world
    velocity: np.ndarray  # (C, 3) m/s, a's points relative to b's material points, world


def hull_contact_wrench(params: ContactParams, footprints: Footprints, boats: BoatKinematics
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The boats' pushes on each other (module docs).

    Returns:
        (B, 3) N force and (B, 3) N m torque about the centres of mass, body frames.
    """
    count = boats.mass.shape[0]
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    overlaps = _overlaps(footprints, boats)
    touching: dict[tuple[int, int], int] = {}  # a pair's points in contact, both ways
    for o in overlaps:
        pair = (min(o.a, o.b), max(o.a, o.b))
        touching[pair] = touching.get(pair, 0) + o.depth.shape[0]
    for o in overlaps:
        m_a, m_b = boats.mass[o.a], boats.mass[o.b]
        share = np.full(o.depth.shape[0],
                        m_a * m_b / (m_a + m_b) / touching[(min(o.a, o.b), max(o.a, o.b))])
        push = _point_forces(params, share, o.depth, o.normal, o.velocity)  # on a, world
        for boat, arm, sign in ((o.a, o.arm_a, 1.0), (o.b, o.arm_b, -1.0)):
            body = sign * push @ boats.rotation[boat]  # R^T f, row by row
            force[boat] += body.sum(axis=0)
            torque[boat] += np.cross(arm, body).sum(axis=0)
    return force, torque


def hull_touches(footprints: Footprints, boats: BoatKinematics) -> Touches:
    """Each boat's deepest point in another boat's hull; ``other`` is that boat's index."""
    count = boats.mass.shape[0]
    out = Touches.empty(count)
    for o in _overlaps(footprints, boats):
        k = int(np.argmax(o.depth))
        for boat, other, sign in ((o.a, o.b, 1.0), (o.b, o.a, -1.0)):
            if o.depth[k] > out.depth[boat]:
                out.other[boat], out.point[boat] = other, o.points[k]
                out.normal[boat] = sign * o.normal[k]
                out.depth[boat] = o.depth[k]
                out.approach_speed[boat] = -float(o.normal[k] @ o.velocity[k])
    return out


def _overlaps(footprints: Footprints, boats: BoatKinematics) -> list[_Overlap]:
    """Every pair's points inside the other's footprint, both ways."""
    out = []
    for i, j in near_pairs(boats.reference[:, :2], footprints.radius).tolist():
        for a, b in ((i, j), (j, i)):
            o = _overlap(a, b, footprints, boats)
            if o is not None:
                out.append(o)
    return out


def _overlap(a: int, b: int, footprints: Footprints, boats: BoatKinematics
             ) -> _Overlap | None:
    """Boat a's hull points inside boat b's footprint prism, or None."""
    world, body = boats.points(a)
    rot_a, rot_b = boats.rotation[a], boats.rotation[b]
    q = (world - boats.reference[b]) @ rot_b  # in b's body frame
    corners, normals = footprints.corners[b], footprints.normals[b]
    out = np.einsum("npk,pk->np", q[:, None, :2] - corners[None], normals)  # (n, P)
    low, high = footprints.z[b]
    inside = np.all(out < 0.0, axis=1) & (q[:, 2] >= low) & (q[:, 2] <= high)
    if not inside.any():
        return None
    out, q, world, body = out[inside], q[inside], world[inside], body[inside]
    side = np.argmax(out, axis=1)  # the nearest side's line
    normal = np.zeros((q.shape[0], 3))
    normal[:, :2] = normals[side]
    arm_a = body - boats.center_of_mass[a]
    arm_b = q - boats.center_of_mass[b]
    u_a = (boats.velocity[a] + np.cross(boats.angular_velocity[a], arm_a)) @ rot_a.T
    u_b = (boats.velocity[b] + np.cross(boats.angular_velocity[b], arm_b)) @ rot_b.T
    return _Overlap(a, b, world, arm_a, arm_b, -out[np.arange(q.shape[0]), side],
                    normal @ rot_b.T, u_a - u_b)
