"""Rudder models: physically based lift (default), and the seed notes' arcade variants.

- ``lift``: a lifting surface at the stern meeting the water at its angle of attack,
  alpha = delta + beta_R, beta_R = atan2(v_R, u_R) the drift angle of the flow at the rudder
  (u_R, v_R: the body's velocity through the water at the rudder position, yaw and roll rate
  included). The side force F_y = -1/2 rho C A V_R^2 sin(alpha)
  = -1/2 rho C A V_R (u_R sin(delta) + v_R cos(delta)) acts at the rudder position: a positive
  angle pushes the stern to starboard (-y), so the bow turns to port going ahead (and the
  other way astern); with the rudder amidships it opposes the flow across the rudder, so a
  boat that drifts or yaws is turned back along its path (the rudder's share of the hull's
  directional stability, N_v and N_r). The lift is taken along the body's y axis (small
  drift angles) and has no drag. A skeg (``skeg_area``) at the same place adds the lift of
  the flow's angle alone, -1/2 rho C A_s V_R v_R. No speed, no steering. Sources: the seed
  notes, "Model A: Rudder Torque (Realistic)"; Fossen (2021), "Handbook of Marine Craft
  Hydrodynamics and Motion Control", 2nd ed., sec. 9.5 (alpha_R = delta - beta_R in its
  frame, y to starboard).
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

from boat_dynamics.physics.body.wrench import Real, Wrench, cross

__all__ = ["DEFAULT_LIFT_COEFFICIENT", "DEFAULT_MAX_ANGLE", "RUDDER_MODELS", "Rudder",
           "RudderModel", "rudder_wrench"]

RudderModel = Literal["lift", "torque", "hybrid", "none"]
RUDDER_MODELS: tuple[RudderModel, ...] = get_args(RudderModel)

#: rad, the default rudder range (35 deg either way).
DEFAULT_MAX_ANGLE = math.radians(35.0)

#: The default lift slope C, 1/rad: a rudder of aspect ratio about 1 against the hull's bottom
#: (its image in the hull doubles the effective aspect ratio to 2), by Whicker & Fehlner's
#: C_L,alpha = 0.9 * 2 pi AR / (1.8 + sqrt(AR^2 + 4)) = 2.44 at AR 2 (Molland & Turnock,
#: "Marine Rudders and Control Surfaces", 2007, sec. 3.3).
DEFAULT_LIFT_COEFFICIENT = 2.5


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
        skeg_area: A_s, m^2 (lift), a fixed fin at the rudder's position (a skeg, the lower
            unit of an outboard): the same lift at the flow's angle alone,
            -1/2 rho C A_s V_R v_R.
    """

    model: RudderModel = "lift"
    max_angle: Real = DEFAULT_MAX_ANGLE
    area: Real = 0.25
    lift_coefficient: Real = DEFAULT_LIFT_COEFFICIENT
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    max_torque: Real = 0.0
    base_torque: Real = 0.0
    max_speed: Real = 1.0
    skeg_area: Real = 0.0


def rudder_wrench(model: Rudder, angle, velocity, angular_velocity, water_density,
                  center_of_mass: np.ndarray) -> Wrench:
    """Rudder wrench about the centre of mass, body frame.

    Args:
        model: rudder parameters (numeric fields may be stacked per boat: (B,), (B, 3)).
        angle: delta, rad or (B,), + turns the bow to port.
        velocity: (..., 3) m/s, the body's velocity through the water at the centre of mass,
            body frame (``lift``: with ``angular_velocity``, the flow at the rudder;
            ``hybrid``: its surge part).
        angular_velocity: (..., 3) rad/s, body frame.
        water_density: rho, kg/m^3 or (B,).
        center_of_mass: (..., 3) m, body frame.

    Returns:
        The wrench, (..., 3) each.
    """
    angle = np.asarray(angle, dtype=float)
    velocity = np.asarray(velocity, dtype=float)
    shape = np.broadcast_shapes(angle.shape, velocity.shape[:-1],
                                np.shape(center_of_mass)[:-1])
    zero = np.zeros(shape)
    if model.model == "lift":
        if velocity.ndim == 2:  # a group of boats: compiled
            return _lift_compiled(model, angle, velocity, angular_velocity, water_density,
                                  center_of_mass)
        return _lift_numpy(model, angle, velocity, angular_velocity, water_density,
                           center_of_mass, zero)
    u = velocity[..., 0]
    fraction = angle / model.max_angle
    if model.model == "torque":
        yaw = np.asarray(model.max_torque) * fraction
    elif model.model == "hybrid":
        yaw = (np.asarray(model.base_torque)
               + np.asarray(model.max_torque) * np.abs(u) / model.max_speed) * fraction
    else:
        return Wrench(np.zeros((*shape, 3)), np.zeros((*shape, 3)))
    return Wrench(np.zeros((*shape, 3)), np.stack([zero, zero, zero + yaw], axis=-1))


def _lift_compiled(model: Rudder, angle: np.ndarray, velocity: np.ndarray, angular_velocity,
                   water_density, center_of_mass: np.ndarray) -> Wrench:
    """The ``lift`` model for (G, 3) velocities (``actuator_kernel.rudder_lift_f64``)."""
    from boat_dynamics.physics.force_models.actuator_kernel import rudder_lift_f64, stacked

    g = velocity.shape[0]
    return Wrench(*rudder_lift_f64(
        stacked(angle, g), stacked(velocity, g, 3), stacked(angular_velocity, g, 3),
        stacked(water_density, g), stacked(model.lift_coefficient, g), stacked(model.area, g),
        stacked(model.skeg_area, g), stacked(model.position, g, 3),
        stacked(center_of_mass, g, 3)))


def _lift_numpy(model: Rudder, angle: np.ndarray, velocity: np.ndarray, angular_velocity,
                water_density, center_of_mass: np.ndarray, zero: np.ndarray) -> Wrench:
    """The ``lift`` model in numpy (any shapes; the compiled kernel's oracle)."""
    arm = np.asarray(model.position) - center_of_mass
    local = velocity + cross(np.asarray(angular_velocity, dtype=float), arm)
    u, v = local[..., 0], local[..., 1]
    area, skeg = np.asarray(model.area), np.asarray(model.skeg_area)
    side = (-0.5 * np.asarray(water_density) * model.lift_coefficient * np.sqrt(u * u + v * v)
            * (area * (u * np.sin(angle) + v * np.cos(angle)) + skeg * v))
    force = np.stack([zero, zero + side, zero], axis=-1)
    return Wrench(force, cross(arm, force))
