"""The waves a boat radiates and scatters in a sea, far from it, from its Kochin functions.

Linear potential flow at zero forward speed (Newman 1977, "Marine Hydrodynamics", sec. 6.17
and 6.19): a hull in an incident component of amplitude a, frequency omega and direction
beta scatters the wave it is held in and radiates the waves of its own motion xi (its linear
RAO, (-omega^2 (M + A) - i omega B + C) xi = X, from its coefficient file). Far from it
(k r >> 1) both are a cylindrical wave whose pattern is the sum of the Kochin functions
(Capytaine's ``compute_kochin``, tests/data/wavemaking/README.md), per metre of incident
amplitude and in the hull's frame,

    H(theta) = H_D(theta; beta - psi) + sum_j xi_j H_j(theta),

and whose elevation, in the e^{-i omega t} convention of the file, is the large-r form of
the free-surface Green function (Newman 1977, sec. 6.17, eq. 6.17.5 in deep water; John
1950 for finite depth):

    eta(r, theta) = a e^{i theta_0} (omega / g) sqrt(8 pi / (k r)) kappa H(theta - psi)
                    e^{i (k r - pi / 4)},   kappa = k / (k h sech^2(k h) + tanh(k h)),

kappa = k in deep water, theta_0 the incident component's phase k D . p - omega t + phi at the
hull reference point p (boatsim's eta = a cos(theta) is Re[a e^{i theta}], the same
complex amplitude as the file's), r and theta the distance and world angle from p, psi the
boat's heading. Energy (Newman 1977, sec. 6.19) ties H_j to the file's damping:
B_jj = 4 pi rho k / omega integral |H_j|^2 d theta (deep water).

That is the leading term of the exact wave part outside the hull's circle,
(2 pi k omega / g) sum_n i^n h_n H_n^(1)(k r) e^{i n theta} for H = sum_n h_n e^{i n theta}
(tests/data/wavemaking/README.md). The next term of each Hankel function's expansion,
1 + i (4 n^2 - 1) / (8 k r) (Abramowitz & Stegun 9.2.7), is kept: H is replaced by
H + i (4 C - H) / (8 k r), C = sum n^2 h_n e^{i n theta} = -H'' over the harmonics
|n| <= 8 (:func:`curvature`; higher ones are noise the near field would amplify), k r held
at 2 or more. It is what lags a pattern that varies fast with theta (yaw's sin 2 theta:
17 deg at k r = 6.4) and brings the far field within a few percent of Capytaine's from 20 m.

Near a receiving boat the cylindrical wave is replaced by the plane wave of its local
amplitude, phase and direction: the wide-spacing approximation of multiple-body interaction
(Simon 1982, J. Fluid Mech. 120, 1-25; McIver & Evans 1984, Appl. Ocean Res. 6(2), 101-107),
first order (the receiver's own answer to the made wave does not come back):
:class:`.made_waves.LocalWaves`, whose force :func:`.made_waves.local_wrench` gives.

Close to the source the far field is wrong: the near field (evanescent modes, decaying as
r^{-3/2} and faster) is left out, and the far-field amplitude grows as r^{-1/2} toward the
hull. The waves are therefore zero within the hull's waterline radius R (:func:`hull_radius`)
and tapered smoothly (3 s^2 - 2 s^3, s = (r - R) / R) to the full far field at 2 R. Measured
against Capytaine's full solution for the default 4 x 2 x 1 m box (test_scattered_waves.py;
error over the largest elevation on three rays from 20 m out, waves of 1.45-5.8 s): radiated
waves surge to pitch within 3.6 %, yaw 8.0 %, scattered 3.9 %, the free box in waves 9.1 %
(5.7 % up to 4.5 s); a heaving cylinder 3.5 %. The 7.9 s wave (k r = 1.3 at 20 m): 10-13 %.
Components outside the file's frequency range make no waves; a hull without Kochin
functions in its file makes none; zero forward speed.

Cost (CPU, one thread, numpy): per source and step, the RAO and pattern of each component
(N 6 x 6 solves), then N complex products per point: 0.48 ms for a 16-component sea and
2.7 ms for 945 components, one receiver (plus 0.015 and 0.15 ms for
:func:`.made_waves.local_wrench`); :func:`outgoing_elevation` at 4,096 points 9 ms and 0.3 s.
"""

from __future__ import annotations

import math

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import (
    KOCHIN_HARMONICS,
    HydroCoefficients,
    harmonic_curvature,
)
from boat_dynamics.physics.wave_making.made_waves import LocalWaves
from ocean_sim.physics.waves import WaveField

#: Points per block of :func:`outgoing_elevation`.
_BLOCK = 128
#: The Kochin functions' harmonics the 1 / (k r) term of the far field keeps.
HARMONICS = KOCHIN_HARMONICS
#: The k r below which that term is held at its value there (it is an asymptotic series).
MIN_KR = 2.0

__all__ = ["HARMONICS", "MIN_KR", "curvature", "far_field", "far_field_factor", "hull_radius",
           "motion_rao", "no_waves_note", "outgoing_elevation", "outgoing_waves", "pattern"]


def no_waves_note(hydro: HydroCoefficients) -> str | None:
    """The line to log for a boat whose file has no Kochin functions (it makes no waves).

    None when it has them.
    """
    if hydro.has_kochin:
        return None
    return (f"{hydro.source}: no Kochin functions (a coefficient file made before issue 31): "
            "this boat makes no radiated or scattered waves for the others; `boatsim hydro "
            "SCENARIO --force` makes its file again with them")


def hull_radius(hydro: HydroCoefficients) -> float:
    """m, the half-diagonal of the hull's waterplane, from its hydrostatic stiffness.

    A rectangular waterplane L x B has A_w = L B, I_xx = L B^3 / 12, I_yy = L^3 B / 12, so
    (L^2 + B^2) / 4 = 3 (C44 + C55) / C33 when the metacentric terms (rho g V z_B - m g z_G,
    a few percent for a boat) are neglected: 2.2 m for the default 4 x 2 m box.
    """
    c = hydro.hydrostatic_stiffness
    if c[2, 2] <= 0.0:
        return 0.0
    return float(math.sqrt(max(3.0 * (c[3, 3] + c[4, 4]) / c[2, 2], 0.0)))


def far_field_factor(omega: np.ndarray, k: np.ndarray, r: np.ndarray, gravity: float,
                     depth: float) -> np.ndarray:
    """Complex eta / H of the far field: (omega / g) sqrt(8 pi / (k r)) kappa e^{i (k r - pi/4)}.

    Args:
        omega: (N, 1) rad/s.
        k: (N, 1) rad/m.
        r: (P,) m, > 0.
        gravity: m/s^2.
        depth: m (``inf``: deep water, kappa = k).

    Returns:
        (N, P) complex, 1/(m^2/s) x m: elevation per unit Kochin function.
    """
    if math.isinf(depth):
        kappa = k
    else:
        kh = k * depth
        kappa = k / (kh / np.cosh(np.minimum(kh, 350.0)) ** 2 + np.tanh(kh))
    return (omega / gravity) * np.sqrt(8.0 * np.pi / (k * r)) * kappa * np.exp(
        1j * (k * r - 0.25 * np.pi))


def _omega_weights(grid: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(index i, weight u) of linear interpolation in ``grid`` (clamped) at ``omega``."""
    w = np.clip(omega, grid[0], grid[-1])
    i = np.clip(np.searchsorted(grid, w) - 1, 0, grid.shape[0] - 2)
    return i, (w - grid[i]) / (grid[i + 1] - grid[i])


def motion_rao(hydro: HydroCoefficients, omega: np.ndarray, direction: np.ndarray,
               viscous: np.ndarray | None = None) -> np.ndarray:
    """(N, 6) complex motions per metre of amplitude of the free hull at zero speed.

    (-omega^2 (M + A) - i omega (B + B_v) + C) xi = X_FK + X_D, all from the file
    (:attr:`HydroCoefficients.inertia_matrix`, its hydrostatic stiffness), linear in omega,
    bilinear in direction (:meth:`HydroCoefficients.excitation_at`); phase relative to the
    incident crest at the hull reference point (Re[xi e^{-i omega t}]).

    Args:
        hydro: the hull's coefficients.
        omega: (N,) rad/s.
        direction: (N,) rad, each wave's direction of travel relative to the bow.
        viscous: (6,) linear damping added to B's diagonal, or None.
    """
    omega = np.asarray(omega, dtype=float)
    i, u = _omega_weights(hydro.omega, omega)
    u3 = u[:, None, None]
    added = (1 - u3) * hydro.added_mass[i] + u3 * hydro.added_mass[i + 1]
    damping = (1 - u3) * hydro.radiation_damping[i] + u3 * hydro.radiation_damping[i + 1]
    if viscous is not None:
        damping = damping + np.diag(np.asarray(viscous, dtype=float))
    w2 = omega[:, None, None]
    impedance = (-w2**2 * (hydro.inertia_matrix + added) - 1j * w2 * damping
                 + hydro.hydrostatic_stiffness)
    excitation = hydro.excitation_at(omega, np.asarray(direction, dtype=float))
    return np.linalg.solve(impedance, (excitation[:, :6] + excitation[:, 6:])[..., None])[..., 0]


def pattern(hydro: HydroCoefficients, omega: np.ndarray, direction: np.ndarray,
            motion: np.ndarray, angles: np.ndarray,
            tables: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """(N, P) complex Kochin function H_D + sum_j xi_j H_j at P angles, body frame.

    Linear in the angle (periodic) and in omega (clamped), and in the incident direction
    between the file's directions; a file whose directions span only 0..pi (a hull symmetric
    about its centreplane) gives H_D(theta; -beta) = H_D(-theta; beta). The tables are
    interpolated at the P angles first, so the cost is N x 6 x P, not N x 6 x T.

    Args:
        hydro: coefficients with Kochin functions.
        omega: (N,) rad/s.
        direction: (N,) rad, each incident wave's direction relative to the bow.
        motion: (N, 6) complex, per metre of amplitude (:func:`motion_rao`).
        angles: (P,) rad, body frame, the directions the outgoing waves travel toward.
        tables: (W, 6, T) radiation and (W, D, T) diffraction tables in place of the
            file's Kochin functions (:func:`curvature`'s), or None.

    Returns:
        m^2/s per metre of incident amplitude.
    """
    radiation, diffraction = ((hydro.kochin_radiation, hydro.kochin_diffraction)
                              if tables is None else tables)
    angles = np.asarray(angles, dtype=float)
    i, u = _omega_weights(hydro.omega, np.asarray(omega, dtype=float))
    u2 = u[:, None]
    beta = np.mod(np.asarray(direction, dtype=float), 2 * np.pi)
    grid = hydro.directions
    mirrored = np.zeros(beta.shape, bool)
    if grid[-1] <= np.pi + 1e-9:
        mirrored = beta > np.pi
        beta = np.where(mirrored, 2 * np.pi - beta, beta)
    beta = np.clip(beta, grid[0], grid[-1])
    j = np.clip(np.searchsorted(grid, beta) - 1, 0, grid.shape[0] - 2)
    v = ((beta - grid[j]) / (grid[j + 1] - grid[j]))[:, None]
    kd = _at_angles(hydro.kochin_angles, diffraction, angles)  # (W, D, P)
    scattered = ((1 - u2) * (1 - v) * kd[i, j] + u2 * (1 - v) * kd[i + 1, j]
                 + (1 - u2) * v * kd[i, j + 1] + u2 * v * kd[i + 1, j + 1])
    if np.any(mirrored):
        kd = _at_angles(hydro.kochin_angles, diffraction, -angles)
        flipped = ((1 - u2) * (1 - v) * kd[i, j] + u2 * (1 - v) * kd[i + 1, j]
                   + (1 - u2) * v * kd[i, j + 1] + u2 * v * kd[i + 1, j + 1])
        scattered = np.where(mirrored[:, None], flipped, scattered)
    kr = _at_angles(hydro.kochin_angles, radiation, angles)  # (W, 6, P)
    radiated = (1 - u2[..., None]) * kr[i] + u2[..., None] * kr[i + 1]  # (N, 6, P)
    return scattered + np.einsum("nj,njp->np", motion, radiated)


def curvature(hydro: HydroCoefficients) -> tuple[np.ndarray, np.ndarray] | None:
    """-d^2 H / d theta^2 of the file's Kochin functions, harmonics |n| <= :data:`HARMONICS`.

    :attr:`HydroCoefficients.kochin_curvature` (computed by the coefficients once).

    Returns:
        (W, 6, T) radiation and (W, D, T) diffraction tables, as the file's, or None.
    """
    return hydro.kochin_curvature


def _next_term(h: np.ndarray, bend: np.ndarray, kr: np.ndarray) -> np.ndarray:
    """H + i (4 C - H) / (8 k r): the 1 / (k r) term of each harmonic's H_n^(1)(k r).

    H_n^(1)(x) ~ sqrt(2 / (pi x)) e^{i (x - n pi / 2 - pi / 4)} (1 + i (4 n^2 - 1) / (8 x));
    C = sum n^2 h_n e^{i n theta} (:func:`curvature`). k r below :data:`MIN_KR` counts as it.
    """
    return h + 1j * (4.0 * bend - h) / (8.0 * np.maximum(kr, MIN_KR))


def far_field(hydro: HydroCoefficients, table: np.ndarray, omega: float, k: float,
              xy: np.ndarray, gravity: float, depth: float) -> np.ndarray:
    """(M, P) complex elevations of M Kochin functions of the file's angles, about x = y = 0.

    The far field of :func:`outgoing_elevation` for bare Kochin functions (one problem
    each: a dof's radiation per unit motion, a heading's scattering per metre), body frame,
    e^{-i omega t}; no taper.

    Args:
        hydro: for its ``kochin_angles``.
        table: (M, T) complex, m^2/s, on ``hydro.kochin_angles`` (uniform).
        omega: rad/s.
        k: rad/m.
        xy: (P, 2) m, body frame.
        gravity: m/s^2.
        depth: m (``inf``: deep water).
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    r = np.hypot(xy[:, 0], xy[:, 1])
    alpha = np.arctan2(xy[:, 1], xy[:, 0])
    theta = hydro.kochin_angles
    bend = _at_angles(theta, harmonic_curvature(table), alpha)
    h = _next_term(_at_angles(theta, table, alpha), bend, k * r)
    return h * far_field_factor(np.array([[omega]]), np.array([[k]]), r, gravity, depth)


def _at_angles(theta: np.ndarray, table: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(..., P) of a periodic (..., T) ``table`` on ``theta`` at (P,) ``angles``, linear."""
    t = theta.shape[0]
    ext = np.append(theta, theta[0] + 2 * np.pi)
    a = np.mod(angles - theta[0], 2 * np.pi) + theta[0]
    m = np.clip(np.searchsorted(ext, a, side="right") - 1, 0, t - 1)
    s = (a - ext[m]) / (ext[m + 1] - ext[m])
    return (1 - s) * table[..., m] + s * table[..., (m + 1) % t]


def _sources(hydro: HydroCoefficients, sea: WaveField, source_xy: np.ndarray,
             source_heading: float, t: float, viscous) -> dict | None:
    """Per incident component the source makes waves in: what the points do not change.

    Returns:
        None when it makes none; else ``keep`` (M,) the components it answers, and for
        those N: ``omega``, ``k``, ``beta`` (relative to the bow), ``motion`` (N, 6),
        ``incident`` (N,) complex a e^{i theta_0} at the source at ``t``, the file's
        ``curvature`` tables, and ``pattern``, ``bend`` (N, T) on the file's angles
        (filled on demand).
    """
    arrays = sea.arrays
    keep = (arrays.a > 0.0) & (arrays.omega >= hydro.omega[0]) & (arrays.omega <= hydro.omega[-1])
    if not hydro.has_kochin or not np.any(keep):
        return None
    w, k = arrays.omega[keep], arrays.k[keep]
    beta = np.arctan2(arrays.dy[keep], arrays.dx[keep]) - source_heading
    theta0 = np.asarray(source_xy, dtype=float).reshape(2) @ arrays.kd[:, keep] - w * t
    return dict(keep=keep, omega=w, k=k, beta=beta, motion=motion_rao(hydro, w, beta, viscous),
                incident=arrays.a[keep] * np.exp(1j * (theta0 + arrays.phi[keep])),
                curvature=curvature(hydro))


def _field(hydro: HydroCoefficients, sea: WaveField, src: dict, source_xy: np.ndarray,
           source_heading: float, xy: np.ndarray, radius) -> tuple[np.ndarray, np.ndarray]:
    """(N, P) complex made-wave amplitudes at P points ``xy`` (P, 2), and (P,) world angles."""
    d = xy - np.asarray(source_xy, dtype=float).reshape(2)
    r = np.hypot(d[:, 0], d[:, 1])
    alpha = np.arctan2(d[:, 1], d[:, 0])
    w, k = src["omega"], src["k"]
    args = (hydro, w, src["beta"], src["motion"])
    bent = src["curvature"]
    if alpha.shape[0] <= hydro.kochin_angles.shape[0]:  # few points: at their angles
        h_at = pattern(*args, alpha - source_heading)
        c_at = None if bent is None else pattern(*args, alpha - source_heading, bent)
    else:  # many: on the file's angles once, then per component at the points'
        if "pattern" not in src:
            src["pattern"] = pattern(*args, hydro.kochin_angles)
            src["bend"] = None if bent is None else pattern(*args, hydro.kochin_angles, bent)
        h_at = _at_angles(hydro.kochin_angles, src["pattern"], alpha - source_heading)
        c_at = (None if bent is None
                else _at_angles(hydro.kochin_angles, src["bend"], alpha - source_heading))
    if c_at is not None:
        h_at = _next_term(h_at, c_at, k[:, None] * r)
    near = hull_radius(hydro) if radius is None else float(radius)
    s = np.clip((r - near) / max(near, 1e-9), 0.0, 1.0)
    taper = s * s * (3.0 - 2.0 * s)
    field = far_field_factor(w[:, None], k[:, None], np.maximum(r, 1e-9), sea.gravity, sea.depth)
    return src["incident"][:, None] * h_at * field * taper, alpha


def outgoing_waves(hydro: HydroCoefficients, sea: WaveField, source_xy: np.ndarray,
                   source_heading: float, receivers_xy: np.ndarray, t: float, *,
                   viscous: np.ndarray | None = None, radius: float | None = None
                   ) -> list[LocalWaves]:
    """The waves one boat makes in ``sea``, as plane waves at each receiving point.

    One plane wave per incident component (module docstring): travelling from the source
    toward the receiver, of the cylindrical wave's amplitude and phase there.

    Args:
        hydro: the source boat's coefficients (no Kochin functions: no waves).
        sea: the incident sea (zero forward speed: the source's speed is not used).
        source_xy: (2,) m, world position of the source's hull reference point.
        source_heading: rad, its yaw.
        receivers_xy: (R, 2) m, world points (the receiving boats' reference points).
        t: s.
        viscous: (6,) the source's linear damping added to B in its RAO, or None.
        radius: m, the near-field radius R (None: :func:`hull_radius`).

    Returns:
        R :class:`LocalWaves`, each at its receiver and ``t`` (none for a receiver within R).
    """
    xy = np.asarray(receivers_xy, dtype=float).reshape(-1, 2)
    src = _sources(hydro, sea, source_xy, source_heading, t, viscous)
    if src is None or xy.shape[0] == 0:
        return [LocalWaves.none(at, t) for at in xy]
    amp, alpha = _field(hydro, sea, src, source_xy, source_heading, xy, radius)
    out = []
    for n in range(xy.shape[0]):
        a = np.abs(amp[:, n])
        on = a > 0.0
        count = int(np.count_nonzero(on))
        out.append(LocalWaves(xy[n].copy(), float(t), a[on], src["omega"][on], src["k"][on],
                              np.full(count, alpha[n]), np.angle(amp[on, n]))
                   if count else LocalWaves.none(xy[n], t))
    return out


def outgoing_elevation(hydro: HydroCoefficients, sea: WaveField, source_xy: np.ndarray,
                       source_heading: float, xy: np.ndarray, t: float, *,
                       viscous: np.ndarray | None = None, radius: float | None = None
                       ) -> np.ndarray:
    """(P,) m, the elevation of the waves one boat makes, at P world points ``xy`` (P, 2).

    The cylindrical waves themselves (not their plane-wave stand-ins); arguments as
    :func:`outgoing_waves`. Cost: N components x P points complex products.
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    out = np.zeros(xy.shape[0])
    src = _sources(hydro, sea, source_xy, source_heading, t, viscous)
    if src is None:
        return out
    for start in range(0, xy.shape[0], _BLOCK):  # N x _BLOCK at a time: in cache
        block = xy[start:start + _BLOCK]
        amp, _ = _field(hydro, sea, src, source_xy, source_heading, block, radius)
        out[start:start + block.shape[0]] = amp.real.sum(axis=0)
    return out
