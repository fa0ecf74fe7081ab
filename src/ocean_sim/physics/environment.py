"""What besides the waves moves a boat: a uniform current and the wind, with gusts.

Directions as for waves: the heading the current or wind travels toward, radians
counter-clockwise from +x (east). Both are uniform in space.

Gusts (``gusts: norsok``): the wind speed along its mean direction is U + u(t), u a sum of N
harmonic components of the NORSOK spectrum (NORSOK N-003, 2007, sec. 6.3; DNV-RP-C205, 2010,
sec. 2.3.2.13, the Froya spectrum; Fossen 2021, sec. 10.1.2) at 10 m height,

    S(f) = 320 (U/10)^2 / (1 + x^n)^(5 / (3 n)),   x = 172 f (U/10)^-0.75,   n = 0.468

(S in m^2/s^2/Hz, f in Hz, U the one-hour mean at 10 m in m/s), over its range 1/600 Hz to
0.5 Hz: u(t) = sum_i sqrt(2 S(f_i) df_i) cos(2 pi f_i t + phi_i), the bins equally spaced in
log f, phases uniform from ``numpy.random.default_rng(seed)``: a function of time alone, so
every process computes the same gusts, and the same seed gives the same wind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

__all__ = ["GUST_MODELS", "MAX_CURRENT_SPEED", "MAX_GUST_COMPONENTS", "MAX_WIND_SPEED",
           "Environment", "GustModel", "InvalidEnvironmentError", "Wind", "norsok_spectrum"]

GustModel = Literal["none", "norsok"]
#: The gust models of :class:`Wind`.
GUST_MODELS: tuple[GustModel, ...] = ("none", "norsok")

#: The NORSOK spectrum's frequency range, Hz.
NORSOK_RANGE = (1.0 / 600.0, 0.5)

#: The bounds every reader of an environment applies, the scenario, the ocean node's parameters
#: and the dynamics node's /ocean/environment subscriber alike: m/s, m/s, components.
MAX_CURRENT_SPEED = 20.0
MAX_WIND_SPEED = 100.0
MAX_GUST_COMPONENTS = 1000


class InvalidEnvironmentError(ValueError):
    """An environment out of its bounds: which key, which value, what is allowed."""

    def __init__(self, key: str, value: object, allowed: str) -> None:
        self.key, self.value, self.allowed = key, value, allowed
        super().__init__(f"{key}: {value!r} is not allowed: {allowed}")


def _speed(key: str, value: object, high: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and 0.0 <= value <= high):
        raise InvalidEnvironmentError(key, value, f"a number in [0, {high:g}] m/s")


def _direction(key: str, value: object) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value)):
        raise InvalidEnvironmentError(key, value, "a finite angle, rad")


def norsok_spectrum(f: np.ndarray, mean_speed: float) -> np.ndarray:
    """(F,) m^2/s^2/Hz, the NORSOK wind spectrum at 10 m of a one-hour mean ``mean_speed``."""
    u = mean_speed / 10.0
    x = 172.0 * np.asarray(f, dtype=float) * u ** -0.75
    n = 0.468
    return 320.0 * u**2 / (1.0 + x**n) ** (5.0 / (3.0 * n))


@dataclass(frozen=True)
class Wind:
    """A uniform wind: mean speed and direction, and its gusts.

    Build with :meth:`make` (which draws the gust components); ``Wind()`` is calm.

    Attributes:
        speed: m/s, the one-hour mean at 10 m, >= 0.
        direction: rad, the heading the wind blows toward, counter-clockwise from +x.
        gusts: the gust model.
        components: N, the gust components asked for.
        seed: the seed their phases were drawn from.
        frequencies: (N,) rad/s, gust components (empty without gusts).
        amplitudes: (N,) m/s.
        phases: (N,) rad.
    """

    speed: float = 0.0
    direction: float = 0.0
    gusts: GustModel = "none"
    components: int = 50
    seed: int = 0
    frequencies: np.ndarray = field(default_factory=lambda: np.zeros(0))
    amplitudes: np.ndarray = field(default_factory=lambda: np.zeros(0))
    phases: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @classmethod
    def make(cls, speed: float, direction: float, gusts: GustModel = "none",
             components: int = 50, seed: int = 0) -> Wind:
        """The wind, its gust components drawn from ``seed`` (``components`` of them).

        Raises:
            InvalidEnvironmentError: a speed, direction, gust model or component count out of
                its bounds (checked before anything is drawn).
        """
        _speed("wind.speed", speed, MAX_WIND_SPEED)
        _direction("wind.direction", direction)
        if gusts not in GUST_MODELS:
            raise InvalidEnvironmentError("wind.gusts", gusts, f"one of: {', '.join(GUST_MODELS)}")
        if (isinstance(components, bool) or not isinstance(components, (int, np.integer))
                or not 1 <= components <= MAX_GUST_COMPONENTS):
            raise InvalidEnvironmentError("wind.gust_components", components,
                                          f"an integer in [1, {MAX_GUST_COMPONENTS}]")
        if gusts == "none" or speed == 0.0:
            return cls(speed, direction, gusts, components, seed)
        edges = np.geomspace(*NORSOK_RANGE, components + 1)
        f = np.sqrt(edges[:-1] * edges[1:])
        amplitudes = np.sqrt(2.0 * norsok_spectrum(f, speed) * np.diff(edges))
        phases = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, components)
        return cls(speed, direction, gusts, components, seed, 2.0 * math.pi * f, amplitudes,
                   phases)

    def speed_at(self, t: float) -> float:
        """m/s, the wind speed along its mean direction at time ``t`` (s)."""
        if self.frequencies.size == 0:
            return self.speed
        return self.speed + float(self.amplitudes @ np.cos(self.frequencies * t + self.phases))

    def velocity(self, t: float) -> np.ndarray:
        """(3,) m/s, world frame, the wind's velocity at time ``t`` (s)."""
        u = self.speed_at(t)
        return np.array([u * math.cos(self.direction), u * math.sin(self.direction), 0.0])


@dataclass(frozen=True)
class Environment:
    """The uniform current and the wind.

    Attributes:
        current_speed: m/s, >= 0.
        current_direction: rad, the heading the current flows toward.
        wind: the wind.
    """

    current_speed: float = 0.0
    current_direction: float = 0.0
    wind: Wind = field(default_factory=Wind)

    def __post_init__(self) -> None:
        _speed("current.speed", self.current_speed, MAX_CURRENT_SPEED)
        _direction("current.direction", self.current_direction)

    @property
    def current(self) -> np.ndarray:
        """(3,) m/s, world frame, the current's velocity."""
        return np.array([self.current_speed * math.cos(self.current_direction),
                         self.current_speed * math.sin(self.current_direction), 0.0])

    @property
    def is_calm(self) -> bool:
        """No current and no wind."""
        return self.current_speed == 0.0 and self.wind.speed == 0.0
