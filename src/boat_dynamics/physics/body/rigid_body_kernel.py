"""The 6 x 6 semi-implicit Euler step of :mod:`.rigid_body`, compiled, boat by boat.

:func:`integrate_coupled_f64` is
:func:`boat_dynamics.physics.body.rigid_body.integrate_coupled` in one pass per boat:
nu' = (M_RB + A)^-1 (tau - [m w x v, w x (I w)]) (Fossen 2011, eqs. 3.47-3.48 and 6.1), the
new velocities, then the pose from them: q <- q exp(w dt / 2), normalised, and
p <- p + dt R(q) v (quaternion kinematics, Fossen eq. 2.54; R in the homogeneous form of
eq. 2.72). The numpy implementation (``rigid_body._integrate_coupled_numpy``) is the tests'
oracle (within 1e-12 relative).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["integrate_coupled_f64", "warm"]


@kernel
def _pose(p, q, v, w, dt, b, p_out, q_out):  # pragma: no cover  (compiled)
    """Boat b's pose after dt s at its new body velocities v, w (rows b of the arrays)."""
    r0, r1, r2 = w[b, 0] * dt, w[b, 1] * dt, w[b, 2] * dt
    angle = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
    half = 0.5 * angle
    scale = math.sin(half) / angle if angle > 0.0 else 0.5  # sin(|r|/2) / |r|
    ex, ey, ez, ew = r0 * scale, r1 * scale, r2 * scale, math.cos(half)
    x, y, z, s = q[b, 0], q[b, 1], q[b, 2], q[b, 3]
    nx = s * ex + x * ew + y * ez - z * ey  # the Hamilton product q exp(w dt / 2)
    ny = s * ey - x * ez + y * ew + z * ex
    nz = s * ez + x * ey - y * ex + z * ew
    nw = s * ew - x * ex - y * ey - z * ez
    norm = math.sqrt(nx * nx + ny * ny + nz * nz + nw * nw)
    x, y, z, s = nx / norm, ny / norm, nz / norm, nw / norm
    q_out[b, 0], q_out[b, 1], q_out[b, 2], q_out[b, 3] = x, y, z, s
    v0, v1, v2 = v[b, 0], v[b, 1], v[b, 2]
    d = s * s - x * x - y * y - z * z
    p_out[b, 0] = p[b, 0] + dt * ((d + 2.0 * x * x) * v0 + 2.0 * (x * y - s * z) * v1
                                  + 2.0 * (x * z + s * y) * v2)
    p_out[b, 1] = p[b, 1] + dt * (2.0 * (x * y + s * z) * v0 + (d + 2.0 * y * y) * v1
                                  + 2.0 * (y * z - s * x) * v2)
    p_out[b, 2] = p[b, 2] + dt * (2.0 * (x * z - s * y) * v0 + 2.0 * (y * z + s * x) * v1
                                  + (d + 2.0 * z * z) * v2)


@kernel
def integrate_coupled_f64(position, orientation, velocity, angular_velocity, force, torque,
                          mass, inertia, mass_matrix_inverse, dt
                          ):  # pragma: no cover  (compiled)
    """One semi-implicit Euler step with 6 x 6 mass matrices, for B boats.

    Args:
        position: (B, 3) m, centres of mass, world frame.
        orientation: (B, 4) unit quaternions (x, y, z, w), body to world.
        velocity: (B, 3) m/s, body frames.
        angular_velocity: (B, 3) rad/s, body frames.
        force: (B, 3) N, total, body frames.
        torque: (B, 3) N m, total about the centres of mass, body frames.
        mass: (B,) kg, rigid-body masses.
        inertia: (B, 3, 3) kg m^2, rigid-body inertia tensors about the centres of mass.
        mass_matrix_inverse: (B, 6, 6) (M_RB + A)^-1.
        dt: s.

    Returns:
        New (position, orientation, velocity, angular_velocity), shapes as given.
    """
    count = position.shape[0]
    p, q = np.empty((count, 3)), np.empty((count, 4))
    v, w = np.empty((count, 3)), np.empty((count, 3))
    rhs = np.empty(6)
    for b in range(count):
        w0, w1, w2 = angular_velocity[b, 0], angular_velocity[b, 1], angular_velocity[b, 2]
        v0, v1, v2 = velocity[b, 0], velocity[b, 1], velocity[b, 2]
        s0 = inertia[b, 0, 0] * w0 + inertia[b, 0, 1] * w1 + inertia[b, 0, 2] * w2
        s1 = inertia[b, 1, 0] * w0 + inertia[b, 1, 1] * w1 + inertia[b, 1, 2] * w2
        s2 = inertia[b, 2, 0] * w0 + inertia[b, 2, 1] * w1 + inertia[b, 2, 2] * w2
        m = mass[b]
        rhs[0] = force[b, 0] - m * (w1 * v2 - w2 * v1)
        rhs[1] = force[b, 1] - m * (w2 * v0 - w0 * v2)
        rhs[2] = force[b, 2] - m * (w0 * v1 - w1 * v0)
        rhs[3] = torque[b, 0] - (w1 * s2 - w2 * s1)
        rhs[4] = torque[b, 1] - (w2 * s0 - w0 * s2)
        rhs[5] = torque[b, 2] - (w0 * s1 - w1 * s0)
        for i in range(6):
            acc = 0.0
            for j in range(6):
                acc += mass_matrix_inverse[b, i, j] * rhs[j]
            if i < 3:
                v[b, i] = velocity[b, i] + dt * acc
            else:
                w[b, i - 3] = angular_velocity[b, i - 3] + dt * acc
        _pose(position, orientation, v, w, dt, b, p, q)
    return p, q, v, w


def warm() -> float:
    """Compile (or load from the cache) this module's kernel; returns the s it took."""
    start = time.perf_counter()
    zeros = np.zeros((1, 3))
    integrate_coupled_f64(zeros, np.array([[0.0, 0.0, 0.0, 1.0]]), zeros, zeros, zeros, zeros,
                          np.ones(1), np.eye(3)[None], np.eye(6)[None], 0.01)
    return time.perf_counter() - start
