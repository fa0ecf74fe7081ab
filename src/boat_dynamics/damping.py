"""Hydrodynamic damping per degree of freedom, body frame: linear + quadratic.

    F   = -(D_lin[0:3] + D_quad[0:3] |v_rel|) * v_rel
    tau = -(D_lin[3:6] + D_quad[3:6] |w|)     * w

where v_rel is the body velocity relative to the surface water particle (element-wise per
DOF). Source: Fossen (2011), eqs. 6.54 and 6.59 (diagonal linear and quadratic damping); the
seed notes, "Damping" (b v and 1/2 rho Cd A |v| v).
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.wrench import Wrench

__all__ = ["damping"]


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
