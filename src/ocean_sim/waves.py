"""Gerstner wave field: displacement, height queries, normals and particle kinematics.

Pure numpy; never imports rclpy. Conventions (DESIGN.md, "Waves"): world frame ENU, the wave
direction is the heading it travels toward, radians counter-clockwise from +x. A surface
particle at rest position ``p0 = (x0, y0)`` moves, for components ``i``, to::

    theta_i = k_i * dot(D_i, p0) - omega_i * t + phi_i,   omega_i^2 = g k_i tanh(k_i h)
    x = x0 - sum_i Q_i a_i D_ix sin(theta_i)
    y = y0 - sum_i Q_i a_i D_iy sin(theta_i)
    z =      sum_i     a_i      cos(theta_i)

Source: Tessendorf, "Simulating Ocean Water" (SIGGRAPH course notes, 2001), eq. 9 for the
displacement and eq. 14 for the finite-depth dispersion relation; the seed notes
(../shared/seed/boat-on-gerstner-waves.txt, "Gerstner waves") for the steepness form.

A world point ``(x, y)`` is not a rest position: the height there is ``z(p0)`` at the ``p0``
whose displaced position lands on ``(x, y)``. :func:`find_rest_positions` inverts the
horizontal displacement by damped Newton iteration (see its docstring for the bound).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ocean_sim.constants import GRAVITY, TWO_PI

__all__ = [
    "INVERSION_MAX_ITERATIONS",
    "INVERSION_TOLERANCE",
    "InvalidSeaStateError",
    "SurfaceSample",
    "WaveComponent",
    "WaveField",
    "angular_frequency",
    "displace",
    "find_rest_positions",
    "sample_surface",
    "surface_height",
]

#: Horizontal residual, m, at which the rest-position inversion stops. Heights are then
#: exact to well below 1 mm wherever the surface slope is finite.
INVERSION_TOLERANCE = 1e-7

#: Upper bound on Newton iterations of the inversion (it typically needs 3-6).
INVERSION_MAX_ITERATIONS = 60


class InvalidSeaStateError(ValueError):
    """A sea state that the Gerstner model refuses.

    Attributes:
        key: which value, e.g. ``"components[2].wavelength"``.
        value: the offending value.
        allowed: what would have been accepted.

    """

    def __init__(self, key: str, value: object, allowed: str) -> None:
        self.key = key
        self.value = value
        self.allowed = allowed
        super().__init__(f"{key} = {value!r} is not allowed: {allowed}")


@dataclass(frozen=True)
class WaveComponent:
    """One Gerstner component.

    Attributes:
        amplitude: a, m, >= 0.
        wavelength: lambda, m, > 0.
        direction: heading the wave travels toward, rad, counter-clockwise from +x (east).
        steepness: Q, dimensionless, 0 (sine wave) .. 1 (trochoid, sharp crests).
        phase: phi, rad.

    """

    amplitude: float
    wavelength: float
    direction: float = 0.0
    steepness: float = 0.0
    phase: float = 0.0

    @property
    def wavenumber(self) -> float:
        """K = 2 pi / wavelength, rad/m."""
        return TWO_PI / self.wavelength


def angular_frequency(wavenumber: np.ndarray | float, gravity: float, depth: float) -> np.ndarray:
    """Linear dispersion relation omega = sqrt(g k tanh(k h)).

    Args:
        wavenumber: k, rad/m (any shape).
        gravity: g, m/s^2.
        depth: h, m; ``inf`` for deep water (then omega = sqrt(g k)).

    Returns:
        omega, rad/s, same shape as ``wavenumber``.

    Source: Tessendorf (2001), eq. 14; Dean & Dalrymple, "Water Wave Mechanics for Engineers
    and Scientists" (1991), eq. 4.19.

    """
    k = np.asarray(wavenumber, dtype=float)
    if math.isinf(depth):
        return np.sqrt(gravity * k)
    return np.sqrt(gravity * k * np.tanh(k * depth))


@dataclass(frozen=True)
class _Arrays:
    """Per-component arrays, shape (M,), derived once from a :class:`WaveField`."""

    a: np.ndarray  # amplitude, m
    k: np.ndarray  # wavenumber, rad/m
    dx: np.ndarray  # direction unit vector x
    dy: np.ndarray  # direction unit vector y
    q: np.ndarray  # steepness
    phi: np.ndarray  # phase, rad
    omega: np.ndarray  # angular frequency, rad/s
    kd: np.ndarray  # (2, M): k * D, rad/m
    qad: np.ndarray  # (M, 2): Q a D, m


@dataclass(frozen=True)
class WaveField:
    """A sea state: Gerstner components over water of depth ``depth``.

    Construction validates: refuses non-finite values, non-positive wavelength, negative
    amplitude, steepness outside [0, 1], non-positive gravity or depth, and seas whose crests
    would loop (sum_i Q_i k_i a_i > 1).

    Attributes:
        components: the wave components.
        gravity: g, m/s^2, > 0.
        depth: h, m, > 0; ``inf`` = deep water.

    """

    components: tuple[WaveComponent, ...] = ()
    gravity: float = GRAVITY
    depth: float = math.inf

    def __post_init__(self) -> None:
        object.__setattr__(self, "components", tuple(self.components))
        _validate(self)

    @property
    def is_flat(self) -> bool:
        """True for a still, flat sea (no component with a non-zero amplitude)."""
        return not any(c.amplitude > 0.0 for c in self.components)

    @property
    def steepness_sum(self) -> float:
        """sum_i Q_i k_i a_i: crests stay free of loops while this is <= 1."""
        return float(np.sum(self.arrays.q * self.arrays.k * self.arrays.a))

    @cached_property
    def arrays(self) -> _Arrays:
        """Per-component numpy arrays (computed once)."""
        cs = self.components
        a = np.array([c.amplitude for c in cs], dtype=float)
        lam = np.array([c.wavelength for c in cs], dtype=float)
        k = TWO_PI / lam if cs else np.zeros(0)
        heading = np.array([c.direction for c in cs], dtype=float)
        dx, dy = np.cos(heading), np.sin(heading)
        q = np.array([c.steepness for c in cs], dtype=float)
        phi = np.array([c.phase for c in cs], dtype=float)
        omega = angular_frequency(k, self.gravity, self.depth)
        kd = np.stack([k * dx, k * dy]) if cs else np.zeros((2, 0))
        qad = np.stack([q * a * dx, q * a * dy], axis=1) if cs else np.zeros((0, 2))
        return _Arrays(a=a, k=k, dx=dx, dy=dy, q=q, phi=phi, omega=omega, kd=kd, qad=qad)


def _validate(wf: WaveField) -> None:
    if not (math.isfinite(wf.gravity) and wf.gravity > 0.0):
        raise InvalidSeaStateError("gravity", wf.gravity, "must be a finite number > 0 (m/s^2)")
    if math.isnan(wf.depth) or wf.depth <= 0.0:
        raise InvalidSeaStateError("depth", wf.depth, "must be > 0 (m), or .inf for deep water")
    for i, c in enumerate(wf.components):
        name = f"components[{i}]"
        for attr in ("amplitude", "wavelength", "direction", "steepness", "phase"):
            v = getattr(c, attr)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InvalidSeaStateError(f"{name}.{attr}", v, "must be a finite number")
        if c.amplitude < 0.0:
            raise InvalidSeaStateError(f"{name}.amplitude", c.amplitude, "must be >= 0 (m)")
        if c.wavelength <= 0.0:
            raise InvalidSeaStateError(f"{name}.wavelength", c.wavelength, "must be > 0 (m)")
        if not 0.0 <= c.steepness <= 1.0:
            raise InvalidSeaStateError(f"{name}.steepness", c.steepness, "must be in [0, 1]")
    s = sum(c.steepness * c.wavenumber * c.amplitude for c in wf.components)
    if s > 1.0 + 1e-12:
        raise InvalidSeaStateError(
            "components",
            f"sum of Q*k*a = {s:.4g}",
            "crests loop when sum_i steepness_i * (2 pi / wavelength_i) * amplitude_i > 1; "
            "lower the steepness or the amplitude",
        )


def _phases(wf: WaveField, rest_xy: np.ndarray, t: float) -> np.ndarray:
    """theta_i at rest positions: (N, M) rad.

    omega*t is reduced modulo 2 pi per component before it meets the (N, M) array, so long
    runs keep full precision.
    """
    ar = wf.arrays
    time_phase = np.mod(ar.omega * t, TWO_PI)
    return rest_xy @ ar.kd + (ar.phi - time_phase)


def displace(wf: WaveField, rest_xy: np.ndarray, t: float) -> np.ndarray:
    """Displaced surface positions of particles at rest positions.

    Args:
        wf: the sea state.
        rest_xy: (N, 2) m, rest positions p0 in the world frame.
        t: simulation time, s.

    Returns:
        (N, 3) m, world positions (x, y, z) of those surface particles.

    """
    p0 = np.asarray(rest_xy, dtype=float).reshape(-1, 2)
    out = np.zeros((p0.shape[0], 3))
    out[:, :2] = p0
    if not wf.components:
        return out
    theta = _phases(wf, p0, t)
    out[:, :2] -= np.sin(theta) @ wf.arrays.qad
    out[:, 2] = np.cos(theta) @ wf.arrays.a
    return out


def find_rest_positions(
    wf: WaveField,
    xy: np.ndarray,
    t: float,
    tol: float = INVERSION_TOLERANCE,
    max_iter: int = INVERSION_MAX_ITERATIONS,
) -> np.ndarray:
    """Rest positions p0 whose displaced horizontal position is ``xy``.

    Solves F(p0) = p0 - sum_i Q_i a_i D_i sin(theta_i(p0)) - xy = 0 by Newton iteration on
    the 2x2 Jacobian J = I - sum_i Q_i a_i k_i cos(theta_i) D_i D_i^T. J is the Hessian of a
    convex potential when sum Q k a <= 1, so it is positive semi-definite. Where a Newton step
    does not reduce |F| (near a cusp of a sea with sum Q k a close to 1), the fixed-point step
    p0 <- xy + sum Q a D sin(theta) is taken instead; it shrinks |F| by the factor
    sum Q k a < 1. Iteration stops when |F| < ``tol`` for every point (typically 3-6
    iterations) or after ``max_iter``.

    Args:
        wf: the sea state.
        xy: (N, 2) m, world horizontal positions.
        t: simulation time, s.
        tol: horizontal residual, m.
        max_iter: iteration bound.

    Returns:
        (N, 2) m, rest positions.

    """
    target = np.asarray(xy, dtype=float).reshape(-1, 2)
    p = target.copy()
    ar = wf.arrays
    if not wf.components or not np.any(ar.q * ar.a > 0.0):
        return p

    def residual(pts: np.ndarray, goal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        theta = _phases(wf, pts, t)
        return pts - np.sin(theta) @ ar.qad - goal, theta

    qak = ar.q * ar.a * ar.k
    wxx, wxy, wyy = qak * ar.dx * ar.dx, qak * ar.dx * ar.dy, qak * ar.dy * ar.dy
    r, theta = residual(p, target)
    err = np.hypot(r[:, 0], r[:, 1])
    for _ in range(max_iter):
        active = np.flatnonzero(err > tol)
        if active.size == 0:
            break
        c = np.cos(theta[active])
        jxx, jxy, jyy = 1.0 - c @ wxx, -(c @ wxy), 1.0 - c @ wyy
        det = jxx * jyy - jxy * jxy
        ra = r[active]
        safe = np.where(det > 1e-12, det, 1.0)
        newton = np.stack(
            [(jyy * ra[:, 0] - jxy * ra[:, 1]) / safe, (jxx * ra[:, 1] - jxy * ra[:, 0]) / safe],
            axis=1,
        )
        step = np.where((det > 1e-12)[:, None], newton, ra)
        cand = p[active] - step
        rc, thc = residual(cand, target[active])
        ec = np.hypot(rc[:, 0], rc[:, 1])
        worse = ec >= err[active]
        if np.any(worse):
            w = np.flatnonzero(worse)
            cand[w] = p[active[w]] - ra[w]
            rc[w], thc[w] = residual(cand[w], target[active[w]])
            ec[w] = np.hypot(rc[w, 0], rc[w, 1])
        p[active], r[active], theta[active], err[active] = cand, rc, thc, ec
    return p


@dataclass(frozen=True)
class SurfaceSample:
    """The water surface at N world points.

    Attributes:
        heights: (N,) m, surface elevation z at each (x, y).
        normals: (N, 3) unit upward surface normals, world frame.
        velocities: (N, 3) m/s, velocity of the surface water particle there.
        accelerations: (N, 3) m/s^2, acceleration of that particle.
        rest_xy: (N, 2) m, the particles' rest positions p0.

    """

    heights: np.ndarray
    normals: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray
    rest_xy: np.ndarray


def sample_surface(wf: WaveField, xy: np.ndarray, t: float) -> SurfaceSample:
    """Height, normal and particle kinematics of the surface at world points.

    Normals are the cross product of the analytic tangents dP/dx0 x dP/dy0 of the displaced
    surface P(p0) (Tessendorf 2001, sec. 4.2; the seed notes' tangent/binormal form), so they
    equal finite differences of the displaced surface. Velocity and acceleration are dP/dt and
    d2P/dt2 at fixed p0.

    Args:
        wf: the sea state.
        xy: (N, 2) m, world horizontal positions (a third column, if given, is ignored).
        t: simulation time, s.

    Returns:
        The :class:`SurfaceSample` at those points.

    """
    pts = np.asarray(xy, dtype=float)
    pts = pts.reshape(-1, pts.shape[-1] if pts.ndim > 1 else 2)[:, :2]
    n = pts.shape[0]
    p0 = find_rest_positions(wf, pts, t)
    normals = np.zeros((n, 3))
    normals[:, 2] = 1.0
    if not wf.components:
        zeros = np.zeros((n, 3))
        return SurfaceSample(np.zeros(n), normals, zeros, zeros.copy(), p0)
    ar = wf.arrays
    theta = _phases(wf, p0, t)
    s, c = np.sin(theta), np.cos(theta)
    heights = c @ ar.a
    # Tangents of P(p0) along x0 and y0.
    w = c * (ar.q * ar.a * ar.k)
    ak_s = s * (ar.a * ar.k)
    txx, txy, txz = 1.0 - w @ (ar.dx * ar.dx), -(w @ (ar.dx * ar.dy)), -(ak_s @ ar.dx)
    tyx, tyy, tyz = txy, 1.0 - w @ (ar.dy * ar.dy), -(ak_s @ ar.dy)
    nrm = np.stack([txy * tyz - txz * tyy, txz * tyx - txx * tyz, txx * tyy - txy * tyx], axis=1)
    length = np.linalg.norm(nrm, axis=1)
    ok = length > 1e-12  # a cusp (sum Q k a = 1 at a crest) has a vertical normal
    normals[ok] = nrm[ok] / length[ok, None]
    qaw = ar.q * ar.a * ar.omega
    aw = ar.a * ar.omega
    aw2 = aw * ar.omega
    qaw2 = qaw * ar.omega
    vel = np.stack([c @ (qaw * ar.dx), c @ (qaw * ar.dy), s @ aw], axis=1)
    acc = np.stack([s @ (qaw2 * ar.dx), s @ (qaw2 * ar.dy), -(c @ aw2)], axis=1)
    return SurfaceSample(heights, normals, vel, acc, p0)


def surface_height(wf: WaveField, xy: np.ndarray, t: float) -> np.ndarray:
    """Surface elevation at world points.

    Args:
        wf: the sea state.
        xy: (N, 2) m, world horizontal positions.
        t: simulation time, s.

    Returns:
        (N,) m, the height z of the displaced surface above each (x, y).

    """
    p0 = find_rest_positions(wf, xy, t)
    if not wf.components:
        return np.zeros(p0.shape[0])
    return np.cos(_phases(wf, p0, t)) @ wf.arrays.a
