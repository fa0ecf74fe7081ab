"""An FFT ocean: Tessendorf's periodic tile, and the same sea as Gerstner components.

Pure numpy; never imports rclpy. Source: J. Tessendorf, "Simulating Ocean Water" (SIGGRAPH
course notes, 2001); equation numbers below are his.

A tile of side ``L`` (m) and ``N x N`` points holds one wave per lattice wavevector
k = 2 pi (n, m) / L, n, m in [-N/2, N/2) (eq. 36). Its complex amplitude is drawn from the
seed as h0(k) = (xi_r + i xi_i) sqrt(P(k) / 2) (eq. 42; xi standard normal, so
<|h0|^2> = P(k)), where P(k) is the variance of the wave at k: the directional wavenumber
spectrum F(k) (m^4) times the lattice cell (2 pi / L)^2 over 2 (below: each lattice point
carries one travelling wave of amplitude 2 |h0|, variance 2 |h0|^2). The wave at k = 0 and
the Nyquist row and column (n or m = -N/2, whose -k is themselves on the lattice, so their
horizontal displacement would not be real) are left out. The height field is eq. 26 with the
sign of time reversed, so that h0(k) travels toward +k (the direction convention of
:mod:`ocean_sim.physics.waves`)::

    h~(k, t) = h0(k) exp(-i w t) + conj(h0(-k)) exp(+i w t),  w^2 = g k tanh(k h)  (eq. 14)
    h(x, t)  = sum_k h~(k, t) exp(i k.x)                                           (eq. 19)
             = sum_k a_k cos(k.x - w_k t + phi_k),   a_k = 2 |h0(k)|, phi_k = arg h0(k)

Choppy waves (eq. 29-30): D(x, t) = sum_k -i (k / |k|) h~(k, t) exp(i k.x)
= sum_k a_k k^ sin(theta_k), and the surface point at rest position x moves to x + lambda D.
Tessendorf's lambda must be negative for sharp crests (with lambda > 0 the troughs sharpen);
with Q = -lambda >= 0 the displaced point is::

    x0 - Q sum_k a_k k^ sin(theta_k),  z = sum_k a_k cos(theta_k)

which is exactly the Gerstner sum of :mod:`ocean_sim.physics.waves` with every component's
steepness Q_k = Q. So a tile *is* a :class:`~ocean_sim.physics.waves.WaveField` of up to
(N-1)^2 components (:func:`tile_sea`): its heights, normals and particle kinematics at any
world point come from the existing query (rest position inverted, exact), and
:func:`build_tile` computes the same surface on the tile's grid of rest positions by inverse
FFTs, O(N^2 log N) instead of the direct sum's O(N^4). Crests stay free of loops (and the
inversion converges) while Q sum_k k a_k <= 1; as the sum grows with N (the spectrum's tail),
the tile's ``choppiness`` is that budget: Q = min(1, choppiness / sum_k k a_k)
(:func:`tile_steepness`), so choppiness 1 is the sharpest sea without loops (Tessendorf's
lambda = -Q; Q = 1 is the trochoid).

Spectra, as F(k) with variance = integral of F over the wavevector plane:

- ``phillips`` (eq. 40): F = A exp(-1 / (k L_w)^2) / k^4 |k^ . w^|^2, L_w = U^2 / g, whose
  integral is pi A L_w^2 / 2; the default A = 2 (0.21)^2 / (16 pi) gives the fully developed
  sea of Pierson & Moskowitz (1964), H_s = 0.21 U^2 / g, peak near k = 0.82 g / U^2
  (Pierson-Moskowitz: 0.77). Waves run both with and against the wind (the |k^ . w^|^2
  factor, as eq. 40 is written).
- ``jonswap``: F = S(w(k)) (dw/dk) D(theta) / k with S the JONSWAP frequency spectrum of
  :func:`ocean_sim.physics.spectra.jonswap` and D the normalized cos-2s spreading
  D = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2)) cos^(2s)((theta - theta_0) / 2)
  (DNV-RP-C205, 2010, sec. 3.5.8.4).

The tile keeps the spectrum's variance only between its longest wave (L) and its shortest
(2 L / N): choose L several peak wavelengths long. Tessendorf's small-wave suppression
(eq. 24) multiplies either spectrum by exp(-k^2 l^2) (``suppression_length`` l).

The sea of a tile carries it (``WaveField.tile``), so the view and /ocean/surface draw its
surface by :func:`grid_surface`: the particles of rest points on an M x M grid of the tile,
any M (:func:`grid_points`), summed by inverse FFTs from the components and tiled
periodically, exact at the nodes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from ocean_sim.physics.constants import GRAVITY, TWO_PI
from ocean_sim.physics.spectra import jonswap
from ocean_sim.physics.waves import (
    MAX_COMPONENTS,
    InvalidSeaStateError,
    TileGrid,
    WaveComponent,
    WaveField,
    angular_frequency,
    time_phase,
)

__all__ = [
    "FFT_SPECTRA",
    "MAX_GRID_POINTS",
    "MAX_RESOLUTION",
    "OCEAN_MODELS",
    "PIERSON_MOSKOWITZ_PHILLIPS",
    "FftSpectrum",
    "OceanModel",
    "Tile",
    "TileSpec",
    "build_tile",
    "grid_points",
    "grid_surface",
    "lattice",
    "spectral_density",
    "tile_amplitudes",
    "tile_sea",
    "tile_steepness",
]

#: The sea models a scenario chooses between (``ocean.model``): the Gerstner sum of explicit
#: and spectrum components, or this module's tile.
OceanModel = Literal["gerstner", "fft"]
OCEAN_MODELS: tuple[OceanModel, ...] = get_args(OceanModel)

#: Spectra of a tile.
FftSpectrum = Literal["phillips", "jonswap"]
FFT_SPECTRA: tuple[FftSpectrum, ...] = get_args(FftSpectrum)

#: Phillips' constant A of a fully developed sea: pi A (U^2/g)^2 / 2 = (0.21 U^2 / g)^2 / 16.
PIERSON_MOSKOWITZ_PHILLIPS = 2.0 * 0.21**2 / (16.0 * math.pi)

#: Largest (even) N of an N x N tile: its (N - 1)^2 components within waves.MAX_COMPONENTS
#: (64: 3969 of 4096).
MAX_RESOLUTION = (math.isqrt(MAX_COMPONENTS) + 1) // 2 * 2


@dataclass(frozen=True)
class TileSpec:
    """A periodic tile of Tessendorf's ocean (the scenario's ``ocean.fft`` block).

    Attributes:
        size: L, m, the tile's side (it repeats every L in x and y).
        resolution: N, even, 4..MAX_RESOLUTION: N x N grid points, (N - 1)^2 waves.
        seed: seed of the amplitudes h0 (same seed, same sea).
        spectrum: ``phillips`` or ``jonswap``.
        wind_speed: U, m/s (phillips).
        phillips_constant: A, dimensionless (phillips).
        significant_height: H_s, m (jonswap).
        peak_period: T_p, s (jonswap).
        gamma: JONSWAP peak enhancement, 1..7.
        spreading: s of the cos-2s spreading (jonswap).
        direction: the wind's / mean waves' direction toward, rad, counter-clockwise from +x.
        choppiness: 0..1, the budget Q sum_k k a_k of the steepness Q = -lambda that every
            component gets (:func:`tile_steepness`); 1 = crests at the verge of looping.
        suppression_length: l, m, 0..size: Tessendorf's small-wave suppression (eq. 24), the
            spectrum times exp(-k^2 l^2): waves shorter than l keep less than exp(-4 pi^2)
            = 7e-18 of their variance, waves of 10 l keep 67 %; 0 = none.
        gravity: g, m/s^2.
        depth: h, m (inf = deep water).
    """

    size: float = 200.0
    resolution: int = 32
    seed: int = 0
    spectrum: FftSpectrum = "phillips"
    wind_speed: float = 8.0
    phillips_constant: float = PIERSON_MOSKOWITZ_PHILLIPS
    significant_height: float = 1.0
    peak_period: float = 6.0
    gamma: float = 3.3
    spreading: float = 10.0
    direction: float = 0.0
    choppiness: float = 0.5
    suppression_length: float = 0.0
    gravity: float = GRAVITY
    depth: float = math.inf

    def __post_init__(self) -> None:
        _check(self)


def _check(spec: TileSpec) -> None:
    """Refuse a tile's bad values (key ``fft.<name>``)."""
    n = spec.resolution
    if isinstance(n, bool) or not isinstance(n, int) or n % 2 or not 4 <= n <= MAX_RESOLUTION:
        raise InvalidSeaStateError("fft.resolution", n,
                                   f"must be an even integer in [4, {MAX_RESOLUTION}]")
    if spec.spectrum not in FFT_SPECTRA:
        raise InvalidSeaStateError("fft.spectrum", spec.spectrum,
                                   f"must be one of: {', '.join(FFT_SPECTRA)}")
    if isinstance(spec.seed, bool) or not isinstance(spec.seed, int) or spec.seed < 0:
        raise InvalidSeaStateError("fft.seed", spec.seed, "must be an integer >= 0")
    for name, lo, hi in (("size", 1e-3, 1e6), ("wind_speed", 0.0, 100.0),
                         ("phillips_constant", 0.0, 1.0), ("significant_height", 0.0, 30.0),
                         ("peak_period", 0.5, 40.0), ("gamma", 1.0, 7.0),
                         ("spreading", 0.0, 1000.0), ("direction", -1e3, 1e3),
                         ("choppiness", 0.0, 1.0), ("gravity", 1e-9, 1e3)):
        v = getattr(spec, name)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
            raise InvalidSeaStateError(f"fft.{name}", v, f"must be a number in [{lo:g}, {hi:g}]")
    if math.isnan(spec.depth) or spec.depth <= 0.0:
        raise InvalidSeaStateError("fft.depth", spec.depth, "must be > 0 (m), or inf")
    length = spec.suppression_length
    if isinstance(length, bool) or not isinstance(length, (int, float)) or not (
            0.0 <= length <= spec.size):
        raise InvalidSeaStateError("fft.suppression_length", length,
                                   f"must be a number in [0, {spec.size:g}] m (the tile's size)")


def lattice(spec: TileSpec) -> tuple[np.ndarray, np.ndarray]:
    """The tile's wavevectors (eq. 36), each (N, N) rad/m in numpy's FFT order.

    ``kx[i, j]`` and ``ky[i, j]`` belong to grid axis 0 = x and axis 1 = y.
    """
    k1 = TWO_PI * np.fft.fftfreq(spec.resolution, d=spec.size / spec.resolution)
    return np.meshgrid(k1, k1, indexing="ij")


def _group_velocity(k: np.ndarray, omega: np.ndarray, gravity: float, depth: float
                    ) -> np.ndarray:
    """dw/dk of w^2 = g k tanh(k h): g (tanh(kh) + kh sech^2(kh)) / (2 w)."""
    if math.isinf(depth):
        return gravity / (2.0 * omega)
    t = np.tanh(k * depth)
    return gravity * (t + k * depth * (1.0 - t * t)) / (2.0 * omega)


def _cos2s(spec: TileSpec, heading: np.ndarray) -> np.ndarray:
    """Normalized cos-2s spreading D(theta), 1/rad (its integral over a turn is 1)."""
    s = spec.spreading
    norm = math.exp(math.lgamma(s + 1.0) - math.lgamma(s + 0.5)) / (2.0 * math.sqrt(math.pi))
    off = np.angle(np.exp(1j * (heading - spec.direction)))  # in [-pi, pi]
    return norm * np.cos(0.5 * off) ** (2.0 * s)


def spectral_density(spec: TileSpec, kx: np.ndarray, ky: np.ndarray) -> np.ndarray:
    """Directional wavenumber spectrum F(k), m^4 (variance per unit wavevector area).

    Args:
        spec: the tile (its spectrum and parameters; see the module docstring).
        kx: wavevector x components, rad/m, any shape.
        ky: wavevector y components, rad/m, same shape (k = 0 gives F = 0).

    Returns:
        F, same shape; 0 at k = 0.
    """
    k = np.hypot(kx, ky)
    out = np.zeros_like(k)
    ok = k > 0.0
    kk, hx, hy = k[ok], kx[ok] / k[ok], ky[ok] / k[ok]
    if spec.spectrum == "phillips":
        if spec.wind_speed > 0.0:
            lw = spec.wind_speed**2 / spec.gravity
            along = hx * math.cos(spec.direction) + hy * math.sin(spec.direction)
            out[ok] = spec.phillips_constant * np.exp(-1.0 / (kk * lw) ** 2) / kk**4 * along**2
        return out
    if spec.significant_height > 0.0:
        omega = angular_frequency(kk, spec.gravity, spec.depth)
        s = jonswap(omega, spec.significant_height, spec.peak_period, spec.gamma)
        cg = _group_velocity(kk, omega, spec.gravity, spec.depth)
        out[ok] = s * cg * _cos2s(spec, np.arctan2(hy, hx)) / kk
    return out


def tile_amplitudes(spec: TileSpec) -> np.ndarray:
    """h0(k), (N, N) complex m, in FFT order (eq. 42); 0 at k = 0 and on the Nyquist lines.

    Deterministic: ``numpy.random.default_rng(seed)`` draws xi_r then xi_i, N x N each.
    With a ``suppression_length`` l, P(k) is times exp(-k^2 l^2) (eq. 24), so h0 is times
    exp(-k^2 l^2 / 2) (the same draws).
    """
    n = spec.resolution
    kx, ky = lattice(spec)
    variance = spectral_density(spec, kx, ky) * (TWO_PI / spec.size) ** 2 / 2.0
    if spec.suppression_length > 0.0:
        variance *= np.exp(-(kx * kx + ky * ky) * spec.suppression_length**2)
    rng = np.random.default_rng(spec.seed)
    xi = rng.standard_normal((2, n, n))
    h0 = (xi[0] + 1j * xi[1]) * np.sqrt(variance / 2.0)
    h0[n // 2, :] = 0.0
    h0[:, n // 2] = 0.0
    return h0


def tile_steepness(spec: TileSpec, h0: np.ndarray) -> float:
    """Q = -lambda, every component's steepness: min(1, choppiness / sum_k k a_k) (0 if flat).

    Args:
        spec: the tile.
        h0: its :func:`tile_amplitudes`.
    """
    kx, ky = lattice(spec)
    total = float(np.sum(np.hypot(kx, ky) * 2.0 * np.abs(h0)))
    return min(1.0, spec.choppiness / total) if total > 0.0 else 0.0


def tile_sea(spec: TileSpec, h0: np.ndarray | None = None) -> WaveField:
    """The tile as Gerstner components: one per non-zero h0(k) (see the module docstring).

    Component k: amplitude 2 |h0(k)|, wavelength 2 pi / |k|, direction atan2(ky, kx),
    steepness :func:`tile_steepness`, phase arg h0(k); in FFT order (x index, then y); waves of
    zero amplitude (k = 0, the Nyquist lines, across a Phillips wind) are left out. The sea's
    ``tile`` is the spec's size and resolution (so the view and /ocean/surface draw it by
    :func:`grid_surface`).

    Args:
        spec: the tile.
        h0: :func:`tile_amplitudes` of ``spec`` if already computed.
    """
    h0 = tile_amplitudes(spec) if h0 is None else h0
    kx, ky = lattice(spec)
    keep = np.abs(h0) > 0.0
    a, k = 2.0 * np.abs(h0[keep]), np.hypot(kx[keep], ky[keep])
    heading, phase = np.arctan2(ky[keep], kx[keep]), np.angle(h0[keep])
    q = tile_steepness(spec, h0)
    comps = tuple(WaveComponent(float(a[i]), float(TWO_PI / k[i]), float(heading[i]), q,
                                float(phase[i]))
                  for i in range(a.size))
    return WaveField(comps, gravity=spec.gravity, depth=spec.depth,
                     tile=TileGrid(float(spec.size), spec.resolution))


@dataclass(frozen=True)
class Tile:
    """Tessendorf's surface on the tile's grid of rest positions at one time.

    Grid point (i, j) rests at ``(i, j) * size / N``; axis 0 is x, axis 1 is y.

    Attributes:
        positions: (N, N, 3) m, the displaced surface points (x0 - Q D, z = h).
        normals: (N, N, 3) unit upward normals, dP/dx0 x dP/dy0 (spectral derivatives).
        jacobian: (N, N) det of the horizontal map x0 -> x0 - Q D (eq. 31, lambda = -Q):
            Tessendorf's foam where it nears 0; never negative (choppiness <= 1).
        time: t, s.
    """

    positions: np.ndarray
    normals: np.ndarray
    jacobian: np.ndarray
    time: float


def _spectra(spec: TileSpec, h0: np.ndarray, t: float) -> tuple[np.ndarray, ...]:
    """h~(k, t) (eq. 26, time reversed) and k^ components, kx, ky (FFT order)."""
    n = spec.resolution
    kx, ky = lattice(spec)
    k = np.hypot(kx, ky)
    phase = np.exp(-1j * np.mod(angular_frequency(k, spec.gravity, spec.depth) * t, TWO_PI))
    minus = np.conj(h0[(-np.arange(n)) % n][:, (-np.arange(n)) % n])  # conj(h0(-k))
    ht = h0 * phase + minus * np.conj(phase)
    safe = np.where(k > 0.0, k, 1.0)
    return ht, kx / safe, ky / safe, kx, ky


def build_tile(spec: TileSpec, t: float, h0: np.ndarray | None = None) -> Tile:
    """The displaced grid at time t by inverse FFTs (eq. 19, 29-31).

    Eight real fields in four complex inverse FFTs (two Hermitian spectra A + iB per
    transform): h, D_x, D_y, dh/dx, dh/dy, dD_x/dx, dD_x/dy = dD_y/dx, dD_y/dy. Each equals
    the direct sum of :func:`tile_sea`'s components at the grid points (to rounding).

    Args:
        spec: the tile.
        t: time, s.
        h0: :func:`tile_amplitudes` of ``spec`` if already computed.
    """
    h0 = tile_amplitudes(spec) if h0 is None else h0
    ht, ux, uy, kx, ky = _spectra(spec, h0, t)
    scale = spec.resolution**2  # numpy's ifft2 divides by N^2; eq. 19 does not
    f1 = np.fft.ifft2(ht + (-1j * ux * ht) * 1j) * scale  # h + i D_x
    f2 = np.fft.ifft2(-1j * uy * ht + (1j * kx * ht) * 1j) * scale  # D_y + i dh/dx
    f3 = np.fft.ifft2(1j * ky * ht + (kx * ux * ht) * 1j) * scale  # dh/dy + i dDx/dx
    f4 = np.fft.ifft2(kx * uy * ht + (ky * uy * ht) * 1j) * scale  # dDx/dy + i dDy/dy
    c = tile_steepness(spec, h0)
    x0 = np.arange(spec.resolution) * (spec.size / spec.resolution)
    gx, gy = np.meshgrid(x0, x0, indexing="ij")
    positions = np.stack([gx - c * f1.imag, gy - c * f2.real, f1.real], axis=-1)
    hx, hy = f2.imag, f3.real
    # tangents dP/dx0 = (1 - a, -b, hx), dP/dy0 = (-b, 1 - cc, hy)
    a, b, cc = c * f3.imag, c * f4.real, c * f4.imag
    nrm = np.stack([-b * hy - hx * (1.0 - cc), -b * hx - (1.0 - a) * hy,
                    (1.0 - a) * (1.0 - cc) - b * b], axis=-1)
    normals = nrm / np.linalg.norm(nrm, axis=-1, keepdims=True)
    return Tile(positions, normals, (1.0 - a) * (1.0 - cc) - b * b, float(t))


#: The largest M of an M x M grid :func:`grid_surface` sums by FFT (512: 262,144 rest points,
#: about 40 MB of work arrays); a finer one is left to the direct sum (:func:`grid_points`).
MAX_GRID_POINTS = 512


def grid_points(tile: TileGrid, spacing: float) -> int | None:
    """M, the points per side of the tile's FFT grid at most ``spacing`` (m) apart.

    M = ceil(L / spacing) (the grid spacing L / M is ``spacing`` when L is a multiple of it,
    else a little finer), or None when M would exceed :data:`MAX_GRID_POINTS`.
    """
    m = max(1, math.ceil(tile.size / spacing - 1e-9))
    return m if m <= MAX_GRID_POINTS else None


def _grid_fields(sea: WaveField, t: float, m: int, cells: np.ndarray, count: int
                 ) -> np.ndarray:
    """(count, K) the first ``count`` (4 or 8) real fields below at the cells.

    By count / 2 inverse FFTs.

    Each field is Re sum_i c_i e^{i k_i . x0} with c_i = a_i e^{i(phi_i - omega_i t)} times a
    factor per field (theta_i's derivatives; -sin theta = Re(i e^{i theta})):
    z: 1; D_x, D_y: i Q d_x, i Q d_y; dz/dx0, dz/dy0: i k_x, i k_y; dD_x/dx0, dD_x/dy0
    (= dD_y/dx0), dD_y/dy0: -Q d_x k_x, -Q d_x k_y, -Q d_y k_y. Two fields A, B per
    transform: the Hermitian parts of their spectra (Re of the sum) as A + iB.
    """
    ar = sea.arrays
    idx = np.round(ar.kd * (sea.tile.size / TWO_PI)).astype(np.int64) % m  # (2, C) cells
    c = ar.a * np.exp(1j * time_phase(sea, t))
    kx, ky = ar.kd
    qx, qy = ar.q * ar.dx, ar.q * ar.dy
    factors = (np.ones_like(kx), 1j * qx, 1j * qy, 1j * kx, 1j * ky, -qx * kx, -qx * ky,
               -qy * ky)
    neg, i, j = (-np.arange(m)) % m, cells[:, 0] % m, cells[:, 1] % m
    out = np.empty((count, cells.shape[0]))
    for p in range(count // 2):
        raw = np.zeros((2, m, m), dtype=complex)
        for f in range(2):  # add.at: waves that alias onto one cell (M < N) add up
            np.add.at(raw[f], (idx[0], idx[1]), factors[2 * p + f] * c)
        herm = 0.5 * (raw + np.conj(raw[:, neg][:, :, neg]))
        field = np.fft.ifft2(herm[0] + 1j * herm[1])[i, j] * (m * m)
        out[2 * p], out[2 * p + 1] = field.real, field.imag
    return out


def grid_surface(sea: WaveField, t: float, cells: np.ndarray, m: int, normals: bool = True
                 ) -> tuple[np.ndarray, np.ndarray | None]:
    """The surface particles of rest positions on the tile's M x M grid, tiled over any area.

    Rest position of cell (i, j): (i, j) L / M for any integers (the tile repeats every L),
    so the answer is exact at those nodes: the direct sum of the sea's components there, by
    four inverse FFTs over the tile (eq. 19, 29-31; like :func:`build_tile`, but from the
    components, any amplitude, phase and steepness each; two without the normals), then
    indexed modulo M. No interpolation: a point between nodes is not asked for. Costs in
    docs/DESIGN.md ("The FFT ocean").

    Args:
        sea: a sea with a ``tile`` (:func:`tile_sea`).
        t: time, s.
        cells: (K, 2) integers, the rest positions' grid cells.
        m: M, the grid's points per side (:func:`grid_points`).
        normals: also the normals (two more inverse FFTs).

    Returns:
        positions (K, 3) m, the displaced points (x0 - Q D, z = h); normals (K, 3), unit,
        upward, dP/dx0 x dP/dy0 (None unless ``normals``).
    """
    cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    rest = cells * (sea.tile.size / m)
    if not sea.components:
        up = np.zeros((cells.shape[0], 3))
        up[:, 2] = 1.0
        return np.column_stack([rest, np.zeros(cells.shape[0])]), up if normals else None
    fields = _grid_fields(sea, t, m, cells, 8 if normals else 4)
    positions = np.column_stack([rest + fields[1:3].T, fields[0]])
    if not normals:
        return positions, None
    zx, zy, axx, axy, ayy = fields[3:]
    # tangents dP/dx0 = (1 + axx, axy, zx), dP/dy0 = (axy, 1 + ayy, zy)
    nrm = np.column_stack([axy * zy - zx * (1.0 + ayy), axy * zx - (1.0 + axx) * zy,
                           (1.0 + axx) * (1.0 + ayy) - axy * axy])
    return positions, nrm / np.linalg.norm(nrm, axis=1, keepdims=True)
