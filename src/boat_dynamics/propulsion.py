"""Propulsion: a thruster at a body point pushing along a body direction.

    F = throttle * max_thrust * direction,  applied at ``position``

Thrust at the stern below the centre of mass gives the pitch-up of a real boat under power.
Source: the seed notes, "Thrust application point".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.wrench import Wrench, wrench_at

__all__ = ["Propulsion", "thrust"]


@dataclass(frozen=True)
class Propulsion:
    """Thruster parameters.

    Attributes:
        max_thrust: N, > 0, force at throttle 1.
        position: (3,) m, application point, body frame (relative to the hull reference point).
        direction: (3,) unit vector, body frame, along which positive throttle pushes.

    """

    max_thrust: float
    position: np.ndarray
    direction: np.ndarray


def thrust(model: Propulsion, throttle: float, center_of_mass: np.ndarray) -> Wrench:
    """Thrust wrench.

    Args:
        model: thruster parameters.
        throttle: -1..1, fraction of max thrust; negative = reverse.
        center_of_mass: (3,) m, body frame.

    Returns:
        The thrust wrench about the centre of mass, body frame.

    """
    force = throttle * model.max_thrust * model.direction
    return wrench_at(force, model.position - center_of_mass)
