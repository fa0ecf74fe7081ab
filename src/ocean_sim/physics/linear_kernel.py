"""Linear (Airy) theory under the surface, compiled: pressure head and orbital velocity.

:func:`pressure_head_f64` and :func:`orbital_velocity_f64` compute, point by point, what
:func:`ocean_sim.physics.waves.pressure_head` and :func:`ocean_sim.physics.waves.orbital_velocity`
compute with numpy (``_pressure_head_numpy``, ``_orbital_velocity_numpy``, kept as their
oracle: equal within 1e-12 of the field's size over random seas and points). Each
component's depth decay is Wheeler-stretched (Wheeler 1970): deep water e^{k z_s},
z_s = min(z - eta, 0); depth h: z_s = clip(h (z - eta) / (h + eta), -h, 0), and
cosh / sinh ratios written with exponentials that do not overflow (Dean & Dalrymple 1991,
eqs. 4.16-4.17 and 4.23). sin and cos are :mod:`ocean_sim.physics.surface_kernel`'s
polynomial pair. Pure functions of arrays.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ocean_sim.physics.jit import kernel
from ocean_sim.physics.surface_kernel import _sincos

__all__ = ["orbital_velocity_f64", "pressure_head_f64", "warm"]


@kernel
def _stretched(z, eta, h, deep):  # pragma: no cover  (compiled)
    """z_s, m: the point's height mapped from [-h, eta] onto [-h, 0] (Wheeler)."""
    if deep:
        return min(z - eta, 0.0)
    return min(max(h * (z - eta) / (h + eta), -h), 0.0)


@kernel
def pressure_head_f64(xy, z, eta, kd, time_phase, a, k, h, deep):  # pragma: no cover
    """(N,) m: p / (rho g) = sum_i a_i cos(theta_i) E_i(z_s) - z at N points under the surface.

    Args:
        xy: (N, 2) m, the rest positions of the surface particles above the points.
        z: (N,) m, the points' heights.
        eta: (N,) m, the surface height above each.
        kd: (2, M) rad/m, k D of every component.
        time_phase: (M,) rad, phi - omega t reduced modulo 2 pi.
        a: (M,) m, amplitudes.
        k: (M,) rad/m, wavenumbers.
        h: m, the water depth (unused in deep water).
        deep: every component sees deep water (``waves._deep``).
    """
    n, m = xy.shape[0], kd.shape[1]
    out = np.empty(n)
    for i in range(n):
        zs = _stretched(z[i], eta[i], h, deep)
        total = 0.0
        for j in range(m):
            _, c = _sincos(xy[i, 0] * kd[0, j] + xy[i, 1] * kd[1, j] + time_phase[j])
            kz = k[j] * zs
            decay = math.exp(kz)
            if not deep:
                decay = (decay * (1.0 + math.exp(-2.0 * (kz + k[j] * h)))
                         / (1.0 + math.exp(-2.0 * k[j] * h)))
            total += c * decay * a[j]
        out[i] = total - z[i]
    return out


@kernel
def orbital_velocity_f64(xy, z, eta, kd, time_phase, a_omega, k, dx, dy, h, deep
                         ):  # pragma: no cover  (compiled)
    """(N, 3) m/s: the water's velocity at N points below the surface, linear theory.

    Each component: a omega cos(theta) E_h(z_s) along its direction, a omega sin(theta)
    E_v(z_s) upward, theta at the point's own horizontal position.

    Args:
        xy: (N, 2) m, the points' horizontal positions.
        z: (N,) m, their heights.
        eta: (N,) m, the surface height above each.
        kd: (2, M) rad/m, k D of every component.
        time_phase: (M,) rad, phi - omega t reduced modulo 2 pi.
        a_omega: (M,) m/s, a omega.
        k: (M,) rad/m.
        dx: (M,) x of the components' unit directions.
        dy: (M,) their y.
        h: m, the water depth (unused in deep water).
        deep: every component sees deep water.
    """
    n, m = xy.shape[0], kd.shape[1]
    out = np.zeros((n, 3))
    for i in range(n):
        zs = _stretched(z[i], eta[i], h, deep)
        for j in range(m):
            s, c = _sincos(xy[i, 0] * kd[0, j] + xy[i, 1] * kd[1, j] + time_phase[j])
            kz = k[j] * zs
            horizontal = vertical = math.exp(kz)
            if not deep:
                fall = math.exp(-2.0 * (kz + k[j] * h))
                norm = 1.0 - math.exp(-2.0 * k[j] * h)
                horizontal = horizontal * (1.0 + fall) / norm
                vertical = vertical * (1.0 - fall) / norm
            speed = horizontal * c * a_omega[j]
            out[i, 0] += speed * dx[j]
            out[i, 1] += speed * dy[j]
            out[i, 2] += vertical * s * a_omega[j]
    return out


def warm() -> float:
    """Compile (or load from the cache) this module's kernels; returns the s it took."""
    start = time.perf_counter()
    xy, one, kd = np.zeros((1, 2)), np.ones(1), np.array([[0.25], [0.0]])
    for deep in (True, False):
        pressure_head_f64(xy, -one, 0.0 * one, kd, 0.0 * one, one, one, 10.0, deep)
        orbital_velocity_f64(xy, -one, 0.0 * one, kd, 0.0 * one, one, one, one, 0.0 * one,
                             10.0, deep)
    return time.perf_counter() - start
