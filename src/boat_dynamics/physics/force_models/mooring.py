"""A soft horizontal mooring: how a towing tank holds a model on station in waves.

Seakeeping tests of a model at zero speed hold it with soft springs so that it keeps its mean
position and heading without the springs touching its wave-frequency motion: their natural
period is many wave periods (ITTC Recommended Procedure 7.5-02-07-02.1, "Seakeeping
Experiments", sec. 3.3; Faltinsen, "Sea Loads on Ships and Offshore Structures", 1990,
ch. 7). Without it a free hull drifts with the waves' mean second-order force, and its
encounter frequency drifts with it.

Here: linear springs and dampers on the world x, y of the centre of mass and on the heading,
attached at the centre of mass (so no roll or pitch moment)::

    F_x = -k_x (x - x_0) - c_x x',   F_y = -k_y (y - y_0) - c_y y',
    N_z = -k_psi wrap(psi - psi_0) - c_psi psi'

:func:`soft_mooring` sets k for a natural period T with the rigid-body plus added mass, and c
critical, c = 2 sqrt(k m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench

__all__ = ["Mooring", "mooring_wrench", "soft_mooring"]


@dataclass(frozen=True)
class Mooring:
    """Springs and dampers holding one boat on station.

    Attributes:
        anchor: (3,) world x (m), y (m) of the centre of mass and heading (rad) held.
        stiffness: (3,) N/m, N/m, N m/rad.
        damping: (3,) N s/m, N s/m, N m s/rad.
    """

    anchor: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray


def soft_mooring(anchor: np.ndarray, mass: np.ndarray, period: float) -> Mooring:
    """A critically damped mooring of natural period ``period`` s.

    Args:
        anchor: (3,) world x, y (m) of the centre of mass and heading (rad) held.
        mass: (3,) kg, kg, kg m^2: surge, sway and yaw mass including added mass.
        period: s, > 0: many wave periods for a mooring that leaves the wave-frequency
            motion alone.
    """
    omega = 2 * math.pi / period
    mass = np.asarray(mass, dtype=float)
    stiffness = mass * omega**2
    return Mooring(np.asarray(anchor, dtype=float), stiffness, 2.0 * np.sqrt(stiffness * mass))


def mooring_wrench(stiffness: np.ndarray, damping: np.ndarray, anchor: np.ndarray,
                   position: np.ndarray, rotation: np.ndarray, velocity: np.ndarray,
                   angular_velocity: np.ndarray) -> Wrench:
    """The moorings' wrenches, body frames, about the centres of mass.

    Args:
        stiffness: (B, 3) N/m, N/m, N m/rad (zero for a boat not moored).
        damping: (B, 3) N s/m, N s/m, N m s/rad.
        anchor: (B, 3) m, m, rad.
        position: (B, 3) m, centres of mass, world frame.
        rotation: (B, 3, 3) body to world.
        velocity: (B, 3) m/s, body frame.
        angular_velocity: (B, 3) rad/s, body frame.
    """
    world_velocity = np.einsum("bij,bj->bi", rotation, velocity)
    world_rate = np.einsum("bij,bj->bi", rotation, angular_velocity)[:, 2]
    heading = np.arctan2(rotation[:, 1, 0], rotation[:, 0, 0])
    error = np.angle(np.exp(1j * (heading - anchor[:, 2])))
    force = np.zeros_like(position)
    force[:, :2] = (-stiffness[:, :2] * (position[:, :2] - anchor[:, :2])
                    - damping[:, :2] * world_velocity[:, :2])
    torque = np.zeros_like(position)
    torque[:, 2] = -stiffness[:, 2] * error - damping[:, 2] * world_rate
    return Wrench(np.einsum("bji,bj->bi", rotation, force),
                  np.einsum("bji,bj->bi", rotation, torque))
