"""Sea states from wave spectra: JONSWAP, Pierson-Moskowitz, cos-2s spreading, Beaufort presets.

Pure numpy; never imports rclpy. A spectrum becomes N Gerstner components:

1. the frequency range [0.5, 3] omega_p is cut into N bins of equal energy (equal m0) of the
   continuous spectrum S(omega); each component sits at its bin's energy centroid with
   amplitude a_i = sqrt(2 m0_bin), so sum a_i^2 / 2 = m0 and H_s = 4 sqrt(m0) is kept up to the
   energy outside the range (about 1.5 % of m0 for Pierson-Moskowitz, 0.8 % of H_s);
2. the wavelength follows from the dispersion relation omega^2 = g k tanh(k h);
3. each component's direction is drawn from the cos-2s spreading function, its phase uniformly
   from [0, 2 pi), both from ``numpy.random.default_rng(seed)``: same seed, same sea;
4. steepness Q_i = min(1, Q / (N k_i a_i)), so sum Q_i k_i a_i <= Q <= 1: crests never loop.

Sources: DNV-RP-C205 (2010), sec. 3.5.5 (JONSWAP with A_gamma = 1 - 0.287 ln gamma, sigma
0.07/0.09) and 3.5.8.4 (cos-2s spreading, Longuet-Higgins et al. 1963); Pierson & Moskowitz,
J. Geophys. Res. 69 (1964) for the fully developed sea (H_s = 0.21 U^2/g, omega_p = 0.877 g/U).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ocean_sim.physics.constants import GRAVITY, TWO_PI
from ocean_sim.physics.waves import InvalidSeaStateError, WaveComponent, WaveField

__all__ = [
    "BEAUFORT_SIGNIFICANT_HEIGHT",
    "SPECTRUM_TYPES",
    "SpectrumSpec",
    "beaufort_sea",
    "generate_sea",
    "jonswap",
    "pierson_moskowitz_peak_period",
    "wavenumber",
]

#: Spectrum shapes understood by :func:`generate_sea`.
SPECTRUM_TYPES = ("jonswap", "pierson_moskowitz")

#: Significant wave height, m, for Beaufort forces 0..12: the WMO "probable wave height" in the
#: open sea (WMO-No. 558, Manual on Marine Meteorological Services, Beaufort scale table).
BEAUFORT_SIGNIFICANT_HEIGHT = (0.0, 0.1, 0.2, 0.6, 1.0, 2.0, 3.0, 4.0, 5.5, 7.0, 9.0, 11.5, 14.0)

# Range of the discretization, in units of the peak frequency.
_OMEGA_LOW, _OMEGA_HIGH = 0.5, 3.0
# Points of the fine grid the spectrum is integrated on.
_GRID = 4096


def pierson_moskowitz_peak_period(significant_height: float, gravity: float = GRAVITY) -> float:
    """Peak period, s, of a fully developed sea of significant height H_s (m).

    From H_s = 0.21 U^2 / g and omega_p = 0.877 g / U (Pierson & Moskowitz 1964):
    T_p = 2 pi / 0.877 * sqrt(H_s / (0.21 g)).
    """
    return TWO_PI / 0.877 * math.sqrt(significant_height / (0.21 * gravity))


def jonswap(omega: np.ndarray, significant_height: float, peak_period: float,
            gamma: float = 3.3) -> np.ndarray:
    """JONSWAP spectral density S(omega), m^2 s/rad (gamma = 1: Pierson-Moskowitz).

    S = A_gamma S_PM(omega) gamma^exp(-(omega - omega_p)^2 / (2 sigma^2 omega_p^2)), with
    S_PM = 5/16 H_s^2 omega_p^4 omega^-5 exp(-5/4 (omega / omega_p)^-4) (DNV-RP-C205 3.5.5).

    Args:
        omega: (K,) rad/s, > 0.
        significant_height: H_s, m.
        peak_period: T_p, s.
        gamma: peak enhancement factor, 1..7.

    Returns:
        (K,) spectral density.
    """
    w = np.asarray(omega, dtype=float)
    wp = TWO_PI / peak_period
    pm = 5.0 / 16.0 * significant_height**2 * wp**4 * w**-5 * np.exp(-1.25 * (w / wp) ** -4)
    sigma = np.where(w <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-0.5 * ((w - wp) / (sigma * wp)) ** 2)
    return (1.0 - 0.287 * math.log(gamma)) * pm * peak


def wavenumber(omega: np.ndarray, gravity: float, depth: float) -> np.ndarray:
    """K solving omega^2 = g k tanh(k h) (Newton iteration from the deep-water k = omega^2/g)."""
    w = np.asarray(omega, dtype=float)
    k = w * w / gravity
    if math.isinf(depth):
        return k
    k = np.maximum(k, w / math.sqrt(gravity * depth))  # shallow-water start is an upper bound
    for _ in range(50):
        t = np.tanh(k * depth)
        f = gravity * k * t - w * w
        df = gravity * (t + k * depth * (1.0 - t * t))
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-14 * k):
            break
    return k


@dataclass(frozen=True)
class SpectrumSpec:
    """A generated sea state (the scenario's ``ocean.spectrum`` block).

    Attributes:
        type: ``jonswap`` or ``pierson_moskowitz``.
        significant_height: H_s, m, >= 0.
        peak_period: T_p, s, > 0.
        direction: mean direction the waves travel toward, rad, counter-clockwise from +x.
        spreading: s of the cos-2s spreading function (larger = narrower), or None for
            long-crested waves all in ``direction``.
        components: N, the number of Gerstner components.
        gamma: JONSWAP peak enhancement (ignored by pierson_moskowitz).
        steepness: Q, the budget of sum Q_i k_i a_i, 0..1.
    """

    type: str = "jonswap"
    significant_height: float = 1.0
    peak_period: float = 6.0
    direction: float = 0.0
    spreading: float | None = 10.0
    components: int = 16
    gamma: float = 3.3
    steepness: float = 0.5


def _check(spec: SpectrumSpec) -> None:
    if spec.type not in SPECTRUM_TYPES:
        raise InvalidSeaStateError("spectrum.type", spec.type,
                                   f"must be one of: {', '.join(SPECTRUM_TYPES)}")
    checks = (
        ("significant_height", spec.significant_height, 0.0, 30.0, "m"),
        ("peak_period", spec.peak_period, 0.5, 40.0, "s"),
        ("gamma", spec.gamma, 1.0, 7.0, ""),
        ("steepness", spec.steepness, 0.0, 1.0, ""),
        ("direction", spec.direction, -1e3, 1e3, "rad"),
    )
    for name, v, lo, hi, unit in checks:
        if not (isinstance(v, (int, float)) and math.isfinite(v) and lo <= v <= hi):
            raise InvalidSeaStateError(f"spectrum.{name}", v,
                                       f"must be a number in [{lo:g}, {hi:g}] {unit}".rstrip())
    if spec.spreading is not None and not (math.isfinite(spec.spreading)
                                           and 0.0 <= spec.spreading <= 1000.0):
        raise InvalidSeaStateError("spectrum.spreading", spec.spreading,
                                   "must be a number in [0, 1000], or null for long-crested")
    if not (isinstance(spec.components, int) and 1 <= spec.components <= 1000):
        raise InvalidSeaStateError("spectrum.components", spec.components,
                                   "must be an integer in [1, 1000]")


def _spreading_directions(rng: np.random.Generator, n: int, mean: float,
                          s: float | None) -> np.ndarray:
    """N directions drawn from D(theta) ~ cos^(2s)((theta - mean) / 2), by inverse CDF."""
    if s is None:
        return np.full(n, mean)
    theta = np.linspace(-math.pi, math.pi, 2049)
    density = np.cos(theta / 2) ** (2 * s)
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]))])
    cdf /= cdf[-1]
    return mean + np.interp(rng.uniform(0.0, 1.0, n), cdf, theta)


def generate_sea(spec: SpectrumSpec, seed: int = 0, gravity: float = GRAVITY,
                 depth: float = math.inf) -> WaveField:
    """Gerstner components of a spectrum (see the module docstring for the method).

    Args:
        spec: the spectrum.
        seed: random seed of directions and phases.
        gravity: g, m/s^2.
        depth: water depth h, m (inf = deep).

    Returns:
        The sea state (flat if H_s = 0).

    Raises:
        InvalidSeaStateError: a spectrum parameter out of range (key ``spectrum.<name>``).
    """
    _check(spec)
    if spec.significant_height == 0.0:
        return WaveField((), gravity=gravity, depth=depth)
    n = spec.components
    wp = TWO_PI / spec.peak_period
    gamma = 1.0 if spec.type == "pierson_moskowitz" else spec.gamma
    w = np.linspace(_OMEGA_LOW * wp, _OMEGA_HIGH * wp, _GRID)
    s = jonswap(w, spec.significant_height, spec.peak_period, gamma)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (s[1:] + s[:-1]) * np.diff(w))])
    first_moment = np.concatenate([[0.0], np.cumsum(0.5 * (s[1:] * w[1:] + s[:-1] * w[:-1])
                                                    * np.diff(w))])
    edges = np.linspace(0.0, cum[-1], n + 1)
    m0_at = edges
    w1_at = np.interp(edges, cum, first_moment)
    m0_bins = np.diff(m0_at)
    omega = np.diff(w1_at) / m0_bins  # energy centroid of each bin
    amplitude = np.sqrt(2.0 * m0_bins)
    k = wavenumber(omega, gravity, depth)
    rng = np.random.default_rng(seed)
    phases = rng.uniform(0.0, TWO_PI, n)
    directions = _spreading_directions(rng, n, spec.direction, spec.spreading)
    q = np.minimum(1.0, spec.steepness / (n * k * amplitude))
    comps = tuple(
        WaveComponent(float(amplitude[i]), float(TWO_PI / k[i]), float(directions[i]),
                      float(q[i]), float(phases[i]))
        for i in range(n)
    )
    return WaveField(comps, gravity=gravity, depth=depth)


def beaufort_sea(force: int, direction: float = 0.0, spreading: float | None = 10.0,
                 components: int = 16, steepness: float = 0.5, seed: int = 0,
                 gravity: float = GRAVITY, depth: float = math.inf) -> WaveField:
    """A Pierson-Moskowitz sea for a Beaufort force 0..12.

    H_s from :data:`BEAUFORT_SIGNIFICANT_HEIGHT`, T_p from
    :func:`pierson_moskowitz_peak_period` (fully developed sea).

    Raises:
        InvalidSeaStateError: force outside 0..12.
    """
    if isinstance(force, bool) or not isinstance(force, int) or not 0 <= force <= 12:
        raise InvalidSeaStateError("spectrum.beaufort", force, "must be an integer in [0, 12]")
    hs = BEAUFORT_SIGNIFICANT_HEIGHT[force]
    tp = pierson_moskowitz_peak_period(hs, gravity) if hs > 0 else 1.0
    spec = SpectrumSpec("pierson_moskowitz", hs, tp, direction, spreading, components,
                        1.0, steepness)
    return generate_sea(spec, seed=seed, gravity=gravity, depth=depth)
