"""Sample-point buoyancy, derived from density (no tuned spring), with the seed notes' options.

Each of N points stands at the bottom of a vertical column of the hull and carries an equal
share V / N of the hull's volume V = mass / density. Submerged by ``d`` (surface height above
the point), it carries the weight of the water its column displaces::

    F_i = rho g (V / N) s(d_i)      s = clamp(d / max_depth, 0, 1)            (linear)
                                    s = (1 - exp(-alpha d / max_depth)) / (1 - exp(-alpha))
                                        for d in [0, max_depth]              (exponential)

straight up (default) or along the surface normal, applied at the centre of the submerged
part of the column (``min(d, max_depth) / 2`` above the point), so a box with a grid of points
has its true centre of buoyancy. With ``curve: sphere`` each point is instead the lowest point
of a sphere of diameter D = ``max_depth`` (Assassin's Creed IV's ships float on such spheres,
4 or more a side: the seed notes, "buoyancy spheres"); its share of the volume is the
sphere's, pi D^3 / 6, and its force the weight of the water in the submerged spherical cap of
height h = x D::

    s = x^2 (3 - 2 x)        (cap volume pi h^2 (3 r - h) / 3 over 4 pi r^3 / 3)

applied at the cap's centroid, D (1/2 - 3 (1 - x)^2 / (6 - 4 x)) above the point (for a
cap of height h the centroid lies 3 (2 r - h)^2 / (4 (3 r - h)) from the sphere's centre;
Weisstein, "Spherical Cap", MathWorld). The surface is taken as level across each sphere.
Linear curve: sum F_i = m g gives draft / height = m / (rho V)
= density / rho, whatever the mass. Options (all from the notes, each labelled as such):
``depth_scale`` multiplies by clamp(d, 0, 1 m) (less jitter at the waterline), ``point_damping``
adds -c (m / N) v_i at each submerged point (damping proportional to mass keeps the damping
ratio when the load changes), ``force_clamp`` caps each point at that fraction of rho g V / N.

Source: the seed notes (docs/seed-notes.txt, "Sample-Point / Voxel
Buoyancy", "derive everything from density", "Solutions to shooting out" 1, 2 and 6, the
Vertex Fragment damping); Archimedes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.wrench import Real, Wrench, cross, per_element, sum_by_owner

__all__ = [
    "CURVES",
    "POINT_DIRECTIONS",
    "Curve",
    "PointDirection",
    "SamplePointBuoyancy",
    "sample_point_buoyancy",
    "sample_point_group",
    "sample_point_wrenches",
    "sphere_cap",
]

#: How a point's force grows with its submersion: Archimedes for a vertical column, the
#: saturating arcade curve, or Archimedes for a sphere (Assassin's Creed's buoyancy spheres).
Curve = Literal["linear", "exponential", "sphere"]
CURVES: tuple[Curve, ...] = get_args(Curve)
#: Where a point's force points: world up (Archimedes), or along the local surface normal.
PointDirection = Literal["up", "normal"]
POINT_DIRECTIONS: tuple[PointDirection, ...] = get_args(PointDirection)


@dataclass(frozen=True)
class SamplePointBuoyancy:
    """Parameters of the sample-point model.

    Attributes:
        points: (N, 3) m, column bottoms in the body frame (relative to the hull reference point).
        volume: V, m^3, volume displaced when every column is fully submerged (mass / density).
        max_depth: m, submersion at which a column is full (the hull height for a box); the
            spheres' diameter for ``curve: sphere``.
        curve: ``linear`` (Archimedes), ``exponential`` (saturating, arcade) or ``sphere``.
        alpha: steepness of the exponential curve, > 0.
        direction: ``up`` (Archimedes) or ``normal`` (along the local surface normal).
        depth_scale: multiply each force by clamp(depth, 0, 1 m).
        point_damping: c, 1/s; each submerged point adds -c (m / N) v_point.
        force_clamp: cap of each point's force as a fraction of rho g V / N; None = no cap.
    """

    points: np.ndarray
    volume: Real
    max_depth: Real
    curve: Curve = "linear"
    alpha: Real = 3.0
    direction: PointDirection = "up"
    depth_scale: bool = False
    point_damping: Real = 0.0
    force_clamp: Real | None = None


def sphere_cap(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume fraction and centroid height of a sphere submerged to x of its diameter.

    Args:
        x: (N,) submersion over diameter, in [0, 1].

    Returns:
        (N,) the cap's volume over the sphere's, x^2 (3 - 2 x), and (N,) the height of its
        centroid above the sphere's lowest point, in diameters, 1/2 - 3 (1 - x)^2 / (6 - 4 x).
    """
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x), 0.5 - 3.0 * (1.0 - x) ** 2 / (6.0 - 4.0 * x)


def sample_point_buoyancy(
    model: SamplePointBuoyancy,
    depths: np.ndarray,
    rotation: np.ndarray,
    center_of_mass: np.ndarray,
    water_density: float,
    gravity: float,
    normals: np.ndarray | None = None,
    point_velocities: np.ndarray | None = None,
    mass: float = 0.0,
) -> Wrench:
    """Buoyancy wrench of one boat's sample points (see :func:`sample_point_wrenches`).

    Args:
        model: the sample-point parameters.
        depths: (N,) m, surface height minus point height at each point (> 0 = submerged).
        rotation: (3, 3) body-to-world rotation matrix.
        center_of_mass: (3,) m, body frame, relative to the hull reference point.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.
        normals: (N, 3) world surface normals at the points (``direction: normal``).
        point_velocities: (N, 3) m/s, world velocity of each point relative to the water
            (``point_damping``).
        mass: kg, the boat's mass (``point_damping``).

    Returns:
        The buoyancy wrench about the centre of mass, body frame.
    """
    owner = np.zeros(model.points.shape[0], dtype=np.intp)
    force, torque = sample_point_wrenches(
        model, owner, 1, depths, rotation[None], np.asarray(center_of_mass)[None],
        np.array([water_density * gravity]), normals, point_velocities, np.array([mass]))
    return Wrench(force[0], torque[0])


def sample_point_wrenches(
    model: SamplePointBuoyancy,
    owner: np.ndarray,
    count: int,
    depths: np.ndarray,
    rotation: np.ndarray,
    center_of_mass: np.ndarray,
    rho_g: np.ndarray,
    normals: np.ndarray | None,
    point_velocities: np.ndarray | None,
    mass: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Buoyancy force and torque of the sample points of ``count`` boats, body frames.

    Args:
        model: the sample-point parameters; ``points`` (P, 3) are the boats' points
            concatenated, the numeric fields are scalars or (B,) arrays, one per boat.
        owner: (P,) int, the boat of each point.
        count: number of boats, B.
        depths: (P,) m, surface height minus point height (> 0 = submerged).
        rotation: (B, 3, 3) body-to-world rotations.
        center_of_mass: (B, 3) m, body frame, relative to the hull reference point.
        rho_g: (B,) N/m^3, water density times gravity.
        normals: (P, 3) world surface normals at the points (``direction: normal``).
        point_velocities: (P, 3) m/s, world velocity of each point relative to the water
            (``point_damping``).
        mass: (B,) kg (``point_damping``).

    Returns:
        (B, 3) N forces and (B, 3) N m torques about the centres of mass, body frames.
    """
    points_per_boat = np.bincount(owner, minlength=count)
    share = (rho_g * model.volume / points_per_boat)[owner]
    max_depth = per_element(model.max_depth, owner)
    submerged = np.clip(depths, 0.0, max_depth)
    rise = submerged / 2.0  # the centre of the submerged part, above the point
    if model.curve == "exponential":
        alpha = per_element(model.alpha, owner)
        fraction = (1.0 - np.exp(-alpha * submerged / max_depth)) / (1.0 - np.exp(-alpha))
    elif model.curve == "sphere":
        fraction, rise = sphere_cap(submerged / max_depth)
        rise = rise * max_depth
    else:
        fraction = submerged / max_depth
    magnitude = share * fraction
    if model.depth_scale:
        magnitude = magnitude * np.clip(depths, 0.0, 1.0)
    if model.force_clamp is not None:
        magnitude = np.minimum(magnitude, per_element(model.force_clamp, owner) * share)
    if model.direction == "normal" and normals is not None:
        forces_world = magnitude[:, None] * normals
    else:
        forces_world = np.zeros((magnitude.shape[0], 3))
        forces_world[:, 2] = magnitude
    if np.any(np.asarray(model.point_damping) > 0.0) and point_velocities is not None:
        c = per_element(np.asarray(model.point_damping) * mass / points_per_boat, owner)
        forces_world = forces_world - ((depths > 0.0) * c)[:, None] * point_velocities
    arms = model.points - center_of_mass[owner]
    arms[:, 2] += rise
    forces_body = np.einsum("pji,pj->pi", rotation[owner], forces_world)
    sums = sum_by_owner(np.concatenate([forces_body, cross(arms, forces_body)], axis=1),
                        owner, count)
    return sums[:, :3], sums[:, 3:]


def sample_point_group(model: SamplePointBuoyancy, owner: np.ndarray, count: int,
                       depths: np.ndarray, rotation: np.ndarray, center_of_mass: np.ndarray,
                       rho_g: np.ndarray, normals: np.ndarray, water_velocities: np.ndarray,
                       velocity: np.ndarray, angular_velocity: np.ndarray, mass: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sample_point_wrenches` of a group of boats in motion, body frames.

    The points' velocities relative to the water (for ``point_damping``) are
    v_p = R (v + omega x r_p) - u_water, r_p the point's arm from the centre of mass.

    Args:
        model: as for :func:`sample_point_wrenches`.
        owner: (P,) int, the boat of each point.
        count: number of boats, B.
        depths: (P,) m, surface height minus point height.
        rotation: (B, 3, 3) body-to-world rotations.
        center_of_mass: (B, 3) m, body frame, relative to the hull reference point.
        rho_g: (B,) N/m^3.
        normals: (P, 3) world surface normals at the points.
        water_velocities: (P, 3) m/s, world velocity of the surface water at the points.
        velocity: (B, 3) m/s, centre-of-mass velocities, body frames.
        angular_velocity: (B, 3) rad/s, body frames.
        mass: (B,) kg.

    Returns:
        (B, 3) N forces and (B, 3) N m torques about the centres of mass, body frames.
    """
    point_velocities = None
    if np.any(np.asarray(model.point_damping) > 0.0):
        arms = model.points - center_of_mass[owner]
        v_points = velocity[owner] + cross(angular_velocity[owner], arms)
        point_velocities = (np.einsum("eij,ej->ei", rotation[owner], v_points)
                            - water_velocities)
    return sample_point_wrenches(model, owner, count, depths, rotation, center_of_mass, rho_g,
                                 normals, point_velocities, mass)
