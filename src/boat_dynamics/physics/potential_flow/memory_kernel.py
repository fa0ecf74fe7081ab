"""The Cummins memory and the added mass at speed, compiled, boat by boat.

:func:`advance_f64` and :func:`memory_wrench_f64` are
:func:`boat_dynamics.physics.potential_flow.radiation.advance` and ``memory_wrench`` (the
state-space radiation memory: first-order-hold update z+ = e^{p dt} z + psi0 u0 + psi1 (u1 -
u0) and F = -Re[output z]; Kristiansen, Egeland & Fossen 2005); :func:`kirchhoff_f64` is
:func:`boat_dynamics.physics.potential_flow.added_mass.kirchhoff` on the horizontal plane
(Q(nu) = -C_A(nu) nu, Fossen 2011, eqs. 6.43-6.44). Their numpy implementations
(``radiation._advance_numpy``, ``radiation._memory_wrench_numpy``,
``added_mass._added_mass_coriolis_numpy``) are the tests' oracles (within 1e-12 relative).
"""

from __future__ import annotations

import cmath
import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["advance_f64", "kirchhoff_f64", "memory_wrench_f64", "warm"]


@kernel
def advance_f64(poles, input_, memory, before, after, dt):  # pragma: no cover  (compiled)
    """(B, N) complex memory states after dt s, velocity linear from ``before`` to ``after``.

    Args:
        poles: (B, N) complex, 1/s.
        input_: (B, N, 6) complex.
        memory: (B, N) complex, z at the start of the step.
        before: (B, 6) body velocities [v, w] at the start of the step.
        after: (B, 6) at its end.
        dt: s.
    """
    out = np.empty_like(memory)
    for b in range(poles.shape[0]):
        for n in range(poles.shape[1]):
            p = poles[b, n]
            decay = cmath.exp(p * dt)
            psi0 = (decay - 1.0) / p
            psi1 = (decay - 1.0 - p * dt) / (p * p * dt)
            u0 = 0j
            u1 = 0j
            for j in range(6):
                u0 += input_[b, n, j] * before[b, j]
                u1 += input_[b, n, j] * after[b, j]
            out[b, n] = decay * memory[b, n] + psi0 * u0 + psi1 * (u1 - u0)
    return out


@kernel
def memory_wrench_f64(output, memory, carried):  # pragma: no cover  (compiled)
    """(B, 3) N force and (B, 3) N m torque, -Re[output z] times the share ``carried`` (B,).

    Args:
        output: (B, 6, N) complex, the boats' memory outputs.
        memory: (B, N) complex, their memory states z.
        carried: (B,) in [0, 1], the share of its fluid each hull carries.
    """
    count = output.shape[0]
    force, torque = np.empty((count, 3)), np.empty((count, 3))
    for b in range(count):
        for i in range(6):
            acc = 0.0
            for n in range(output.shape[2]):
                z = output[b, i, n] * memory[b, n]
                acc += z.real
            if i < 3:
                force[b, i] = -acc * carried[b]
            else:
                torque[b, i - 3] = -acc * carried[b]
    return force, torque


@kernel
def kirchhoff_f64(added_mass, carried, velocity, angular_velocity
                  ):  # pragma: no cover  (compiled)
    """(B, 3) N and (B, 3) N m: Q(nu) of the horizontal-plane motion, on surge, sway, yaw.

    nu = (u, v, 0, 0, 0, r) and A = ``carried`` x ``added_mass``: a1 = A11 nu_v + A12 nu_w,
    a2 = A21 nu_v + A22 nu_w, Q = [a1 x w, a1 x v + a2 x w], kept on surge, sway and yaw.

    Args:
        added_mass: (B, 6, 6) kg, kg m, kg m^2, about the centres of mass, body axes.
        carried: (B,) in [0, 1], the share each hull carries.
        velocity: (B, 3) m/s, body frame, relative to the current.
        angular_velocity: (B, 3) rad/s, body frame.
    """
    count = added_mass.shape[0]
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    m = np.empty(6)
    for b in range(count):
        u, v, r = velocity[b, 0], velocity[b, 1], angular_velocity[b, 2]
        s = carried[b]
        for i in range(6):
            m[i] = (added_mass[b, i, 0] * s * u + added_mass[b, i, 1] * s * v
                    + added_mass[b, i, 5] * s * r)
        # a1 x w with w = (0, 0, r); a1 x v + a2 x w with v = (u, v, 0): kept x, y and z
        force[b, 0] = m[1] * r
        force[b, 1] = -m[0] * r
        torque[b, 2] = m[0] * v - m[1] * u
    return force, torque


def warm() -> float:
    """Compile (or load from the cache) this module's kernels; returns the s it took."""
    start = time.perf_counter()
    poles = np.array([[-1.0 + 1.0j]])
    advance_f64(poles, np.ones((1, 1, 6), complex), np.zeros((1, 1), complex), np.zeros((1, 6)),
                np.ones((1, 6)), 0.01)
    memory_wrench_f64(np.ones((1, 6, 1), complex), np.ones((1, 1), complex), np.ones(1))
    kirchhoff_f64(np.eye(6)[None], np.ones(1), np.ones((1, 3)), np.ones((1, 3)))
    return time.perf_counter() - start
