"""Slamming: the force of the water a hull sets in motion as its wetted waterline widens fast.

Momentum theory (von Karman 1929; Wagner 1932; Faltinsen, "Hydrodynamics of High-Speed Marine
Vehicles", 2005, sec. 8.2): a section entering the water at vertical speed V carries the 2-D
added mass of a flat plate of its wetted width b, m_a = rho pi b^2 / 8 per unit length, and the
water's momentum m_a V grows; at a speed that changes slowly the force is V dm_a/dt. Strip
theory adds the sections along the hull::

    m_a(t) = rho (pi / 8) k^2 integral b(x, t)^2 dx,    F_z = max(-w, 0) dm_a/dt  (upward)

with b(x, t) the width of the hull's waterline at station x (measured on the hull, where it
crosses the water surface, at :data:`STATIONS` equally spaced stations), w the hull's vertical
velocity relative to the water, and k = 1 (``geometric``: von Karman's wetted width) or
pi / 2 (``wagner``: the water piles up along the hull, Wagner's wetted width). For a wedge of
deadrise beta dropped at constant speed V this is exactly von Karman's
F = rho pi V^3 t L / tan^2(beta), or Wagner's (pi / 2)^2 times it. dm_a/dt is the change of
m_a since the previous step over its time (the previous m_a is state:
:attr:`boat_dynamics.physics.core.system.FleetState.slamming`); the force acts only while the
waterline widens with the hull moving down into the water, at the centroid of the waterline.
A hull with vertical sides heaving in calm water keeps its waterline, so feels none; a flat
bottom re-entering the water gets m_a V in one step (the impulse of von Karman's flat plate).

Kerner's model (``kerner``; Kerner, "Water interaction model for boats in video games: part 2",
Game Developer, 2016; as the Habrador tutorial the seed notes cite implements it), per hull
triangle i of area A_i with submerged area S_i and centre velocity v_i (over ground)::

    Gamma_i = |S_i v_i - (S_i v_i)_previous step| / (A_i dt)        (m/s^2)
    F_i = -clamp(Gamma_i / Gamma_max, 0, 1)^p cos(theta_i) F_stop,i    (cos = n_i . v_i / |v_i|)
    F_stop,i = m v_i (2 S_i / S) / dt                                (S: the hull's area)

only on triangles moving along their outward normal (cos > 0), at their centres: the force
that would stop the triangle's share of the boat in one step, ramped by how fast its swept
water volume changes. Dimensioned here (the tutorial's F_stop omits 1 / dt). It is a game
model: it scales as m / dt and with V^(2 p + 1) (Gamma ~ V^2 at constant speed), so it cannot
follow von Karman (V^3) across speeds or time steps; the tests record how far apart they are.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.wrench import Real, Wrench, cross, per_element, sum_by_owner

__all__ = ["SLAMMING_MODELS", "STATIONS", "Slamming", "SlammingModel", "kerner_wrench",
           "slamming_wrench", "swept_volumes", "wetted_added_mass"]

#: ``none``; momentum theory with von Karman's (``geometric``) or Wagner's wetted width; or
#: Kerner's per-triangle model (``kerner``, the seed notes' article).
SlammingModel = Literal["none", "geometric", "wagner", "kerner"]
SLAMMING_MODELS: tuple[SlammingModel, ...] = get_args(SlammingModel)

_PILE_UP = {"geometric": 1.0, "wagner": np.pi / 2.0}


#: Sections along the hull length whose waterline widths are summed.
STATIONS = 40


@dataclass(frozen=True)
class Slamming:
    """Slamming options of a mesh hull.

    Attributes:
        model: :data:`SlammingModel`.
        power: p of Kerner's ramp (``kerner``), > 0.
        acceleration_max: Gamma_max, m/s^2, of Kerner's ramp (``kerner``), > 0.
    """

    model: SlammingModel = "none"
    power: Real = 2.0
    acceleration_max: Real = 50.0


def _crossings(faces: np.ndarray, world: np.ndarray, depths: np.ndarray, face_owner: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Waterline segments: where each triangle with corners on both sides crosses the surface.

    Returns:
        (S, 3) and (S, 3) m, the segments' ends, world frame, and (S,) their boats.
    """
    d = depths[faces]  # (F, 3)
    wet = d > 0.0
    mixed = wet.any(axis=1) & ~wet.all(axis=1)
    f, d, owner = faces[mixed], d[mixed], face_owner[mixed]
    p = world[f]  # (S, 3 corners, 3)
    ends = []
    for j in range(3):  # the edge j -> j + 1 crosses where its corners' signs differ
        k = (j + 1) % 3
        crossed = (d[:, j] > 0.0) != (d[:, k] > 0.0)
        t = d[:, j] / np.where(crossed, d[:, j] - d[:, k], 1.0)
        ends.append((crossed, p[:, j] + t[:, None] * (p[:, k] - p[:, j])))
    # a mixed triangle crosses exactly two of its edges: take them in edge order
    first = np.where(ends[0][0][:, None], ends[0][1], ends[1][1])
    second = np.where(ends[2][0][:, None], ends[2][1], ends[1][1])
    return first, second, owner


def wetted_added_mass(model: Slamming, faces: np.ndarray, world: np.ndarray,
                      depths: np.ndarray, face_owner: np.ndarray, rotation: np.ndarray,
                      reference: np.ndarray, length: np.ndarray, water_density: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Strip theory's added mass of the wetted waterline, and the waterline's centroid.

    Args:
        model: the slamming options (``geometric`` or ``wagner``).
        faces: (F, 3) int, the group's hull triangles.
        world: (V, 3) m, their vertices, world frame.
        depths: (V,) m, surface height minus vertex height.
        face_owner: (F,) int, the boat of each triangle.
        rotation: (G, 3, 3) body-to-world rotations.
        reference: (G, 3) m, world hull reference points.
        length: (G,) m, hull lengths.
        water_density: (G,) kg/m^3.

    Returns:
        (G,) kg, rho (pi / 8) k^2 sum_j b_j^2 dx, and (G, 3) m the length-weighted centroid of
        the waterline segments, world frame (the reference point for a boat with none).
    """
    count, n = rotation.shape[0], STATIONS
    a, b, owner = _crossings(faces, world, depths, face_owner)
    body_a = np.einsum("sji,sj->si", rotation[owner], a - reference[owner])
    body_b = np.einsum("sji,sj->si", rotation[owner], b - reference[owner])
    dx = length / n
    x = (np.arange(n) + 0.5)[None, :] * dx[owner][:, None] - length[owner][:, None] / 2
    span = body_b[:, 0] - body_a[:, 0]
    u = (x - body_a[:, :1]) / np.where(np.abs(span) > 1e-12, span, np.inf)[:, None]
    inside = (u >= 0.0) & (u <= 1.0) & (np.abs(span) > 1e-12)[:, None]
    y = body_a[:, 1:2] + u * (body_b[:, 1] - body_a[:, 1])[:, None]
    slot = (owner[:, None] * n + np.arange(n)[None, :])[inside]
    low, high = np.full(count * n, np.inf), np.full(count * n, -np.inf)
    np.minimum.at(low, slot, y[inside])
    np.maximum.at(high, slot, y[inside])
    width = np.where(high > low, high - low, 0.0).reshape(count, n)
    k = _PILE_UP[model.model]
    added = water_density * (np.pi / 8.0) * k * k * (width**2).sum(axis=1) * dx
    seg = np.linalg.norm(b - a, axis=1)
    weights = np.bincount(owner, seg, minlength=count)
    mid = np.stack([np.bincount(owner, seg * (a[:, i] + b[:, i]) / 2.0, minlength=count)
                    for i in range(3)], axis=1)
    centroid = np.where(weights[:, None] > 0.0, mid / np.where(weights > 0.0, weights,
                                                                 1.0)[:, None], reference)
    return added, centroid


def slamming_wrench(added: np.ndarray, before: np.ndarray, elapsed: np.ndarray,
                    vertical_velocity: np.ndarray, centroid: np.ndarray,
                    center_of_mass: np.ndarray, rotation: np.ndarray) -> Wrench:
    """Slamming force and torque about the centres of mass, body frames.

    Args:
        added: (G,) kg, the wetted added mass now (:func:`wetted_added_mass`).
        before: (G,) kg, at the previous step.
        elapsed: (G,) s since the previous step (0: none yet, no force).
        vertical_velocity: (G,) m/s, the hulls' vertical velocity relative to the water.
        centroid: (G, 3) m, where the force acts (the waterline's centroid), world frame.
        center_of_mass: (G, 3) m, world frame.
        rotation: (G, 3, 3) body-to-world rotations.
    """
    ready = elapsed > 0.0  # a hull with no previous step yet feels none
    rate = np.where(ready, np.maximum(added - before, 0.0) / np.where(ready, elapsed, 1.0), 0.0)
    world = np.zeros_like(centroid)
    world[:, 2] = rate * np.maximum(-vertical_velocity, 0.0)
    torque = cross(centroid - center_of_mass, world)
    return Wrench(np.einsum("gji,gj->gi", rotation, world),
                  np.einsum("gji,gj->gi", rotation, torque))


def swept_volumes(faces: np.ndarray, world: np.ndarray, face_owner: np.ndarray,
                  wet_faces: np.ndarray, wet_areas: np.ndarray, velocity: np.ndarray,
                  angular_velocity: np.ndarray, center_of_mass: np.ndarray
                  ) -> tuple[np.ndarray, ...]:
    """Kerner's swept-volume rates S_i v_i of a group's hull triangles, and what goes with them.

    Args:
        faces: (F, 3) int, the triangles.
        world: (V, 3) m, their vertices, world frame.
        face_owner: (F,) int, the boat of each triangle.
        wet_faces: (T,) int, the triangle each wet part comes from.
        wet_areas: (T,) m^2, the wet parts' areas.
        velocity: (G, 3) m/s, centre-of-mass velocities, world frame.
        angular_velocity: (G, 3) rad/s, world frame.
        center_of_mass: (G, 3) m, world frame.

    Returns:
        (F, 3) m^3/s S_i v_i, (F, 3) m/s v_i, (F, 3) m centres, (F,) m^2 S_i, (F, 3) m^2
        vector areas (area times outward normal), world frame.
    """
    corners = world[faces]  # (F, 3, 3)
    centres = corners.mean(axis=1)
    vector_areas = 0.5 * cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    arms = centres - center_of_mass[face_owner]
    v = velocity[face_owner] + cross(angular_velocity[face_owner], arms)
    wet = np.bincount(wet_faces, wet_areas, minlength=faces.shape[0])
    return wet[:, None] * v, v, centres, wet, vector_areas


def kerner_wrench(model: Slamming, swept: tuple[np.ndarray, ...], before: np.ndarray,
                  face_owner: np.ndarray, elapsed: np.ndarray, mass: np.ndarray,
                  center_of_mass: np.ndarray, rotation: np.ndarray) -> Wrench:
    """Kerner's slamming force and torque about the centres of mass, body frames.

    Args:
        model: the options (``power``, ``acceleration_max``: scalars or (G,)).
        swept: :func:`swept_volumes` now.
        before: (F, 3) m^3/s, S_i v_i at the previous step (``swept[0]`` itself: none).
        face_owner: (F,) int.
        elapsed: (G,) s since the previous step (0: none yet, no force).
        mass: (G,) kg.
        center_of_mass: (G, 3) m, world frame.
        rotation: (G, 3, 3) body-to-world rotations.
    """
    now, v, centres, wet, vector_areas = swept
    count = rotation.shape[0]
    dt = elapsed[face_owner]
    area = np.linalg.norm(vector_areas, axis=1)
    hull = np.bincount(face_owner, area, minlength=count)[face_owner]
    ready = (dt > 0.0) & (area > 0.0)
    safe_dt = np.where(ready, dt, 1.0)
    gamma = np.linalg.norm(now - before, axis=1) / (np.where(ready, area, 1.0) * safe_dt)
    speed = np.linalg.norm(v, axis=1)
    cos = np.einsum("fi,fi->f", vector_areas, v) / np.where(speed * area > 0.0, speed * area,
                                                             np.inf)
    ramp = np.clip(gamma / per_element(model.acceleration_max, face_owner), 0.0, 1.0)
    factor = ramp ** per_element(model.power, face_owner) * np.maximum(cos, 0.0) * ready
    stop = (mass[face_owner] * 2.0 * wet / hull / safe_dt)[:, None] * v
    force = -factor[:, None] * stop
    torque = cross(centres - center_of_mass[face_owner], force)
    sums = sum_by_owner(np.concatenate([force, torque], axis=1), face_owner, count)
    return Wrench(np.einsum("gji,gj->gi", rotation, sums[:, :3]),
                  np.einsum("gji,gj->gi", rotation, sums[:, 3:]))

