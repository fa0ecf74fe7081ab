"""The wave excitation of linear potential flow, compiled (:func:`excitation_f64`).

For each boat and wave component: the encounter frequency, the transfer function's bilinear
lookup in (omega, direction) and Re[a X e^{i theta}], summed over the components: what
:func:`boat_dynamics.physics.potential_flow.diffraction.excitation_wrench` did with numpy
(``diffraction._excitation_numpy``, kept as its oracle: equal within 1e-12 of the wrench's
size over random boats and seas). Newman 1977, sec. 6.17; Lewandowski 2004, sec. 3.4.
"""

from __future__ import annotations

import math
import time

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import _MIRRORED  # one table for both
from ocean_sim.physics.jit import kernel
from ocean_sim.physics.surface_kernel import _sincos

__all__ = ["excitation_f64", "warm"]

_TWO_PI = 2.0 * math.pi


@kernel
def _cell(grid, x):  # pragma: no cover  (compiled)
    """The cell i (grid[i] <= x <= grid[i + 1], clamped) of a sorted grid, and x's share u."""
    i = min(max(np.searchsorted(grid, x) - 1, 0), grid.shape[0] - 2)
    return i, (x - grid[i]) / (grid[i + 1] - grid[i])


@kernel
def excitation_f64(omegas, directions, table, a, omega, k, dx, dy, wave_direction, xy, kd,
                   time_phase, psi, velocity, encounter):  # pragma: no cover  (compiled)
    """(G, K) the excitation wrenches of G boats: sum_i Re[a_i X(omega_i, beta_i) e^{i theta_i}].

    Args:
        omegas: (W,) rad/s, the table's frequencies (sorted).
        directions: (D,) rad, its wave directions relative to the heading (sorted; 0..pi
            only: the other half mirrored, sway, roll and yaw changing sign).
        table: (W, D, K) complex transfer functions per metre of amplitude, K a multiple of 6.
        a: (M,) m, amplitudes.
        omega: (M,) rad/s.
        k: (M,) rad/m.
        dx: (M,) x of the components' directions.
        dy: (M,) their y.
        wave_direction: (M,) rad, arctan2(dy, dx).
        xy: (G, 2) m, the hull reference points.
        kd: (2, M) rad/m, k D.
        time_phase: (M,) rad, phi - omega t reduced modulo 2 pi.
        psi: (G,) rad, the headings.
        velocity: (G, 2) m/s, the hulls' velocities over ground, world frame.
        encounter: look the table up at the encounter frequency omega - k D . V (a wave the hull
            overtakes: |omega_e|, from the opposite direction, phase reversed); else at omega.
    """
    count, m, width = psi.shape[0], a.shape[0], table.shape[2]
    half = directions[-1] <= math.pi + 1e-9
    out = np.zeros((count, width))
    for g in range(count):
        for j in range(m):
            w, beta = omega[j], wave_direction[j] - psi[g]
            theta = xy[g, 0] * kd[0, j] + xy[g, 1] * kd[1, j] + time_phase[j]
            if encounter:
                w = omega[j] - k[j] * (velocity[g, 0] * dx[j] + velocity[g, 1] * dy[j])
                if w < 0.0:
                    w, beta, theta = -w, beta + math.pi, -theta
            w = min(max(w, omegas[0]), omegas[-1])
            beta = beta % _TWO_PI
            mirrored = half and beta > math.pi
            if mirrored:
                beta = _TWO_PI - beta
            beta = min(max(beta, directions[0]), directions[-1])
            i, u = _cell(omegas, w)
            n, v = _cell(directions, beta)
            s, c = _sincos(theta)
            for q in range(width):
                x = ((1 - u) * (1 - v) * table[i, n, q] + u * (1 - v) * table[i + 1, n, q]
                     + (1 - u) * v * table[i, n + 1, q] + u * v * table[i + 1, n + 1, q])
                sign = _MIRRORED[q % 6] if mirrored else 1.0
                out[g, q] += sign * a[j] * (x.real * c - x.imag * s)
    return out


def warm() -> float:
    """Compile (or load from the cache) this module's kernel; returns the s it took."""
    start = time.perf_counter()
    one, grid = np.ones(1), np.array([0.0, 1.0])
    table = np.ones((2, 2, 6), dtype=np.complex128)
    excitation_f64(grid, grid, table, one, one, one, one, 0.0 * one, 0.0 * one,
                   np.zeros((1, 2)), np.zeros((2, 1)), 0.0 * one, 0.0 * one, np.zeros((1, 2)),
                   True)
    return time.perf_counter() - start
