"""A towing carriage: the boat moved at a prescribed speed along a line, heave, roll, pitch free.

A towing tank's carriage tows the model at a constant speed U; the model is free to heave and
pitch (and here to roll), and held in sway and yaw (ITTC Recommended Procedure 7.5-02-07-02.1,
"Seakeeping Experiments", sec. 3.3, and 7.5-02-02-01, "Resistance Test"). The force the
carriage needs is the model's resistance: in calm water its calm-water resistance, in waves
plus the added resistance.

Here, after each step, three velocity constraints on the centre of mass, in the world frame:
the speed along the carriage's line d is U, the speed across it brings the lateral offset back
with the time constant :data:`TIME_CONSTANT`, and the yaw rate brings the heading back alike
(Baumgarte stabilization of a velocity-level constraint). With C the (3, 6) rows of these
world components in body coordinates and M the boat's 6 x 6 mass matrix (rigid plus added),
the impulse that meets them and disturbs nothing else is the Gauss least-action one::

    lambda = (C M^-1 C^T)^-1 (target - C nu),   nu' = nu + M^-1 C^T lambda

(Featherstone, "Rigid Body Dynamics Algorithms", 2008, sec. 8.1), so the coupling of surge with
heave and pitch through the added mass is kept. lambda / dt is the carriage's force along the
line and across it (N, world frame) and its yaw moment (N m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["TIME_CONSTANT", "Carriage", "body_wrench", "towed_velocity"]

#: s, the time constant with which the carriage brings back a lateral offset or a heading error.
TIME_CONSTANT = 0.2


@dataclass(frozen=True)
class Carriage:
    """A carriage towing one boat.

    Attributes:
        speed: m/s along the line (negative: astern).
        origin: (2,) m, world x, y of the centre of mass where the tow starts; NaN until
            :func:`boat_dynamics.physics.core.pipeline.init` places it at the boat's start.
        heading: rad, the line's direction and the boat's heading (world, CCW from +x); NaN
            until placed.
    """

    speed: float
    origin: np.ndarray
    heading: float


def towed_velocity(carriage: Carriage, mass_matrix: np.ndarray, rotation: np.ndarray,
                   position: np.ndarray, nu: np.ndarray, dt: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The body velocities meeting the carriage's constraints, and the carriage's wrench.

    Args:
        carriage: the carriage (placed).
        mass_matrix: (6, 6) the boat's mass matrix about its centre of mass, body axes.
        rotation: (3, 3) body to world.
        position: (3,) m, centre of mass, world frame.
        nu: (6,) body velocities [u, v, w, p, q, r] before the constraint.
        dt: s, the step.

    Returns:
        (6,) the constrained body velocities; (3,) the carriage's force along its line, across
        it (N) and its yaw moment (N m), world frame, over the step.
    """
    h = carriage.heading
    along = np.array([math.cos(h), math.sin(h), 0.0])
    across = np.array([-math.sin(h), math.cos(h), 0.0])
    rows = np.zeros((3, 6))
    rows[0, :3] = along @ rotation
    rows[1, :3] = across @ rotation
    rows[2, 3:] = rotation[2]
    offset = float(across[:2] @ (position[:2] - carriage.origin))
    heading = math.atan2(rotation[1, 0], rotation[0, 0])
    error = math.remainder(heading - h, 2.0 * math.pi)
    target = np.array([carriage.speed, -offset / TIME_CONSTANT, -error / TIME_CONSTANT])
    inverse_rows = np.linalg.solve(mass_matrix, rows.T)  # M^-1 C^T, (6, 3)
    impulse = np.linalg.solve(rows @ inverse_rows, target - rows @ nu)
    return nu + inverse_rows @ impulse, impulse / dt


def body_wrench(carriage: Carriage, rotation: np.ndarray, towing: np.ndarray) -> np.ndarray:
    """(6,) the carriage's force (N) and moment (N m) on the boat, body frame.

    Args:
        carriage: the carriage (placed).
        rotation: (3, 3) body to world.
        towing: (3,) :func:`towed_velocity`'s force along and across the line (N) and yaw
            moment (N m), world frame.

    Returns:
        Force then torque about the centre of mass, in the body frame: the form of the
        ``wrench/<source>`` topics.
    """
    h = carriage.heading
    force = towing[0] * np.array([math.cos(h), math.sin(h), 0.0]) + towing[1] * np.array(
        [-math.sin(h), math.cos(h), 0.0])
    return np.concatenate([rotation.T @ force, rotation.T @ np.array([0.0, 0.0, towing[2]])])
