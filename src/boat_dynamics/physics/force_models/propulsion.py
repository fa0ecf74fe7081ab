"""Propulsion: a thruster at a body point pushing along a body direction.

    F = thrust_fraction * max_thrust * direction,  applied at ``position``

Options (the seed notes, "Thrust application point"): a steerable nozzle (the rudder command
turns the thrust about the body z axis, so a positive angle pushes the stern to starboard and
turns the bow to port), thrust at the centre of mass (pure surge, no turning or pitching
moment), and a first-order lag of the actual thrust behind the command,
tau dT/dt = T_cmd - T, integrated exactly over a step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.wrench import Real, Wrench, cross

__all__ = ["MAX_THRUSTERS", "Propulsion", "lagged_throttle", "thrust", "thrusters_wrench"]

#: The most thrusters a boat may have; a fleet state holds this many throttles per boat.
MAX_THRUSTERS = 8


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
        max_angle: rad, the steering limit of a steerable thruster of a thruster list (its
            angle command is clamped to it); a single thruster steers with the rudder command.
    """

    max_thrust: Real
    position: np.ndarray
    direction: np.ndarray
    steerable: bool = False
    at_center_of_mass: bool = False
    time_constant: Real = 0.0
    max_angle: Real = 0.0


def lagged_throttle(model: Propulsion, actual, command, dt: float):
    """Actual throttle after dt s of first-order lag toward ``command`` (exact for a step).

    ``actual``, ``command`` and the model's ``time_constant`` may be (B,) arrays (one per boat).
    """
    tau = np.asarray(model.time_constant)
    if not np.any(tau > 0.0):
        return command
    decay = np.exp(-dt / np.where(tau > 0.0, tau, 1.0))
    return np.where(tau > 0.0, command + (np.asarray(actual) - command) * decay, command)


def thrust(model: Propulsion, throttle, nozzle_angle, center_of_mass: np.ndarray) -> Wrench:
    """Thrust wrench.

    Args:
        model: thruster parameters (numeric fields may be stacked per boat: (B,), (B, 3)).
        throttle: -1..1 or (B,), actual fraction of max thrust; negative = reverse.
        nozzle_angle: rad or (B,), rudder command (used when the thruster is steerable).
        center_of_mass: (..., 3) m, body frame.

    Returns:
        The thrust wrench about the centre of mass, body frame, (..., 3) each.
    """
    throttle = np.asarray(throttle, dtype=float)
    if throttle.ndim == 1 and np.ndim(center_of_mass) == 2:  # a group of boats: compiled
        return _thrust_compiled(model, throttle, nozzle_angle, center_of_mass)
    return _thrust_numpy(model, throttle, nozzle_angle, center_of_mass)


def _thrust_compiled(model: Propulsion, throttle: np.ndarray, nozzle_angle,
                     center_of_mass: np.ndarray) -> Wrench:
    """:func:`thrust` for a group's (G,) throttles (``actuator_kernel.thrust_f64``)."""
    from boat_dynamics.physics.force_models.actuator_kernel import stacked, thrust_f64

    g = throttle.shape[0]
    return Wrench(*thrust_f64(
        stacked(throttle, g), stacked(nozzle_angle, g), stacked(model.max_thrust, g),
        stacked(model.direction, g, 3), stacked(model.position, g, 3),
        stacked(center_of_mass, g, 3), bool(model.steerable), bool(model.at_center_of_mass)))


def _thrust_numpy(model: Propulsion, throttle, nozzle_angle, center_of_mass: np.ndarray
                  ) -> Wrench:
    """:func:`thrust` in numpy (any shapes; the compiled kernel's oracle)."""
    direction = np.asarray(model.direction, dtype=float)
    if model.steerable:
        angle = -np.asarray(nozzle_angle, dtype=float)
        c, s = np.cos(angle), np.sin(angle)
        dx, dy = direction[..., 0], direction[..., 1]
        direction = np.stack([c * dx - s * dy, s * dx + c * dy,
                              np.broadcast_to(direction[..., 2], np.shape(c * dx))], axis=-1)
    magnitude = np.asarray(throttle, dtype=float) * np.asarray(model.max_thrust, dtype=float)
    force = magnitude[..., None] * direction
    if model.at_center_of_mass:
        return Wrench(force, np.zeros_like(force))
    return Wrench(force, cross(np.asarray(model.position) - center_of_mass, force))


def thrusters_wrench(models: tuple[Propulsion, ...], throttle: np.ndarray,
                     angles: Sequence[np.ndarray], center_of_mass: np.ndarray) -> Wrench:
    """The summed wrench of a boat's (or a group's) thrusters.

    Args:
        models: the thrusters, each stacked per boat of the group.
        throttle: (G, T) actual thrust fractions, thruster j in column j (T >= len(models)).
        angles: per thruster, (G,) rad, its steering angle (used if it is steerable).
        center_of_mass: (G, 3) m, body frame.
    """
    total = thrust(models[0], throttle[:, 0], angles[0], center_of_mass)
    for j in range(1, len(models)):
        total = total + thrust(models[j], throttle[:, j], angles[j], center_of_mass)
    return total
