"""Force + torque pairs, the common currency of the force models.

Every force model returns a :class:`Wrench`: force and torque about the centre of mass, both in
the body frame (FLU), which is what the ``wrench/<source>`` topics publish.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ZERO_WRENCH", "Wrench", "wrench_at"]


@dataclass(frozen=True)
class Wrench:
    """Force (N) and torque (N m) about the centre of mass, body frame.

    Attributes:
        force: (3,) N.
        torque: (3,) N m.

    """

    force: np.ndarray
    torque: np.ndarray

    def __add__(self, other: Wrench) -> Wrench:
        return Wrench(self.force + other.force, self.torque + other.torque)


ZERO_WRENCH = Wrench(np.zeros(3), np.zeros(3))


def wrench_at(forces: np.ndarray, points: np.ndarray) -> Wrench:
    """Sum of forces applied at points, as a wrench about the centre of mass.

    Args:
        forces: (N, 3) or (3,) N, body frame.
        points: (N, 3) or (3,) m, application points relative to the centre of mass, body frame.

    Returns:
        The wrench: sum of forces, and sum of r x F.

    """
    f = np.atleast_2d(forces)
    r = np.atleast_2d(points)
    return Wrench(f.sum(axis=0), np.cross(r, f).sum(axis=0))
