"""Hull drag on the submerged triangles of a mesh hull: ITTC 1957 friction, pressure drag.

Both are options of the mesh model (off by default), acting on the triangles that
:func:`boat_dynamics.physics.force_models.mesh_buoyancy.submerged_triangles` returns, with each
triangle's velocity relative to the water v_i (taken at its centroid):

- viscous resistance: C_F = 0.075 / (log10 Rn - 2)^2 with Rn = U L / nu (ITTC 1957
  correlation line), and on each triangle the tangential flow
  F_i = -1/2 rho C_F (1 + k) A_i |v_t| v_t, v_t = v_i - (v_i . n_i) n_i.
- pressure drag: a triangle advancing into the water (cos = v_hat . n > 0) is pushed back,
  F = -(C_PD1 v/v_r + C_PD2 (v/v_r)^2) cos^f_P A n; one moving away is sucked,
  F = +(C_SD1 v/v_r + C_SD2 (v/v_r)^2) |cos|^f_S A n.

Source: Kerner, "Water interaction model for boats in video games", part 2 (Game Developer,
2015), after ITTC (1957); the seed notes' Kerner entry.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from boat_dynamics.physics.body.wrench import Real, cross, per_element, sum_by_owner

if TYPE_CHECKING:
    from boat_dynamics.physics.body.clip import SubmergedTriangles

__all__ = ["HullDrag", "friction_coefficient", "hull_drag", "hull_drag_in_motion"]


@dataclass(frozen=True)
class HullDrag:
    """Hull drag options (mesh model).

    Attributes:
        viscous: apply ITTC 1957 friction.
        form_factor: k, the friction is multiplied by 1 + k.
        kinematic_viscosity: nu, m^2/s (sea water at 15 C: 1.19e-6).
        pressure: apply pressure drag.
        reference_speed: v_r, m/s.
        pressure_linear: C_PD1, N/m^2.
        pressure_quadratic: C_PD2, N/m^2.
        suction_linear: C_SD1, N/m^2.
        suction_quadratic: C_SD2, N/m^2.
        pressure_falloff: f_P.
        suction_falloff: f_S.
    """

    viscous: bool = False
    form_factor: Real = 0.0
    kinematic_viscosity: Real = 1.19e-6
    pressure: bool = False
    reference_speed: Real = 1.0
    pressure_linear: Real = 10.0
    pressure_quadratic: Real = 10.0
    suction_linear: Real = 10.0
    suction_quadratic: Real = 10.0
    pressure_falloff: Real = 0.5
    suction_falloff: Real = 0.5


def friction_coefficient(speed, length, kinematic_viscosity):
    """ITTC 1957 friction coefficient C_F = 0.075 / (log10(U L / nu) - 2)^2 (0 at rest).

    Scalars or (B,) arrays. The correlation line holds for turbulent flow only: below
    Rn = 1e3 (no speed) there is no friction.
    """
    rn = np.asarray(speed * length / kinematic_viscosity, dtype=float)
    cf = np.where(rn > 1e3, 0.075 / (np.log10(np.maximum(rn, 1e3)) - 2.0) ** 2, 0.0)
    return float(cf) if cf.ndim == 0 else cf


def hull_drag(model: HullDrag, wet: SubmergedTriangles, owner: np.ndarray, count: int,
              velocities: np.ndarray, speed: np.ndarray, length: np.ndarray,
              water_density: np.ndarray, center_of_mass_world: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """Drag force and torque on each of ``count`` hulls, about its centre of mass, world frame.

    Args:
        model: the drag options (numeric fields scalar, or (B,) one per hull).
        wet: the submerged triangles of the hulls.
        owner: (T,) int, the hull of each triangle.
        count: number of hulls, B.
        velocities: (T, 3) m/s, velocity of each triangle's centroid relative to the water.
        speed: (B,) m/s, hull speed through the water (for the Reynolds number).
        length: (B,) m, hull length (for the Reynolds number).
        water_density: (B,) rho, kg/m^3.
        center_of_mass_world: (B, 3) m.

    Returns:
        (B, 3) N forces and (B, 3) N m torques, world frame.
    """
    normals, areas = wet.normals, wet.areas
    force = np.zeros((areas.shape[0], 3))
    if model.viscous:
        cf = friction_coefficient(speed, length, model.kinematic_viscosity)
        coefficient = (0.5 * np.asarray(water_density) * cf
                       * (1.0 + np.asarray(model.form_factor)))
        vn = np.einsum("ij,ij->i", velocities, normals)
        vt = velocities - vn[:, None] * normals
        mag = np.sqrt(np.einsum("ij,ij->i", vt, vt))
        force -= (per_element(coefficient, owner) * areas * mag)[:, None] * vt
    if model.pressure:
        v = np.sqrt(np.einsum("ij,ij->i", velocities, velocities))
        moving = v > 1e-9
        cos = np.where(moving, np.einsum("ij,ij->i", velocities, normals)
                       / np.where(moving, v, 1.0), 0.0)
        r = v / per_element(model.reference_speed, owner)
        push = ((per_element(model.pressure_linear, owner) * r
                 + per_element(model.pressure_quadratic, owner) * r * r)
                * np.power(np.clip(cos, 0.0, 1.0), per_element(model.pressure_falloff, owner)))
        pull = ((per_element(model.suction_linear, owner) * r
                 + per_element(model.suction_quadratic, owner) * r * r)
                * np.power(np.clip(-cos, 0.0, 1.0), per_element(model.suction_falloff, owner)))
        force += ((pull * (cos < 0) - push * (cos > 0)) * areas)[:, None] * normals
    arms = wet.centroids - center_of_mass_world[owner]
    sums = sum_by_owner(np.concatenate([force, cross(arms, force)], axis=1), owner, count)
    return sums[:, :3], sums[:, 3:]


def hull_drag_in_motion(model: HullDrag, wet: SubmergedTriangles, owner: np.ndarray, count: int,
                        rotation: np.ndarray, velocity: np.ndarray,
                        angular_velocity: np.ndarray, center_of_mass_world: np.ndarray,
                        length: np.ndarray, water_density: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`hull_drag` of hulls moving through the water, world frame.

    Each wet triangle's velocity relative to the water is taken at its centroid c:
    v = R v_rel + (R omega) x (c - r_com), the hull's speed |v_rel|.

    Args:
        model: the drag options.
        wet: the submerged triangles of the hulls.
        owner: (T,) int, the hull of each triangle.
        count: number of hulls, B.
        rotation: (B, 3, 3) body-to-world rotations.
        velocity: (B, 3) m/s, centre-of-mass velocities relative to the water, body frames.
        angular_velocity: (B, 3) rad/s, body frames.
        center_of_mass_world: (B, 3) m.
        length: (B,) m, hull lengths.
        water_density: (B,) kg/m^3.

    Returns:
        (B, 3) N forces and (B, 3) N m torques about the centres of mass, world frame.
    """
    omega_world = np.einsum("bij,bj->bi", rotation, angular_velocity)
    flow_world = np.einsum("bij,bj->bi", rotation, velocity)
    flow = flow_world[owner] + cross(omega_world[owner],
                                     wet.centroids - center_of_mass_world[owner])
    speed = np.sqrt(np.einsum("bi,bi->b", velocity, velocity))
    return hull_drag(model, wet, owner, count, flow, speed, length, water_density,
                     center_of_mass_world)
