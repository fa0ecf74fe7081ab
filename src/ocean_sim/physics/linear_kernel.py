"""Linear (Airy) theory under the surface, compiled: pressure head and orbital velocity.

:func:`pressure_head_f64` and :func:`orbital_velocity_f64` compute, point by point, what
:func:`ocean_sim.physics.waves.pressure_head` and :func:`ocean_sim.physics.waves.orbital_velocity`
compute with numpy (``_pressure_head_numpy``, ``_orbital_velocity_numpy``, kept as their
oracle: equal within 1e-12 of the field's size over random seas and points). Each
component's depth decay is Wheeler-stretched (Wheeler 1970): deep water e^{k z_s},
z_s = min(z - eta, 0); depth h: z_s = clip(h (z - eta) / (h + eta), -h, 0), and
cosh / sinh ratios written with exponentials that do not overflow (Dean & Dalrymple 1991,
eqs. 4.16-4.17 and 4.23). sin and cos are :mod:`ocean_sim.physics.surface_kernel`'s
polynomial pair, evaluated component by component over blocks of points so that they
vectorize. Pure functions of arrays.
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


#: Points per block: a block's phases and sums stay in the cache while the components go by.
_BLOCK = 2048


@kernel
def _pressure_decay(k, zs, h, deep, decay):  # pragma: no cover  (compiled)
    """One component's pressure decay at the block's z_s: cosh(k (z_s + h)) / cosh(k h)."""
    for i in range(zs.shape[0]):
        kz = k * zs[i]
        decay[i] = math.exp(kz)
        if not deep:
            decay[i] = (decay[i] * (1.0 + math.exp(-2.0 * (kz + k * h)))
                        / (1.0 + math.exp(-2.0 * k * h)))


@kernel
def _decays(k, zs, h, deep, horizontal, vertical):  # pragma: no cover  (compiled)
    """One component's velocity decays at z_s: cosh and sinh(k (z_s + h)) / sinh(k h)."""
    for i in range(zs.shape[0]):
        kz = k * zs[i]
        grow = math.exp(kz)
        if deep:
            horizontal[i] = vertical[i] = grow
        else:
            fall = math.exp(-2.0 * (kz + k * h))
            norm = 1.0 - math.exp(-2.0 * k * h)
            horizontal[i] = grow * (1.0 + fall) / norm
            vertical[i] = grow * (1.0 - fall) / norm


@kernel
def pressure_head_f64(xy, z, eta, kd, time_phase, a, k, h, deep):  # pragma: no cover
    """(N,) m: p / (rho g) = sum_i a_i cos(theta_i) E_i(z_s) - z at N points under the surface.

    Component-major in blocks of points, so that the sines and cosines vectorize (the
    polynomial pair: about 2 ns a point instead of 7 one point at a time).

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
    for lo in range(0, n, _BLOCK):
        hi = min(lo + _BLOCK, n)
        x, y = xy[lo:hi, 0].copy(), xy[lo:hi, 1].copy()
        zs, total, c = np.empty(hi - lo), np.zeros(hi - lo), np.empty(hi - lo)
        decay = np.empty(hi - lo)
        for i in range(hi - lo):
            zs[i] = _stretched(z[lo + i], eta[lo + i], h, deep)
        for j in range(m):
            kx, ky, phase = kd[0, j], kd[1, j], time_phase[j]
            for i in range(hi - lo):
                _, c[i] = _sincos(x[i] * kx + y[i] * ky + phase)
            _pressure_decay(k[j], zs, h, deep, decay)
            for i in range(hi - lo):
                total[i] += c[i] * decay[i] * a[j]
        for i in range(hi - lo):
            out[lo + i] = total[i] - z[lo + i]
    return out


@kernel
def orbital_velocity_f64(xy, z, eta, kd, time_phase, a_omega, k, dx, dy, h, deep
                         ):  # pragma: no cover  (compiled)
    """(N, 3) m/s: the water's velocity at N points below the surface, linear theory.

    Each component: a omega cos(theta) E_h(z_s) along its direction, a omega sin(theta)
    E_v(z_s) upward, theta at the point's own horizontal position. Component-major in blocks
    of points, as :func:`pressure_head_f64`.

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
    for lo in range(0, n, _BLOCK):
        hi = min(lo + _BLOCK, n)
        x, y = xy[lo:hi, 0].copy(), xy[lo:hi, 1].copy()
        zs, s, c = np.empty(hi - lo), np.empty(hi - lo), np.empty(hi - lo)
        horizontal, vertical = np.empty(hi - lo), np.empty(hi - lo)
        u, v, w = np.zeros(hi - lo), np.zeros(hi - lo), np.zeros(hi - lo)
        for i in range(hi - lo):
            zs[i] = _stretched(z[lo + i], eta[lo + i], h, deep)
        for j in range(m):
            kx, ky, phase = kd[0, j], kd[1, j], time_phase[j]
            for i in range(hi - lo):
                s[i], c[i] = _sincos(x[i] * kx + y[i] * ky + phase)
            _decays(k[j], zs, h, deep, horizontal, vertical)
            for i in range(hi - lo):
                speed = horizontal[i] * c[i] * a_omega[j]
                u[i] += speed * dx[j]
                v[i] += speed * dy[j]
                w[i] += vertical[i] * s[i] * a_omega[j]
        for i in range(hi - lo):
            out[lo + i, 0], out[lo + i, 1], out[lo + i, 2] = u[i], v[i], w[i]
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
