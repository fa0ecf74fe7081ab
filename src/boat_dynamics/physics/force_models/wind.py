"""Wind loads on the above-water hull: force and moment from projected areas and coefficients.

The relative wind in the body frame, (u_rw, v_rw) = (u, v) - R^T w (w the wind's world
velocity, (u, v) the boat's), its speed V_rw and angle of attack gamma = -atan2(v_rw, u_rw)
give (Fossen 2021, "Handbook of marine craft hydrodynamics and motion control", 2nd ed.,
sec. 10.1.1, eqs. 10.6-10.10)::

    X = q C_X A_F,   Y = q C_Y A_L,   N = q C_N A_L L_oa,   q = rho_air V_rw^2 / 2
    C_X = -c_x cos(gamma),   C_Y = c_y sin(gamma),   C_N = c_n sin(2 gamma)

(Fossen writes them in NED body axes; in FLU, y and N change sign together with gamma, so the
same formulas hold), with A_F and A_L the frontal and lateral projected areas above the
waterline and c_x in [0.50, 0.90], c_y in [0.70, 0.95], c_n in [0.05, 0.20] (Fossen, for general
ships: the defaults are the middle of each range). X and Y act at the centre of the lateral area
(so the side force also heels the boat); N is the moment about the vertical through the centre
of mass. The areas and that centre are those of the hull's triangles above the calm-water plane
at its upright equilibrium (:func:`windage_of_hull`: the projections of the dry parts' outward
faces), unless the scenario gives them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.body.clip import clip_parts
from boat_dynamics.physics.body.hull import HullMesh
from boat_dynamics.physics.body.wrench import Wrench, cross

__all__ = ["DEFAULT_WIND_COEFFICIENTS", "Windage", "wind_wrench", "windage_of_hull"]

#: (c_x, c_y, c_n), the middle of Fossen's ranges for ships.
DEFAULT_WIND_COEFFICIENTS = (0.70, 0.825, 0.125)


@dataclass(frozen=True)
class Windage:
    """What the wind acts on.

    Attributes:
        frontal_area: m^2, A_F, projected on the body y-z plane, above the waterline.
        lateral_area: m^2, A_L, projected on the body x-z plane, above the waterline.
        length: m, L_oa.
        centre: (3,) m, body frame from the hull reference point: where X and Y act.
        coefficients: (3,) c_x, c_y, c_n.
    """

    frontal_area: float
    lateral_area: float
    length: float
    centre: np.ndarray = field(default_factory=lambda: np.zeros(3))
    coefficients: np.ndarray = field(
        default_factory=lambda: np.array(DEFAULT_WIND_COEFFICIENTS))


def windage_of_hull(mesh: HullMesh, height: float, length: float) -> Windage:
    """The windage of a hull floating upright with its reference point at ``height`` (m).

    Args:
        mesh: the hull, body frame (outward triangles).
        height: m, the reference point's height above the calm water.
        length: m, L_oa.
    """
    tri = mesh.vertices[mesh.faces]  # (F, 3, 3)
    xyz = np.transpose(tri, (2, 1, 0))  # (3 coord, 3 corner, F)
    above = xyz[2] + height  # > 0: above the water
    parts, _, _, _ = clip_parts(xyz, above)
    a, b, c = parts[:, 0], parts[:, 1], parts[:, 2]  # (3, T)
    n = 0.5 * np.cross(b - a, c - a, axis=0)  # area-weighted outward normals
    centroid = (a + b + c) / 3.0
    frontal = float(np.maximum(n[0], 0.0).sum())
    side = np.maximum(n[1], 0.0)
    lateral = float(side.sum())
    centre = (np.array([float(side @ centroid[0]), 0.0, float(side @ centroid[2])]) / lateral
              if lateral > 0.0 else np.array([0.0, 0.0, -height]))
    return Windage(frontal, lateral, length, centre)


def wind_wrench(windage: np.ndarray, centre: np.ndarray, wind_body: np.ndarray,
                velocity: np.ndarray, center_of_mass: np.ndarray,
                air_density: float) -> Wrench:
    """The wind's wrench on B boats, about their centres of mass, body frames.

    Args:
        windage: (B, 6) A_F m^2, A_L m^2, L_oa m, c_x, c_y, c_n per boat.
        centre: (B, 3) m, body frame: where X and Y act.
        wind_body: (B, 3) m/s, the wind's velocity in each body frame.
        velocity: (B, 3) m/s, each boat's centre-of-mass velocity, body frame.
        center_of_mass: (B, 3) m, body frame.
        air_density: kg/m^3.
    """
    u = velocity[:, 0] - wind_body[:, 0]
    v = velocity[:, 1] - wind_body[:, 1]
    gamma = -np.arctan2(v, u)
    q = 0.5 * air_density * (u * u + v * v)
    area_f, area_l, length, cx, cy, cn = windage.T
    force = np.zeros_like(velocity)
    force[:, 0] = -q * cx * np.cos(gamma) * area_f
    force[:, 1] = q * cy * np.sin(gamma) * area_l
    torque = cross(centre - center_of_mass, force)
    torque[:, 2] += q * cn * np.sin(2.0 * gamma) * area_l * length
    return Wrench(force, torque)
