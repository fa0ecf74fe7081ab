"""Hull drag on the submerged triangles of a mesh hull: ITTC 1957 friction, pressure drag.

Both are options of the mesh model (off by default), acting on the triangles that
:func:`boat_dynamics.mesh_buoyancy.submerged_triangles` returns, with each triangle's
velocity relative to the water v_i (taken at its centroid):

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

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.wrench import Wrench, cross

__all__ = ["HullDrag", "friction_coefficient", "hull_drag"]


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
    form_factor: float = 0.0
    kinematic_viscosity: float = 1.19e-6
    pressure: bool = False
    reference_speed: float = 1.0
    pressure_linear: float = 10.0
    pressure_quadratic: float = 10.0
    suction_linear: float = 10.0
    suction_quadratic: float = 10.0
    pressure_falloff: float = 0.5
    suction_falloff: float = 0.5


def friction_coefficient(speed: float, length: float, kinematic_viscosity: float) -> float:
    """ITTC 1957 friction coefficient C_F = 0.075 / (log10(U L / nu) - 2)^2 (0 at rest)."""
    rn = speed * length / kinematic_viscosity
    if rn <= 1e3:  # the correlation line holds for turbulent flow only; no speed, no friction
        return 0.0
    return 0.075 / (math.log10(rn) - 2.0) ** 2


def hull_drag(model: HullDrag, corners: np.ndarray, normals: np.ndarray, areas: np.ndarray,
              velocities: np.ndarray, speed: float, length: float, water_density: float,
              center_of_mass_world: np.ndarray, rotation: np.ndarray) -> Wrench:
    """Drag wrench of the submerged triangles about the centre of mass, body frame.

    Args:
        model: the drag options.
        corners: (T, 3, 3) m, submerged triangles, world frame.
        normals: (T, 3) outward unit normals, world frame.
        areas: (T,) m^2.
        velocities: (T, 3) m/s, velocity of each triangle's centroid relative to the water.
        speed: m/s, hull speed through the water (for the Reynolds number).
        length: m, hull length (for the Reynolds number).
        water_density: rho, kg/m^3.
        center_of_mass_world: (3,) m.
        rotation: (3, 3) body-to-world rotation.
    """
    force = np.zeros((corners.shape[0], 3))
    if corners.shape[0] and model.viscous:
        cf = friction_coefficient(speed, length, model.kinematic_viscosity)
        vn = np.einsum("ij,ij->i", velocities, normals)
        vt = velocities - vn[:, None] * normals
        mag = np.linalg.norm(vt, axis=1)
        force -= (0.5 * water_density * cf * (1.0 + model.form_factor)
                  * (areas * mag)[:, None] * vt)
    if corners.shape[0] and model.pressure:
        v = np.linalg.norm(velocities, axis=1)
        moving = v > 1e-9
        cos = np.where(moving, np.einsum("ij,ij->i", velocities, normals)
                       / np.where(moving, v, 1.0), 0.0)
        r = v / model.reference_speed
        push = (model.pressure_linear * r + model.pressure_quadratic * r * r) * np.power(
            np.clip(cos, 0.0, 1.0), model.pressure_falloff)
        pull = (model.suction_linear * r + model.suction_quadratic * r * r) * np.power(
            np.clip(-cos, 0.0, 1.0), model.suction_falloff)
        force += ((pull * (cos < 0) - push * (cos > 0)) * areas)[:, None] * normals
    if not corners.shape[0]:
        return Wrench(np.zeros(3), np.zeros(3))
    arms = corners.mean(axis=1) - center_of_mass_world
    total = force.sum(axis=0)
    torque = cross(arms, force).sum(axis=0)
    return Wrench(rotation.T @ total, rotation.T @ torque)
