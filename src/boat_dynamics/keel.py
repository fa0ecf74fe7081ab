"""Keel: the seed notes' velocity reflection, an arcade alternative to sway damping.

A keel turns drift into headway: each step a fraction of the sway speed is "reflected" into
surge, keeping the horizontal speed, v_y <- v_y e^(-rate dt),
v_x <- sign(v_x) sqrt(v_x^2 + v_y^2 - v_y'^2). Source: the seed notes, "Lateral resistance"
(reflect the velocity off the keel line).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["reflect_off_keel"]


def reflect_off_keel(velocity: np.ndarray, rate: float, dt: float) -> np.ndarray:
    """Body velocity (3,) m/s after dt s of keel reflection at ``rate`` (1/s)."""
    if rate <= 0.0:
        return velocity
    vx, vy, vz = velocity
    vy_new = vy * math.exp(-rate * dt)
    vx_new = math.copysign(math.sqrt(vx * vx + vy * vy - vy_new * vy_new), vx if vx else 1.0)
    return np.array([vx_new, vy_new, vz])
