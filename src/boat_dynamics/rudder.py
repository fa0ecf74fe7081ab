"""Rudder: a lifting surface at the stern.

    F_y = -1/2 rho C A u|u| sin(delta),  applied at the rudder position (stern)

``u`` is the surge speed through the water. A positive angle pushes the stern to starboard
(-y), so the bow turns to port (+yaw, counter-clockwise seen from above) when going ahead, and
the other way when going astern. No speed, no steering: the physically based model.
Source: the seed notes, "Model A: Rudder Torque (Realistic)"; Fossen (2011), sec. 9.5.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.wrench import Wrench, wrench_at

__all__ = ["LiftRudder", "rudder_lift"]


@dataclass(frozen=True)
class LiftRudder:
    """Lift-type rudder parameters.

    Attributes:
        area: A, m^2, > 0.
        lift_coefficient: C, dimensionless, > 0.
        position: (3,) m, body frame (relative to the hull reference point), at the stern.
        max_angle: rad, the command range is [-max_angle, max_angle].

    """

    area: float
    lift_coefficient: float
    position: np.ndarray
    max_angle: float


def rudder_lift(
    model: LiftRudder,
    angle: float,
    surge_speed: float,
    water_density: float,
    center_of_mass: np.ndarray,
) -> Wrench:
    """Rudder side-force wrench.

    Args:
        model: rudder parameters.
        angle: delta, rad, + turns the bow to port.
        surge_speed: u, m/s, body-x speed through the water.
        water_density: rho, kg/m^3.
        center_of_mass: (3,) m, body frame.

    Returns:
        The rudder wrench about the centre of mass, body frame.

    """
    side = -0.5 * water_density * model.lift_coefficient * model.area
    side *= surge_speed * abs(surge_speed) * np.sin(angle)
    return wrench_at(np.array([0.0, side, 0.0]), model.position - center_of_mass)
