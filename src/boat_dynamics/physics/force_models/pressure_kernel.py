"""The pressure wrench on wetted hull triangles, compiled (:func:`pressure_wrenches_f64`).

What :func:`boat_dynamics.physics.force_models.mesh_buoyancy.pressure_wrenches` computes, in one
pass over the triangles (``mesh_buoyancy._pressure_wrenches_numpy`` is its oracle: equal within
1e-12 of the wrench's size). On a triangle with the pressure head h linear between its corners,
the force is -rho g (sum h / 3) A n and the moment of the pressure about the centre of mass
-rho g (A / 12) sum_j r_j (sum_k h_k + h_j) x n (the seed notes' "true centre of pressure";
Kerner 2015, part 2).
"""

from __future__ import annotations

import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["pressure_wrenches_f64", "warm"]


@kernel
def pressure_wrenches_f64(xyz, heads, vector_areas, owner, count, center_of_mass, rho_g
                          ):  # pragma: no cover  (compiled)
    """(B, 3) N forces and (B, 3) N m torques about the centres of mass, world frame.

    Args:
        xyz: (3, 3, T) m, coordinate k of corner j of triangle t at [k, j, t].
        heads: (3, T) m, the pressure head p / (rho g) at each corner.
        vector_areas: (3, T) m^2, area times outward unit normal.
        owner: (T,) int, the hull (0..B-1) of each triangle.
        count: B.
        center_of_mass: (B, 3) m, world frame.
        rho_g: (B,) N/m^3.
    """
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    r = np.empty(3)
    for t in range(owner.shape[0]):
        b = owner[t]
        h0, h1, h2 = heads[0, t], heads[1, t], heads[2, t]
        total = h0 + h1 + h2
        for k in range(3):
            com = center_of_mass[b, k]
            r[k] = ((xyz[k, 0, t] - com) * (total + h0) + (xyz[k, 1, t] - com) * (total + h1)
                    + (xyz[k, 2, t] - com) * (total + h2))
        push, turn = rho_g[b] * total * (-1.0 / 3.0), rho_g[b] * (-1.0 / 12.0)
        n0, n1, n2 = vector_areas[0, t], vector_areas[1, t], vector_areas[2, t]
        force[b, 0] += push * n0
        force[b, 1] += push * n1
        force[b, 2] += push * n2
        torque[b, 0] += turn * (r[1] * n2 - r[2] * n1)
        torque[b, 1] += turn * (r[2] * n0 - r[0] * n2)
        torque[b, 2] += turn * (r[0] * n1 - r[1] * n0)
    return force, torque


def warm() -> float:
    """Compile (or load from the cache) this module's kernel; returns the s it took."""
    start = time.perf_counter()
    pressure_wrenches_f64(np.zeros((3, 3, 1)), np.ones((3, 1)), np.ones((3, 1)),
                          np.zeros(1, dtype=np.intp), 1, np.zeros((1, 3)), np.ones(1))
    return time.perf_counter() - start
