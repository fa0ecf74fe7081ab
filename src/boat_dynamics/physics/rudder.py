"""Rudder models: physically based lift (default), and the seed notes' arcade variants.

- ``lift``: a lifting surface at the stern, F_y = -1/2 rho C A u|u| sin(delta), applied at the
  rudder position: a positive angle pushes the stern to starboard (-y), so the bow turns to
  port going ahead (and the other way astern). No speed, no steering. Source: the seed notes,
  "Model A: Rudder Torque (Realistic)"; Fossen (2011), sec. 9.5.
- ``torque``: a yaw torque max_torque * delta / max_angle whatever the speed ("Model B:
  Direct Torque (Arcade)").
- ``hybrid``: (base_torque + speed_torque * |u| / max_speed) * delta / max_angle ("Model C").
- ``none``: no rudder (steer with a steerable thruster instead).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.wrench import Real, Wrench, cross

__all__ = ["DEFAULT_MAX_ANGLE", "RUDDER_MODELS", "Rudder", "RudderModel", "rudder_wrench"]

RudderModel = Literal["lift", "torque", "hybrid", "none"]
RUDDER_MODELS: tuple[RudderModel, ...] = get_args(RudderModel)

#: rad, the default rudder range (35 deg either way).
DEFAULT_MAX_ANGLE = math.radians(35.0)


@dataclass(frozen=True)
class Rudder:
    """Rudder parameters (each model reads its own).

    Attributes:
        model: one of :data:`RUDDER_MODELS`.
        max_angle: rad, the command range is [-max_angle, max_angle].
        area: A, m^2 (lift).
        lift_coefficient: C (lift).
        position: (3,) m, body frame, relative to the hull reference point (lift).
        max_torque: N m at full angle (torque), speed-dependent part at max_speed (hybrid).
        base_torque: N m at full angle and no speed (hybrid).
        max_speed: m/s at which the hybrid's speed part is max_torque (hybrid).
    """

    model: RudderModel = "lift"
    max_angle: Real = DEFAULT_MAX_ANGLE
    area: Real = 0.25
    lift_coefficient: Real = 1.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    max_torque: Real = 0.0
    base_torque: Real = 0.0
    max_speed: Real = 1.0


def rudder_wrench(model: Rudder, angle, surge_speed, water_density,
                  center_of_mass: np.ndarray) -> Wrench:
    """Rudder wrench about the centre of mass, body frame.

    Args:
        model: rudder parameters (numeric fields may be stacked per boat: (B,), (B, 3)).
        angle: delta, rad or (B,), + turns the bow to port.
        surge_speed: u, m/s or (B,), body-x speed through the water.
        water_density: rho, kg/m^3 or (B,).
        center_of_mass: (..., 3) m, body frame.

    Returns:
        The wrench, (..., 3) each.
    """
    angle = np.asarray(angle, dtype=float)
    u = np.asarray(surge_speed, dtype=float)
    shape = np.broadcast_shapes(angle.shape, u.shape, np.shape(center_of_mass)[:-1])
    zero = np.zeros(shape)
    if model.model == "lift":
        side = (-0.5 * np.asarray(water_density) * model.lift_coefficient * model.area
                * u * np.abs(u) * np.sin(angle))
        force = np.stack([zero, zero + side, zero], axis=-1)
        return Wrench(force, cross(np.asarray(model.position) - center_of_mass, force))
    fraction = angle / model.max_angle
    if model.model == "torque":
        yaw = np.asarray(model.max_torque) * fraction
    elif model.model == "hybrid":
        yaw = (np.asarray(model.base_torque)
               + np.asarray(model.max_torque) * np.abs(u) / model.max_speed) * fraction
    else:
        return Wrench(np.zeros((*shape, 3)), np.zeros((*shape, 3)))
    return Wrench(np.zeros((*shape, 3)), np.stack([zero, zero, zero + yaw], axis=-1))
