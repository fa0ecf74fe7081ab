"""Propulsion: a thruster at a body point pushing along a body direction.

    F = thrust_fraction * max_thrust * direction,  applied at ``position``

Options (the seed notes, "Thrust application point"): a steerable nozzle (the rudder command
turns the thrust about the body z axis, so a positive angle pushes the stern to starboard and
turns the bow to port), thrust at the centre of mass (pure surge, no turning or pitching
moment), and a first-order lag of the actual thrust behind the command,
tau dT/dt = T_cmd - T, integrated exactly over a step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.wrench import Wrench, wrench_at

__all__ = ["Propulsion", "lagged_throttle", "thrust"]


@dataclass(frozen=True)
class Propulsion:
    """Thruster parameters.

    Attributes:
        max_thrust: N, > 0, force at throttle 1.
        position: (3,) m, application point, body frame (relative to the hull reference point).
        direction: (3,) unit vector, body frame, along which positive throttle pushes.
        steerable: the rudder command also turns the thrust (water-jet nozzle, outboard).
        at_center_of_mass: apply at the centre of mass instead of ``position``.
        time_constant: s, >= 0, first-order lag of the thrust (0 = immediate).
    """

    max_thrust: float
    position: np.ndarray
    direction: np.ndarray
    steerable: bool = False
    at_center_of_mass: bool = False
    time_constant: float = 0.0


def lagged_throttle(model: Propulsion, actual: float, command: float, dt: float) -> float:
    """Actual throttle after dt s of first-order lag toward ``command`` (exact for a step)."""
    if model.time_constant <= 0.0:
        return command
    return command + (actual - command) * math.exp(-dt / model.time_constant)


def thrust(model: Propulsion, throttle: float, nozzle_angle: float,
           center_of_mass: np.ndarray) -> Wrench:
    """Thrust wrench.

    Args:
        model: thruster parameters.
        throttle: -1..1, actual fraction of max thrust; negative = reverse.
        nozzle_angle: rad, rudder command (used when the thruster is steerable).
        center_of_mass: (3,) m, body frame.

    Returns:
        The thrust wrench about the centre of mass, body frame.
    """
    direction = model.direction
    if model.steerable and nozzle_angle != 0.0:
        c, s = math.cos(-nozzle_angle), math.sin(-nozzle_angle)
        direction = np.array([c * direction[0] - s * direction[1],
                              s * direction[0] + c * direction[1], direction[2]])
    force = throttle * model.max_thrust * direction
    if model.at_center_of_mass:
        return Wrench(force, np.zeros(3))
    return wrench_at(force, model.position - center_of_mass)
