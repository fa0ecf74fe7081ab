"""Hydrodynamic damping per degree of freedom, body frame: linear + quadratic.

    F   = -(D_lin[0:3] + D_quad[0:3] |v_rel|) * v_rel
    tau = -(D_lin[3:6] + D_quad[3:6] |w|)     * w

where v_rel is the body velocity relative to the surface water particle (element-wise per
DOF). Source: Fossen (2011), eqs. 6.54 and 6.59 (diagonal linear and quadratic damping); the
seed notes, "Damping" (b v and 1/2 rho Cd A |v| v).

The seed notes' game-engine damping is also here, as an option: not a force but a decay of the
velocities after each step, v <- v / (1 + dt c) per body DOF (Unity's drag and angularDrag;
the notes' per-axis form v (1 - c dt) is its first order). It is exact exponential decay
only as dt -> 0 and acts on the velocity over ground, not through the water.
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench

__all__ = ["damping", "radiation_damping", "velocity_decay"]


def damping(
    linear: np.ndarray, quadratic: np.ndarray, velocity: np.ndarray, angular_velocity: np.ndarray
) -> Wrench:
    """Damping wrench.

    Args:
        linear: (..., 6) [surge, sway, heave] N/(m/s) and [roll, pitch, yaw] N m/(rad/s).
        quadratic: (..., 6) N/(m/s)^2 and N m/(rad/s)^2.
        velocity: (..., 3) m/s, body velocity relative to the water, body frame.
        angular_velocity: (..., 3) rad/s, body frame.

    The leading axes (``...``) are boats.

    Returns:
        The damping wrench, body frame, about the centre of mass, (..., 3) each.
    """
    force = -(linear[..., :3] + quadratic[..., :3] * np.abs(velocity)) * velocity
    torque = -(linear[..., 3:] + quadratic[..., 3:] * np.abs(angular_velocity)) * angular_velocity
    return Wrench(force, torque)


def radiation_damping(coefficients: np.ndarray, velocity: np.ndarray,
                      angular_velocity: np.ndarray) -> Wrench:
    """Wave radiation damping: -B v on the body's own velocity, not relative to the water.

    The waves a moving hull makes carry energy away whatever the water around it does, so this
    force acts on the velocity over ground (Newman 1977, sec. 6.12; WEC-Sim's radiation
    damping); linear damping relative to the water would instead be driven by the waves'
    orbital velocity, which in short waves is larger than their true excitation.

    Args:
        coefficients: (..., 6) N/(m/s) and N m/(rad/s), B_ii per body dof.
        velocity: (..., 3) m/s, body velocity over ground, body frame.
        angular_velocity: (..., 3) rad/s, body frame.
    """
    return Wrench(-coefficients[..., :3] * velocity, -coefficients[..., 3:] * angular_velocity)


def velocity_decay(velocity: np.ndarray, angular_velocity: np.ndarray, rates: np.ndarray,
                   dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocities after one step of the notes' decay, v / (1 + dt c) per DOF.

    Args:
        velocity: (..., 3) m/s, body frame.
        angular_velocity: (..., 3) rad/s, body frame.
        rates: (..., 6) 1/s, c per DOF [surge, sway, heave, roll, pitch, yaw].
        dt: s.
    """
    return (velocity / (1.0 + dt * rates[..., :3]),
            angular_velocity / (1.0 + dt * rates[..., 3:]))
