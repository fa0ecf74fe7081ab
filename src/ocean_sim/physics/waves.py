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
(docs/seed-notes.txt, "Gerstner waves") for the steepness form.

A world point ``(x, y)`` is not a rest position: the height there is ``z(p0)`` at the ``p0``
whose displaced position lands on ``(x, y)``. :func:`find_rest_positions` inverts the
horizontal displacement by damped Newton iteration (see its docstring for the bound).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal, get_args

import numpy as np

from ocean_sim.physics.constants import GRAVITY, TWO_PI
from ocean_sim.physics.errors import InvalidValueError

__all__ = [
    "DEFAULT_PRECISION",
    "INVERSION_MAX_ITERATIONS",
    "INVERSION_TOLERANCE",
    "MAX_COMPONENTS",
    "PRECISIONS",
    "InvalidSeaStateError",
    "Precision",
    "SurfaceSample",
    "TileGrid",
    "WaveComponent",
    "WaveField",
    "angular_frequency",
    "component_phases",
    "displace",
    "find_rest_positions",
    "orbital_velocity",
    "pressure_head",
    "sample_surface",
    "slope_orbit_velocity",
    "stokes_drift",
    "surface_height",
    "time_phase",
]

#: Horizontal residual, m, at which the rest-position inversion stops, per precision. Heights
#: are then exact to well below 1 mm wherever the surface slope is finite.
INVERSION_TOLERANCE = {"float64": 1e-7, "float32": 1e-5}

#: Floating-point precisions of the surface queries. float64 is the reference and the default,
#: computed by a compiled kernel (:mod:`ocean_sim.physics.surface_kernel`), which is also the
#: fastest at every batch size measured (docs/performance.md); float32 is numpy's
#: (vectorized float32 sin/cos), kept selectable: its height error is about
#: 2^-24 * sum_i(a_i k_i) * (distance of a point from its batch's centre): under 0.1 mm for
#: physical seas (a k <= 0.45) over batches a few hundred metres wide.
Precision = Literal["float64", "float32"]
PRECISIONS: tuple[Precision, ...] = get_args(Precision)
#: The precision of every surface query that does not choose one (boats, /ocean services).
DEFAULT_PRECISION: Precision = "float64"

#: Upper bound on Newton iterations of the inversion (it typically needs 3-6).
INVERSION_MAX_ITERATIONS = 60

#: The most components a sea may have, whoever gives it: a scenario, the ocean node's
#: parameters, an /ocean/wave_field message (each component costs every query point a
#: sin/cos; a spectrum's default is 16, its maximum 1000; an FFT tile of 64 x 64 has 3969).
MAX_COMPONENTS = 4096


class InvalidSeaStateError(InvalidValueError):
    """A sea state that the Gerstner model refuses.

    Attributes:
        key: which value, e.g. ``"components[2].wavelength"``.
        value: the offending value.
        allowed: what would have been accepted.
    """

    def __init__(self, key: str, value: object, allowed: str) -> None:
        super().__init__(key, value, allowed, f"{key} = {value!r} is not allowed: {allowed}")


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
class TileGrid:
    """The periodic lattice an FFT tile's components lie on (ocean_sim/physics/fft.py).

    Every component's wavevector is k = 2 pi (n, m) / size with integers |n|, |m| <
    resolution / 2, so the sea repeats every ``size`` in x and y and its surface on any grid
    of rest positions spaced size / M can be summed by inverse FFTs (:func:`fft.grid_surface`).

    Attributes:
        size: L, m, the tile's side, > 0.
        resolution: N, even, >= 4: the tile's N x N grid (its waves are (N - 1)^2 at most).
    """

    size: float
    resolution: int


#: How far from an integer n = k_x L / (2 pi) may be for a component to lie on a tile's
#: lattice (the wavelength and direction of a lattice wave, round-tripped through floats, are
#: off by ~1e-14).
_LATTICE_TOLERANCE = 1e-6


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
    amplitude, steepness outside [0, 1], non-positive gravity or depth, seas whose crests
    would loop (sum_i Q_i k_i a_i > 1), and a ``tile`` whose lattice a component is not on.

    Attributes:
        components: the wave components.
        gravity: g, m/s^2, > 0.
        depth: h, m, > 0; ``inf`` = deep water.
        tile: the FFT tile the components are (``ocean.model: fft``), or None: a Gerstner sum
            (its surface is then never computed on a grid; the queries ignore it).
    """

    components: tuple[WaveComponent, ...] = ()
    gravity: float = GRAVITY
    depth: float = math.inf
    tile: TileGrid | None = None
    # what filtered() and weights() computed: derived from the frozen fields, written by
    # those two methods only (once per sea and key; never stale)
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

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

    def filtered(self, min_wavelength: float) -> WaveField:
        """The same sea without components shorter than ``min_wavelength`` (m); cached.

        A hull is not moved by ripples much shorter than itself (Crest's MinSpatialLength).
        """
        if min_wavelength <= 0.0:
            return self
        key = ("filtered", float(min_wavelength))
        if key not in self._derived:
            kept = tuple(c for c in self.components if c.wavelength >= min_wavelength)
            self._derived[key] = WaveField(kept, self.gravity, self.depth, self.tile)
        return self._derived[key]

    def weights(self, precision: Precision) -> _Weights:
        """The surface kernels' per-component weights in ``precision``; computed once."""
        key = ("weights", precision)
        if key not in self._derived:
            self._derived[key] = _weights_of(self.arrays, precision)
        return self._derived[key]

    @cached_property
    def surface_stokes_drift(self) -> np.ndarray:
        """(3,) m/s, the Stokes drift at the mean surface (:func:`stokes_drift`); computed once."""
        return np.array([*stokes_drift(self), 0.0])

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
    if len(wf.components) > MAX_COMPONENTS:
        raise InvalidSeaStateError("components", f"{len(wf.components)} components",
                                   f"at most {MAX_COMPONENTS}")
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
    if wf.tile is not None:
        _validate_tile(wf)


def _validate_tile(wf: WaveField) -> None:
    """Refuse a tile of bad size or resolution, or whose lattice a component is not on."""
    size, n = wf.tile.size, wf.tile.resolution
    if isinstance(size, bool) or not isinstance(size, (int, float)) or not (
            math.isfinite(size) and size > 0.0):
        raise InvalidSeaStateError("tile.size", size, "must be a finite number > 0 (m)")
    if isinstance(n, bool) or not isinstance(n, int) or n < 4 or n % 2:
        raise InvalidSeaStateError("tile.resolution", n, "must be an even integer >= 4")
    index = wf.arrays.kd * (size / TWO_PI)  # (2, M) lattice indices n, m
    whole = np.round(index)
    outside = ((np.abs(index - whole) > _LATTICE_TOLERANCE) | (np.abs(whole) >= n // 2)
               | ~np.any(whole != 0.0, axis=0))  # k = 0 is no wave: a tile far too small
    if outside.any():
        i = int(np.flatnonzero(outside.any(axis=0))[0])
        raise InvalidSeaStateError(
            f"components[{i}]", wf.components[i],
            f"must lie on the tile's lattice: wavevector 2 pi (n, m) / {size:g} m with "
            f"integers |n|, |m| < {n // 2}")


def time_phase(wf: WaveField, t: float) -> np.ndarray:
    """(M,) rad: phi_i - omega_i t reduced modulo 2 pi in float64, so long runs keep precision."""
    ar = wf.arrays
    return np.mod(ar.phi - np.mod(ar.omega * t, TWO_PI), TWO_PI)


def component_phases(wf: WaveField, xy: np.ndarray, t: float) -> np.ndarray:
    """(N, M) rad, theta_i = k_i D_i . p - omega_i t + phi_i of every component at N points.

    Args:
        wf: the sea state.
        xy: (N, 2) m, horizontal positions (rest positions of surface particles, or any
            points for linear theory).
        t: simulation time, s.
    """
    return np.asarray(xy, dtype=float) @ wf.arrays.kd + time_phase(wf, t)


def displace(wf: WaveField, rest_xy: np.ndarray, t: float) -> np.ndarray:
    """Displaced surface positions of particles at rest positions (float64 reference).

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
    theta = p0 @ wf.arrays.kd + time_phase(wf, t)
    out[:, :2] -= np.sin(theta) @ wf.arrays.qad
    out[:, 2] = np.cos(theta) @ wf.arrays.a
    return out


@dataclass(frozen=True)
class _Weights:
    """Per-component arrays in one precision, shaped for matrix products."""

    kd: np.ndarray  # (2, M) k D
    qad: np.ndarray  # (M, 2) Q a D
    jac: np.ndarray  # (M, 3) Q a k [Dx Dx, Dx Dy, Dy Dy]
    # (2M, 12): [cos theta, sin theta] @ outputs = the columns of _OUTPUTS
    outputs: np.ndarray
    horizontal: bool  # any Q a > 0: the inversion is needed


#: The columns of [cos, sin] @ _Weights.outputs: height, particle velocity and acceleration
#: (3 each), then the terms of the tangents dP/dx0 = (1 - A, -B, -Sx), dP/dy0 = (-B, 1 - C, -Sy).
_OUTPUTS = ("z", "vx", "vy", "vz", "ax", "ay", "az", "A", "B", "C", "Sx", "Sy")


def _weights_of(ar: _Arrays, precision: Precision) -> _Weights:
    """The kernels' per-component weights of a sea's arrays, in ``precision``."""
    qak = ar.q * ar.a * ar.k
    qaw = ar.q * ar.a * ar.omega
    jac = np.stack([qak * ar.dx * ar.dx, qak * ar.dx * ar.dy, qak * ar.dy * ar.dy], axis=1)
    zero = np.zeros_like(ar.a)
    # P = p0 - sum Q a D sin(theta) + z a cos(theta), theta = k D.p0 - omega t + phi
    of_cos = [ar.a, qaw * ar.dx, qaw * ar.dy, zero, zero, zero, -ar.a * ar.omega**2,
              *jac.T, zero, zero]
    of_sin = [zero, zero, zero, ar.a * ar.omega, qaw * ar.omega * ar.dx,
              qaw * ar.omega * ar.dy, zero, zero, zero, zero, ar.a * ar.k * ar.dx,
              ar.a * ar.k * ar.dy]
    outputs = np.concatenate([np.stack(of_cos, axis=1), np.stack(of_sin, axis=1)])
    dt = np.dtype(precision)
    return _Weights(kd=ar.kd.astype(dt), qad=ar.qad.astype(dt), jac=jac.astype(dt),
                    outputs=outputs.astype(dt), horizontal=bool(np.any(ar.q * ar.a > 0.0)))


def _check_precision(precision: Precision) -> None:
    if precision not in PRECISIONS:
        raise ValueError(f"precision {precision!r} is not allowed: must be one of {PRECISIONS}")


def _newton_step(j: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N, 2) Newton steps J^-1 r of the inversion, J = I - sum Q a k cos(theta) D D^T.

    Args:
        j: (N, 3) the sums' xx, xy and yy entries (``cos theta @ jac``).
        r: (N, 2) m, the residuals.

    Returns:
        The steps, and (N,) det J. Where J is near singular (det <= 1e-6) the step is the
        fixed-point step r itself.
    """
    jxx, jxy, jyy = 1.0 - j[:, 0], -j[:, 1], 1.0 - j[:, 2]
    det = jxx * jyy - jxy * jxy
    step = np.empty_like(r)
    step[:, 0] = jyy * r[:, 0] - jxy * r[:, 1]
    step[:, 1] = jxx * r[:, 1] - jxy * r[:, 0]
    if det.min() > 1e-6:
        step /= det[:, None]
    else:  # J near singular: the fixed-point step there
        ok = det > 1e-6
        step /= np.where(ok, det, 1.0)[:, None]
        step[~ok] = r[~ok]
    return step, det


#: det J below which a point is near a cusp of the surface (sum Q k a close to 1; a sea of
#: sum Q k a <= 0.9 never gets here, as det J >= (1 - sum Q k a)^2): there the fixed-point
#: step barely shrinks |F|, so a rejected Newton step is tried damped first.
_CUSP_DET = 1e-2
#: At most this many halvings of a damped Newton step.
_HALVINGS = 40


def _damped(base: np.ndarray, d: np.ndarray, step: np.ndarray, was: np.ndarray, w: _Weights
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The longest step / 2^m (m = 1 .. _HALVINGS) that shrinks |F| below ``was``, per point.

    Near a cusp F(p0) grows like the cube of the distance from it: the full Newton step from
    there overshoots by orders of magnitude, the fixed-point step shrinks |F| by a factor
    close to 1 (60 iterations left 0.67 mm at sum Q k a = 1), a halved step converges.

    Returns:
        (candidate d, sin theta, residual, |residual|); |residual| is inf where no halving
        helped.
    """
    cand, sa = d.copy(), np.zeros((d.shape[0], base.shape[1]), dtype=base.dtype)
    rc, ec = np.zeros_like(d), np.full(d.shape[0], np.inf, dtype=d.dtype)
    todo = np.arange(d.shape[0])
    h = 0.5
    for _ in range(_HALVINGS):
        if todo.size == 0:
            break
        c = d[todo] - h * step[todo]
        s = np.sin(base[todo] + c @ w.kd)
        r = c - s @ w.qad
        e = np.hypot(r[:, 0], r[:, 1])
        better = e < was[todo]
        got = todo[better]
        cand[got], sa[got], rc[got], ec[got] = c[better], s[better], r[better], e[better]
        todo, h = todo[~better], h * 0.5
    return cand, sa, rc, ec


def _fall_back(back: np.ndarray, worse: np.ndarray, base: np.ndarray, d: np.ndarray,
               ra: np.ndarray, step: np.ndarray, det: np.ndarray, w: _Weights,
               out: tuple[np.ndarray, ...]) -> None:
    """Where a Newton step did not shrink |F|: the fixed-point step, or a damped Newton step.

    The fixed-point step shrinks |F| by sum Q k a < 1; near a cusp (det J < _CUSP_DET) a
    damped Newton step is taken instead where it does better (:func:`_damped`).

    Args:
        back: (W,) those points' rows in ``base`` and ``d`` (all of the batch's points).
        worse: (W,) their rows in the iteration's R rows (``ra``, ``step``, ``det``,
            ``out``).
        base: (N, M) rad, the points' phases at d = 0.
        d: (N, 2) m, the corrections before the step.
        ra: (R, 2) m, the residuals before the step.
        step: (R, 2) m, the Newton steps that did not shrink them.
        det: (R,) det J of those steps.
        w: the sea's weights.
        out: (cand, theta, sa, rc, ec): the step's corrections, phases, sines, residuals and
            |residuals|, updated in place at ``worse``.
    """
    cand, theta, sa, rc, ec = out
    cand[worse] = d[back] - ra[worse]
    theta[worse] = base[back] + cand[worse] @ w.kd
    sa[worse] = np.sin(theta[worse])
    rc[worse] = cand[worse] - sa[worse] @ w.qad
    ec[worse] = np.hypot(rc[worse, 0], rc[worse, 1])
    near = det[worse] < _CUSP_DET
    if near.any():
        at, near = back[near], worse[near]
        dc, ds, dr, de = _damped(base[at], d[at], step[near], ec[near], w)
        take = de < ec[near]
        pick = near[take]
        cand[pick], sa[pick], rc[pick], ec[pick] = dc[take], ds[take], dr[take], de[take]
        theta[pick] = base[at[take]] + cand[pick] @ w.kd


def _solve(wf: WaveField, xy: np.ndarray, t: float, precision: Precision, invert: bool,
           tol: float, max_iter: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rest positions of world points and sin/cos of their phases.

    The unknown is the correction d = p0 - xy (metres, small), and the phase is split as
    theta = base + k D . d with base = k D . xy + phi - omega t, each point's own, computed in
    float64 and (float32) reduced modulo 2 pi before the cast, so float32 keeps sub-millimetre
    accuracy far from the origin. Per point, not about the batch's centre: a point's result
    does not depend on the other points of the batch, so a fleet split into shards, or a boat
    stepped alone, gets the same numbers (the batch centre made them differ by float32's
    rounding, 1.5e-7 m/s).

    Returns:
        (p0 (N, 2) float64 m, sin theta (N, M), cos theta (N, M)) in ``precision``.
    """
    dt = np.dtype(precision)
    w = wf.weights(precision)
    n = xy.shape[0]
    base = xy @ wf.arrays.kd + time_phase(wf, t)
    if dt != np.float64:  # reduced to [-pi, pi]: rint is several times cheaper than np.mod
        turns = base * (1.0 / TWO_PI)
        np.rint(turns, out=turns)
        turns *= TWO_PI
        base -= turns
        base = base.astype(dt)
    s, c = np.sin(base), np.cos(base)
    if not (invert and w.horizontal):
        return xy.copy(), s, c
    # F(d) = d - sum Q a D sin(theta) = 0 (F = p0 - displacement - xy), from d = 0
    d = np.zeros(xy.shape, dtype=dt)
    r = -(s @ w.qad)
    err = np.hypot(r[:, 0], r[:, 1])
    for _ in range(max_iter):
        active = np.flatnonzero(err > tol)  # (a non-finite point is never active)
        if active.size == 0:
            break
        # Most points active: step them all and keep the converged ones as they were, which
        # costs less than (N, M) gathers and scatters (and gives the same numbers).
        full = 2 * active.size > n
        rows = slice(None) if full else active
        ra = r[rows]
        step, det = _newton_step(c[rows] @ w.jac, ra)
        cand = d[rows] - step
        theta = base[rows] + cand @ w.kd
        sa = np.sin(theta)
        rc = cand - sa @ w.qad
        ec = np.hypot(rc[:, 0], rc[:, 1])
        was = err[rows]
        if (ec >= was).any():
            worse = np.flatnonzero((ec >= was) & (was > tol))
            if worse.size:
                _fall_back(worse if full else active[worse], worse, base, d, ra, step, det,
                           w, (cand, theta, sa, rc, ec))
        if active.size == n:
            d, s, c, r, err = cand, sa, np.cos(theta), rc, ec
        elif full:
            done = err <= tol
            keep = done[:, None]
            d, s, r = np.where(keep, d, cand), np.where(keep, s, sa), np.where(keep, r, rc)
            c, err = np.where(keep, c, np.cos(theta)), np.where(done, err, ec)
        else:
            d[active], s[active], c[active] = cand, sa, np.cos(theta)
            r[active], err[active] = rc, ec
    return xy + d.astype(float), s, c


def find_rest_positions(
    wf: WaveField,
    xy: np.ndarray,
    t: float,
    tol: float | None = None,
    max_iter: int = INVERSION_MAX_ITERATIONS,
    precision: Precision = "float64",
) -> np.ndarray:
    """Rest positions p0 whose displaced horizontal position is ``xy``.

    Solves F(p0) = p0 - sum_i Q_i a_i D_i sin(theta_i(p0)) - xy = 0 by Newton iteration on
    the 2x2 Jacobian J = I - sum_i Q_i a_i k_i cos(theta_i) D_i D_i^T. J is the Hessian of a
    convex potential when sum Q k a <= 1, so it is positive semi-definite. Where a Newton step
    does not reduce |F| (near a cusp of a sea with sum Q k a close to 1), the fixed-point step
    p0 <- xy + sum Q a D sin(theta) is taken instead; it shrinks |F| by the factor
    sum Q k a < 1, which at a cusp is nearly 1 (a point starting next to one was left 0.67 mm
    off after 60 steps at sum Q k a = 1), so there (det J < 0.01) the Newton step halved until
    |F| shrinks is taken when it does better. Iteration stops when |F| < ``tol`` for every
    point (typically 3-6 iterations) or after ``max_iter``.

    Args:
        wf: the sea state.
        xy: (N, 2) m, world horizontal positions.
        t: simulation time, s.
        tol: horizontal residual, m (default :data:`INVERSION_TOLERANCE` of the precision).
        max_iter: iteration bound.
        precision: "float64" or "float32" (see :data:`PRECISIONS`).

    Returns:
        (N, 2) m, rest positions.
    """
    _check_precision(precision)
    pts = np.asarray(xy, dtype=float).reshape(-1, 2)
    if not wf.components:
        return pts.copy()
    tol = INVERSION_TOLERANCE[precision] if tol is None else tol
    return _solve(wf, pts, t, precision, True, tol, max_iter)[0]


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

    def rows(self, start: int, stop: int) -> SurfaceSample:
        """The sample at points start..stop-1 (views, no copy)."""
        return SurfaceSample(self.heights[start:stop], self.normals[start:stop],
                             self.velocities[start:stop], self.accelerations[start:stop],
                             self.rest_xy[start:stop])


def sample_surface(
    wf: WaveField,
    xy: np.ndarray,
    t: float,
    *,
    invert: bool = True,
    min_wavelength: float = 0.0,
    precision: Precision = "float64",
) -> SurfaceSample:
    """Height, normal and particle kinematics of the surface at world points.

    Normals are the cross product of the analytic tangents dP/dx0 x dP/dy0 of the displaced
    surface P(p0) (Tessendorf 2001, sec. 4.2; the seed notes' tangent/binormal form), so they
    equal finite differences of the displaced surface. Velocity and acceleration are dP/dt and
    d2P/dt2 at fixed p0.

    Args:
        wf: the sea state.
        xy: (N, 2) m, world horizontal positions (a third column, if given, is ignored).
        t: simulation time, s.
        invert: find the rest position whose displaced position is (x, y) (exact). False takes
            (x, y) itself as the rest position: the seed notes' "ignore horizontal
            displacement" approximation, faster, with errors of order Q a k * a.
        min_wavelength: m; components shorter than this are left out (0 = all).
        precision: "float64" (the reference, compiled) or "float32" (numpy).

    Returns:
        The :class:`SurfaceSample` at those points, float64 arrays.
    """
    _check_precision(precision)
    pts = np.asarray(xy, dtype=float)
    pts = pts.reshape(-1, pts.shape[-1] if pts.ndim > 1 else 2)[:, :2]
    sea = wf.filtered(min_wavelength)
    n = pts.shape[0]
    if not sea.components:
        normals = np.zeros((n, 3))
        normals[:, 2] = 1.0
        return SurfaceSample(np.zeros(n), normals, np.zeros((n, 3)), np.zeros((n, 3)),
                             pts.copy())
    if precision == "float64":  # compiled (surface_kernel.py); the numpy path is its oracle
        return _sample_compiled(sea, pts, t, invert)
    return _sample_numpy(sea, pts, t, precision, invert)


def _sample_compiled(sea: WaveField, pts: np.ndarray, t: float, invert: bool) -> SurfaceSample:
    """:func:`sample_surface` in float64 by the compiled kernel (a sea with components)."""
    from ocean_sim.physics.surface_kernel import surface_f64

    w = sea.weights("float64")
    return SurfaceSample(*surface_f64(np.ascontiguousarray(pts), w.kd, time_phase(sea, t),
                                      w.qad, w.jac, w.outputs, invert,
                                      INVERSION_TOLERANCE["float64"], INVERSION_MAX_ITERATIONS))


def _sample_numpy(sea: WaveField, pts: np.ndarray, t: float, precision: Precision,
                  invert: bool) -> SurfaceSample:
    """:func:`sample_surface` in numpy (float32, and the compiled float64 kernel's oracle)."""
    n = pts.shape[0]
    p0, s, c = _solve(sea, pts, t, precision, invert, INVERSION_TOLERANCE[precision],
                      INVERSION_MAX_ITERATIONS)
    w = sea.weights(precision)
    out = (np.concatenate([c, s], axis=1) @ w.outputs).astype(float)  # columns: _OUTPUTS
    a, b, cc, sx, sy = out[:, 7], out[:, 8], out[:, 9], out[:, 10], out[:, 11]
    # dP/dx0 x dP/dy0 with dP/dx0 = (1 - A, -B, -Sx), dP/dy0 = (-B, 1 - C, -Sy)
    nrm = np.empty((n, 3))
    nrm[:, 0] = b * sy + sx * (1.0 - cc)
    nrm[:, 1] = b * sx + sy * (1.0 - a)
    nrm[:, 2] = (1.0 - a) * (1.0 - cc) - b * b
    length = np.sqrt(np.einsum("ij,ij->i", nrm, nrm))
    if n and length.min() > 1e-12:
        normals = nrm / length[:, None]
    else:  # a cusp (sum Q k a = 1 at a crest) has a vertical normal
        normals = np.zeros((n, 3))
        normals[:, 2] = 1.0
        ok = length > 1e-12
        normals[ok] = nrm[ok] / length[ok, None]
    return SurfaceSample(out[:, 0], normals, out[:, 1:4], out[:, 4:7], p0)


def surface_height(wf: WaveField, xy: np.ndarray, t: float, **options: object) -> np.ndarray:
    """Surface elevation (N,) m at world points (N, 2) m; options as :func:`sample_surface`."""
    return sample_surface(wf, xy, t, **options).heights


def slope_orbit_velocity(wf: WaveField, rest_xy: np.ndarray, t: float) -> np.ndarray:
    """Horizontal velocity, (N, 2) m/s, that the surface slope gives a small floating body.

    A body floating on hydrostatic pressure is pushed sideways by -m g grad(eta); to first
    order in the slope, grad(eta) = -sum_i k_i a_i D_i sin(theta_i), so in its periodic motion
    on the waves it moves with u = sum_i (g k_i a_i / omega_i) D_i cos(theta_i), the surface
    orbital velocity of linear (Airy) theory, a_i omega_i / tanh(k_i h) per component
    (Dean & Dalrymple 1991, eq. 4.11 at z = 0). The Gerstner particle itself moves with
    Q_i a_i omega_i D_i cos(theta_i): the two agree for Q = 1 in deep water.

    Args:
        wf: the sea state.
        rest_xy: (N, 2) m, the rest positions p0 of the surface particles where the bodies
            float (:attr:`SurfaceSample.rest_xy`).
        t: simulation time, s.
    """
    p0 = np.asarray(rest_xy, dtype=float).reshape(-1, 2)
    if not wf.components:
        return np.zeros((p0.shape[0], 2))
    ar = wf.arrays
    amplitude = wf.gravity * ar.k * ar.a / ar.omega
    cos_theta = np.cos(p0 @ ar.kd + time_phase(wf, t))
    return cos_theta @ (amplitude[:, None] * np.stack([ar.dx, ar.dy], axis=1))


def pressure_head(wf: WaveField, rest_xy: np.ndarray, heights: np.ndarray, z: np.ndarray,
                  t: float) -> np.ndarray:
    """(N,) m, the pressure head p / (rho g) at world points below the surface.

    Hydrostatic plus the Froude-Krylov pressure of the incident waves, with Wheeler stretching.
    Linear (Airy) theory gives each component's dynamic pressure rho g a cos(theta) E(z), with
    the depth decay E = e^{k z} in deep water and cosh(k (z + h)) / cosh(k h) at depth h
    (Dean & Dalrymple 1991, eq. 4.23; Newman, "Marine Hydrodynamics", sec. 6.3). It is defined
    up to the mean level z = 0; Wheeler stretching (Wheeler 1970) maps the water column
    [-h, eta] onto [-h, 0], evaluating E at z_s = h (z - eta) / (h + eta) (z - eta in deep
    water), so that the pressure is exactly zero on the instantaneous surface and hydrostatic
    far below it::

        p / (rho g) = sum_i a_i cos(theta_i(p0)) E_i(z_s) - z

    The phases are those of the surface particle above the point (its rest position p0 from
    :attr:`SurfaceSample.rest_xy`), so that on the Gerstner surface sum_i a_i cos theta_i is
    its height eta. In still water the head is exactly -z.

    Args:
        wf: the sea state (already filtered to the components acting on the body).
        rest_xy: (N, 2) m, rest positions of the surface particles above the points.
        heights: (N,) m, the surface height eta above each point.
        z: (N,) m, the points' heights (below ``heights``).
        t: simulation time, s.
    """
    z = np.asarray(z, dtype=float)
    if not wf.components:
        return -z
    from ocean_sim.physics.linear_kernel import pressure_head_f64  # numba: loaded when used

    ar = wf.arrays
    return pressure_head_f64(_points2(rest_xy), z, np.asarray(heights, dtype=float), ar.kd,
                             time_phase(wf, t), ar.a, ar.k, float(wf.depth), _deep(wf))


def _points2(xy: np.ndarray) -> np.ndarray:
    """(N, 2) float64, C-contiguous: a kernel's points."""
    return np.ascontiguousarray(np.asarray(xy, dtype=float).reshape(-1, 2))


def _pressure_head_numpy(wf: WaveField, rest_xy: np.ndarray, heights: np.ndarray,
                         z: np.ndarray, t: float) -> np.ndarray:
    """:func:`pressure_head` in numpy: the compiled kernel's oracle (a sea with components)."""
    z = np.asarray(z, dtype=float)
    ar = wf.arrays
    eta = np.asarray(heights, dtype=float)
    cos_theta = np.cos(component_phases(wf, rest_xy, t))
    if _deep(wf):
        decay = np.exp(np.multiply.outer(np.minimum(z - eta, 0.0), ar.k))
    else:
        h = wf.depth
        zs = np.clip(h * (z - eta) / (h + eta), -h, 0.0)
        # cosh(k (zs + h)) / cosh(k h) = e^{k zs} (1 + e^{-2 k (zs + h)}) / (1 + e^{-2 k h}),
        # which does not overflow for deep finite water (k h > 710)
        k_zs = np.multiply.outer(zs, ar.k)
        decay = (np.exp(k_zs) * (1.0 + np.exp(-2.0 * (k_zs + ar.k * h)))
                 / (1.0 + np.exp(-2.0 * ar.k * h)))
    return (cos_theta * decay) @ ar.a - z


def _deep(wf: WaveField) -> bool:
    """Whether every component sees deep water: depth inf, or k h > 350 (e^{-2 k h} < 1e-304).

    The finite-depth decays would then differ from deep water's by less than a float's
    rounding, and their products h (z - eta) and k h overflow for a depth near 1e308 m.
    """
    return math.isinf(wf.depth) or float(wf.arrays.k.min()) > 350.0 / wf.depth


def _stretched_decay(wf: WaveField, eta: np.ndarray, z: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """(N, M) horizontal and vertical depth decays of linear orbital velocity, Wheeler-stretched.

    Deep water: e^{k z_s} both. Depth h: cosh(k (z_s + h)) / sinh(k h) and
    sinh(k (z_s + h)) / sinh(k h) (Dean & Dalrymple 1991, eqs. 4.16-4.17), written with
    exponentials that do not overflow for k h > 710.
    """
    ar = wf.arrays
    if _deep(wf):
        decay = np.exp(np.multiply.outer(np.minimum(z - eta, 0.0), ar.k))
        return decay, decay
    h = wf.depth
    k_zs = np.multiply.outer(np.clip(h * (z - eta) / (h + eta), -h, 0.0), ar.k)
    grow, fall = np.exp(k_zs), np.exp(-2.0 * (k_zs + ar.k * h))
    norm = 1.0 - np.exp(-2.0 * ar.k * h)
    return grow * (1.0 + fall) / norm, grow * (1.0 - fall) / norm


def orbital_velocity(wf: WaveField, xy: np.ndarray, heights: np.ndarray, z: np.ndarray,
                     t: float) -> np.ndarray:
    """(N, 3) m/s, world velocity of the water at points below the surface, linear theory.

    Each component's Airy particle velocity (Dean & Dalrymple 1991, eqs. 4.16-4.17; Newman,
    "Marine Hydrodynamics", sec. 6.3): a omega cos(theta) E_h(z_s) along its direction and
    a omega sin(theta) E_v(z_s) upward, with theta = k D . p - omega t + phi at the point's
    own horizontal position (linear theory does not tell a particle's rest position from
    where it is) and Wheeler stretching as in :func:`pressure_head`, so that at the surface
    the vertical velocity is the Gerstner surface's own. Zero in still water.

    Args:
        wf: the sea state (already filtered to the components acting on the body).
        xy: (N, 2) m, the points' horizontal positions.
        heights: (N,) m, the surface height eta above each point.
        z: (N,) m, the points' heights.
        t: simulation time, s.
    """
    z = np.asarray(z, dtype=float)
    if not wf.components:
        return np.zeros((z.shape[0], 3))
    from ocean_sim.physics.linear_kernel import orbital_velocity_f64  # numba: when used

    ar = wf.arrays
    return orbital_velocity_f64(_points2(xy), z, np.asarray(heights, dtype=float), ar.kd,
                                time_phase(wf, t), ar.a * ar.omega, ar.k, ar.dx, ar.dy,
                                float(wf.depth), _deep(wf))


def _orbital_velocity_numpy(wf: WaveField, xy: np.ndarray, heights: np.ndarray, z: np.ndarray,
                            t: float) -> np.ndarray:
    """:func:`orbital_velocity` in numpy: the compiled kernel's oracle (a sea with components)."""
    z = np.asarray(z, dtype=float)
    out = np.zeros((z.shape[0], 3))
    ar = wf.arrays
    theta = component_phases(wf, xy, t)
    horizontal, vertical = _stretched_decay(wf, np.asarray(heights, dtype=float), z)
    speed = horizontal * np.cos(theta) @ np.diag(ar.a * ar.omega)
    out[:, 0], out[:, 1] = speed @ ar.dx, speed @ ar.dy
    out[:, 2] = (vertical * np.sin(theta)) @ (ar.a * ar.omega)
    return out


def stokes_drift(wf: WaveField, depth_below_surface: float = 0.0) -> np.ndarray:
    """Stokes drift velocity (2,) m/s at a depth below the mean surface.

    Gerstner particles move on closed orbits (no net drift); real waves carry floating
    objects along with the mean Lagrangian velocity of linear theory,
    u_s = sum_i omega_i k_i a_i^2 D_i cosh(2 k_i (h - z)) / (2 sinh^2(k_i h)),
    which is omega k a^2 exp(-2 k z) in deep water (z = depth below the surface, m).
    Source: Dean & Dalrymple (1991), eq. 7.95; the seed notes, "Stokes drift".
    """
    ar = wf.arrays
    if not wf.components:
        return np.zeros(2)
    z = max(depth_below_surface, 0.0)
    if math.isinf(wf.depth):
        factor = np.exp(-2.0 * ar.k * z)
    else:
        kh = ar.k * wf.depth
        factor = np.cosh(2.0 * ar.k * (wf.depth - min(z, wf.depth))) / (2.0 * np.sinh(kh) ** 2)
    mag = ar.omega * ar.k * ar.a**2 * factor
    return np.array([mag @ ar.dx, mag @ ar.dy])
