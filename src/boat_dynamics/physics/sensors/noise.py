"""Sensor noise drawn from the scenario seed, with no hidden generator state.

Every draw is addressed: stream ``key`` (a sensor of a boat of a scenario seed) and sample
index ``sample``. A counter-based generator (Philox; Salmon et al. 2011, "Parallel random
numbers: as easy as 1, 2, 3") is set to counter (0, sample, 0, 0) under that key, so sample k
of a stream is the same whatever was drawn before, in whatever order or process: the same seed
gives the same readings, and a sensor's state is only its last sample's values.

The processes (per axis, sample interval dt):

- white noise of density N (unit/sqrt(Hz)): sigma = N sqrt(rate) = N / sqrt(dt)
  (IEEE Std 952-1997, angle random walk; Woodman 2007, "An introduction to inertial
  navigation", sec. 4);
- a first-order Gauss-Markov process of stationary sigma s and correlation time tau:
  b' = phi b + s sqrt(1 - phi^2) w, phi = exp(-dt / tau) (exact discretization; Gelb 1974,
  "Applied optimal estimation", sec. 3.8); it starts drawn from its stationary law;
- a random walk of density K (unit/s/sqrt(Hz)): b' = b + K sqrt(dt) w.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["DROPOUT_SAMPLES", "dropped", "gauss_markov", "random_walk", "standard_normal",
           "stream_key"]

#: Where a stream's dropout draws start (:func:`dropped`): past every reading's own counter.
DROPOUT_SAMPLES = 2**61


def stream_key(seed: int, *names: str | int) -> np.ndarray:
    """(2,) uint64 Philox key of the stream of ``names`` under ``seed``.

    E.g. ``stream_key(seed, "alpha", "imu")``: a sensor keyed by its boat's and its own name,
    so it reads the same whichever process steps the boat, and whatever other boats exist.
    """
    entropy = [seed]
    for name in names:
        data = name.encode() if isinstance(name, str) else [name]
        entropy += [len(data), *data]
    return np.random.SeedSequence(entropy).generate_state(2, np.uint64)


def standard_normal(key: np.ndarray, sample: int, n: int) -> np.ndarray:
    """(n,) independent N(0, 1) draws: sample ``sample`` (>= 0) of stream ``key``."""
    counter = np.array([0, sample, 0, 0], dtype=np.uint64)
    return np.random.Generator(np.random.Philox(key=key, counter=counter)).standard_normal(n)


def gauss_markov(value: np.ndarray, sigma: float | np.ndarray, tau: float, dt: float,
                 draws: np.ndarray) -> np.ndarray:
    """The Gauss-Markov process one interval ``dt`` (s) later, with N(0, 1) ``draws``.

    ``sigma``: a number or one per axis. ``tau`` (s) = inf makes it a constant (the initial
    draw); ``sigma`` = 0 makes it zero.
    """
    phi = 0.0 if tau == 0.0 else math.exp(-dt / tau)
    return phi * value + sigma * math.sqrt(max(0.0, 1.0 - phi * phi)) * draws


def random_walk(value: np.ndarray, density: float, dt: float, draws: np.ndarray) -> np.ndarray:
    """The random walk one interval ``dt`` (s) later, with N(0, 1) ``draws``."""
    return value + density * math.sqrt(dt) * draws


def dropped(key: np.ndarray, sample: int, probability: float) -> bool:
    """Whether reading ``sample`` of stream ``key`` is lost (a dropout of ``probability``).

    A uniform draw at counter :data:`DROPOUT_SAMPLES` + ``sample``, apart from the reading's
    noise: the same readings are lost in every run of a seed, and the noise of the others is
    what it would be without dropouts.
    """
    if probability <= 0.0:
        return False
    counter = np.array([0, DROPOUT_SAMPLES + sample, 0, 0], dtype=np.uint64)
    draw = np.random.Generator(np.random.Philox(key=key, counter=counter)).random()
    return bool(draw < probability)
