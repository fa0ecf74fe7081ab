"""Keel: the seed notes' velocity reflection, an arcade alternative to sway damping.

A keel turns drift into headway: each step a fraction of the sway speed is "reflected" into
surge, keeping the horizontal speed, v_y <- v_y e^(-rate dt),
v_x <- sign(v_x) sqrt(v_x^2 + v_y^2 - v_y'^2). Source: the seed notes, "Lateral resistance"
(reflect the velocity off the keel line).
"""

from __future__ import annotations

import numpy as np

__all__ = ["reflect_off_keel"]


def reflect_off_keel(velocity: np.ndarray, rate, dt: float) -> np.ndarray:
    """Body velocity (..., 3) m/s after dt s of keel reflection at ``rate`` (1/s, or (B,))."""
    rate = np.asarray(rate, dtype=float)
    if not np.any(rate > 0.0):
        return velocity
    vx, vy, vz = velocity[..., 0], velocity[..., 1], velocity[..., 2]
    vy_new = vy * np.exp(-np.maximum(rate, 0.0) * dt)
    speed = np.sqrt(np.maximum(vx * vx + vy * vy - vy_new * vy_new, 0.0))
    vx_new = np.where(vx < 0.0, -speed, speed)  # sign(vx), + when vx == 0
    return np.stack([vx_new, vy_new, vz], axis=-1)
