"""The surface query compiled: :func:`ocean_sim.physics.waves.sample_surface` in float64.

Every point is inverted on its own (Newton on the 2x2 Jacobian, the fixed-point step where
Newton does not shrink the residual, a halved Newton step near a cusp), then its height,
particle kinematics and normal are summed: the same algorithm, step for step, as the numpy
implementation in :mod:`ocean_sim.physics.waves` (``_solve``, ``_sample_numpy``), which stays
as the tests' oracle (equal within 1e-12 over random seas and points). The points iterate in
lockstep, component-major, in blocks that stay in the cache, so the loops over points
vectorize (SIMD); a point that has converged keeps its values, and the rare fall-back steps
are taken point by point.

sin and cos are a branch-free polynomial (:func:`_sincos`: Cody-Waite reduction by pi/2 in
three parts, fdlibm's kernels on [-pi/4, pi/4]; within 1 ulp of libm's for |x| < 1e5 rad),
which vectorizes where libm's scalar calls do not. Pure functions of arrays.
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["sincos", "surface_f64", "warm"]

#: As ``waves._CUSP_DET`` and ``waves._HALVINGS`` (the numpy oracle's).
_CUSP_DET = 1e-2
_HALVINGS = 40

# pi/2 in three parts (fdlibm's e_rem_pio2.c): n * _PIO2_1 is exact for |n| < 2^20
_INVPIO2 = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e+00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
# fdlibm's k_sin.c and k_cos.c (FreeBSD), |x| <= pi/4
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


@numba.njit(inline="always", error_model="numpy", cache=True)
def _sincos(x):  # pragma: no cover  (compiled)
    """(sin x, cos x), branch-free: selects, no calls (so a loop over x vectorizes)."""
    n = np.floor(x * _INVPIO2 + 0.5)  # a float: math.floor's int blocks SIMD
    r = ((x - n * _PIO2_1) - n * _PIO2_2) - n * _PIO2_3
    z = r * r
    ks = r + (z * r) * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    kc = w + (((1.0 - w) - hz)
              + z * (z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))))
    q = n - 4.0 * np.floor(n * 0.25)  # the quadrant, 0 .. 3
    odd = (q == 1.0) | (q == 3.0)
    a = kc if odd else ks
    b = ks if odd else kc
    return (-a if q >= 2.0 else a), (-b if (q == 1.0) | (q == 2.0) else b)


@kernel
def sincos(x):  # pragma: no cover  (compiled)
    """(sin x, cos x) of an array (N,) by :func:`_sincos` (for its tests and benchmark)."""
    s, c = np.empty_like(x), np.empty_like(x)
    for i in range(x.shape[0]):
        s[i], c[i] = _sincos(x[i])
    return s, c


@kernel
def _trial(base, kd, qad, c0, c1, theta, s, co):  # pragma: no cover  (compiled)
    """One point's phases, sines and cosines at the correction (c0, c1); its (r0, r1, |r|)."""
    a0 = a1 = 0.0
    for j in range(base.shape[0]):
        theta[j] = base[j] + c0 * kd[0, j] + c1 * kd[1, j]
        s[j], co[j] = _sincos(theta[j])
        a0 += s[j] * qad[j, 0]
        a1 += s[j] * qad[j, 1]
    r0, r1 = c0 - a0, c1 - a1
    return r0, r1, math.sqrt(r0 * r0 + r1 * r1)


@kernel
def _fall_back(i, base, kd, qad, d, r, det, step, cand, rc, ec, sa, ca
               ):  # pragma: no cover  (compiled)
    """Point ``i``, whose Newton step did not shrink |F|: the fixed-point step instead.

    Near a cusp, the longest halved Newton step that does better (``waves._fall_back``,
    ``_damped``).
    """
    m = base.shape[0]
    b = base[:, i].copy()
    theta, s, c = np.empty(m), np.empty(m), np.empty(m)
    f0, f1 = d[0, i] - r[0, i], d[1, i] - r[1, i]
    g0, g1, e = _trial(b, kd, qad, f0, f1, theta, s, c)
    if det[i] < _CUSP_DET:
        tt, st, ct = np.empty(m), np.empty(m), np.empty(m)
        h = 0.5
        for _ in range(_HALVINGS):
            h0, h1 = d[0, i] - h * step[0, i], d[1, i] - h * step[1, i]
            q0, q1, eh = _trial(b, kd, qad, h0, h1, tt, st, ct)
            if eh < e:
                f0, f1, g0, g1, e = h0, h1, q0, q1, eh
                theta[:], s[:], c[:] = tt, st, ct
                break
            h *= 0.5
    cand[0, i], cand[1, i], rc[0, i], rc[1, i], ec[i] = f0, f1, g0, g1, e
    sa[:, i], ca[:, i] = s, c


@kernel
def _newton(base, kd, qad, jac, d, r, err, s, c, active):  # pragma: no cover  (compiled)
    """One lockstep iteration of every ``active`` point: d, r, err, s, c updated in place."""
    m, n = base.shape
    j0, j1, j2 = np.zeros(n), np.zeros(n), np.zeros(n)
    for j in range(m):
        for i in range(n):
            j0[i] += c[j, i] * jac[j, 0]
            j1[i] += c[j, i] * jac[j, 1]
            j2[i] += c[j, i] * jac[j, 2]
    det, step, cand = np.empty(n), np.empty((2, n)), np.empty((2, n))
    for i in range(n):
        jxx, jxy, jyy = 1.0 - j0[i], -j1[i], 1.0 - j2[i]
        det[i] = jxx * jyy - jxy * jxy
        s0, s1 = jyy * r[0, i] - jxy * r[1, i], jxx * r[1, i] - jxy * r[0, i]
        ok = det[i] > 1e-6  # else near singular: the fixed-point step
        step[0, i] = s0 / det[i] if ok else r[0, i]
        step[1, i] = s1 / det[i] if ok else r[1, i]
        cand[0, i], cand[1, i] = d[0, i] - step[0, i], d[1, i] - step[1, i]
    a0, a1 = np.zeros(n), np.zeros(n)
    for j in range(m):  # the candidates' sines and cosines, kept by the active points
        for i in range(n):
            sv, cv = _sincos(base[j, i] + cand[0, i] * kd[0, j] + cand[1, i] * kd[1, j])
            a0[i] += sv * qad[j, 0]
            a1[i] += sv * qad[j, 1]
            s[j, i] = sv if active[i] else s[j, i]
            c[j, i] = cv if active[i] else c[j, i]
    rc, ec = np.empty((2, n)), np.empty(n)
    for i in range(n):
        rc[0, i], rc[1, i] = cand[0, i] - a0[i], cand[1, i] - a1[i]
        ec[i] = math.sqrt(rc[0, i] * rc[0, i] + rc[1, i] * rc[1, i])
    for i in range(n):
        if active[i] and ec[i] >= err[i]:
            _fall_back(i, base, kd, qad, d, r, det, step, cand, rc, ec, s, c)
    for i in range(n):
        if active[i]:
            d[0, i], d[1, i], r[0, i], r[1, i], err[i] = cand[0, i], cand[1, i], rc[0, i], \
                rc[1, i], ec[i]


@kernel
def _invert(base, kd, qad, jac, tol, max_iter, s, c):  # pragma: no cover  (compiled)
    """(2, N) m, the corrections p0 - xy; ``s`` and ``c`` left at the points' phases."""
    m, n = base.shape
    d, r, err = np.zeros((2, n)), np.zeros((2, n)), np.empty(n)
    a0, a1 = np.zeros(n), np.zeros(n)
    for j in range(m):
        for i in range(n):
            a0[i] += s[j, i] * qad[j, 0]
            a1[i] += s[j, i] * qad[j, 1]
    for i in range(n):
        r[0, i], r[1, i] = -a0[i], -a1[i]
        err[i] = math.sqrt(a0[i] * a0[i] + a1[i] * a1[i])
    active = np.empty(n, dtype=np.bool_)
    for _ in range(max_iter):
        count = 0
        for i in range(n):
            active[i] = err[i] > tol  # (a non-finite point is never active)
            count += active[i]
        if count == 0:
            break
        _newton(base, kd, qad, jac, d, r, err, s, c, active)
    return d


@kernel
def _normals(out, normals):  # pragma: no cover  (compiled)
    """Unit normals (N, 3) from the tangents' terms A, B, C, Sx, Sy (rows 7-11 of ``out``)."""
    for i in range(out.shape[1]):
        a, b, cc, sx, sy = out[7, i], out[8, i], out[9, i], out[10, i], out[11, i]
        nx, ny = b * sy + sx * (1.0 - cc), b * sx + sy * (1.0 - a)
        nz = (1.0 - a) * (1.0 - cc) - b * b
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        ok = length > 1e-12  # else a cusp (sum Q k a = 1 at a crest): vertical
        normals[i, 0] = nx / length if ok else 0.0
        normals[i, 1] = ny / length if ok else 0.0
        normals[i, 2] = nz / length if ok else 1.0


#: Phases per block (points x components): each block's (M, points) phase, sine and cosine
#: arrays, 64 KiB each, stay in the cache (all 39,000 points of 100 boats in one block took
#: 1.4x as long per point, measured).
_BLOCK = 8192


@kernel
def _block(xy, kd, time_phase, qad, jac, outputs, invert, tol, max_iter, lo, hi, heights,
           normals, velocities, accelerations, rest):  # pragma: no cover  (compiled)
    """:func:`surface_f64` for the points lo..hi-1, written into the output rows lo..hi-1."""
    n, m = hi - lo, kd.shape[1]
    x, y = xy[lo:hi, 0].copy(), xy[lo:hi, 1].copy()
    base, s, c = np.empty((m, n)), np.empty((m, n)), np.empty((m, n))
    horizontal = False
    for j in range(m):
        horizontal = horizontal or qad[j, 0] != 0.0 or qad[j, 1] != 0.0
        for i in range(n):
            base[j, i] = x[i] * kd[0, j] + y[i] * kd[1, j] + time_phase[j]
            s[j, i], c[j, i] = _sincos(base[j, i])
    d = (_invert(base, kd, qad, jac, tol, max_iter, s, c) if invert and horizontal
         else np.zeros((2, n)))
    out = np.zeros((12, n))
    for k in range(12):
        for j in range(m):
            wc, ws = outputs[j, k], outputs[m + j, k]
            for i in range(n):
                out[k, i] += c[j, i] * wc + s[j, i] * ws
    block_normals = np.empty((n, 3))
    _normals(out, block_normals)
    for i in range(n):
        heights[lo + i] = out[0, i]
        rest[lo + i, 0], rest[lo + i, 1] = x[i] + d[0, i], y[i] + d[1, i]
        for k in range(3):
            normals[lo + i, k] = block_normals[i, k]
            velocities[lo + i, k] = out[1 + k, i]
            accelerations[lo + i, k] = out[4 + k, i]


@kernel
def surface_f64(xy, kd, time_phase, qad, jac, outputs, invert, tol, max_iter
                ):  # pragma: no cover  (compiled)
    """Height, normal, particle velocity and acceleration, and rest position at N points.

    The points go in blocks of :data:`_BLOCK` phases, each block in lockstep; a point's
    result does not depend on the other points.

    Args:
        xy: (N, 2) m, world horizontal positions.
        kd: (2, M) rad/m, k D of every component.
        time_phase: (M,) rad, phi - omega t reduced modulo 2 pi (``waves.time_phase``).
        qad: (M, 2) m, Q a D.
        jac: (M, 3) Q a k [Dx Dx, Dx Dy, Dy Dy].
        outputs: (2M, 12) the weights of [cos, sin] (``waves._OUTPUTS``).
        invert: find the rest position under (x, y) (else (x, y) is taken as it).
        tol: m, the inversion's residual.
        max_iter: its iteration bound.

    Returns:
        (heights (N,) m, normals (N, 3), velocities (N, 3) m/s, accelerations (N, 3) m/s^2,
        rest positions (N, 2) m).
    """
    n = xy.shape[0]
    heights, normals, rest = np.empty(n), np.empty((n, 3)), np.empty((n, 2))
    velocities, accelerations = np.empty((n, 3)), np.empty((n, 3))
    size = max(64, _BLOCK // max(kd.shape[1], 1))
    for lo in range(0, n, size):
        _block(xy, kd, time_phase, qad, jac, outputs, invert, tol, max_iter, lo,
               min(lo + size, n), heights, normals, velocities, accelerations, rest)
    return heights, normals, velocities, accelerations, rest


def warm() -> float:
    """Compile (or load from the cache) this module's kernels; returns the s it took."""
    start = time.perf_counter()
    kd, qad = np.array([[0.25], [0.0]]), np.array([[0.1, 0.0]])
    weights = np.zeros((2, 12))
    surface_f64(np.zeros((1, 2)), kd, np.zeros(1), qad, np.zeros((1, 3)), weights, True,
                1e-7, 8)
    sincos(np.zeros(1))
    return time.perf_counter() - start
