"""The added mass at forward speed in the horizontal plane: the Munk moment and its kin.

A boat with potential-flow coefficients carries the infinite-frequency added mass A (6 x 6,
about the centre of mass, body axes) in its mass matrix
(:func:`boat_dynamics.physics.body.rigid_body.integrate_coupled`) and feels its own waves through
the Cummins memory (:mod:`.radiation`), both derived at zero speed. Its equations are written
in the body frame, where the fluid momentum A nu turns with the hull; that costs the force
Q(nu) = -C_A(nu) nu with the skew-symmetric C_A of Kirchhoff's equations (Sagatun & Fossen
1991; Fossen 2011, "Handbook of Marine Craft Hydrodynamics and Motion Control", eqs.
6.43-6.44)::

    Q(nu) = [a1 x w,  a1 x v + a2 x w],   a1 = A11 v + A12 w,  a2 = A21 v + A22 w

(3 x 3 blocks of A), which does no work. :func:`added_mass_coriolis` applies it to the
horizontal-plane motion (surge, sway, yaw), the manoeuvring terms: for nu = (u, v, r),
X = A22 v r + A26 r^2, Y = -A11 u r, N = (A11 - A22) u v - A26 u r. The Munk moment
N = -(A22 - A11) u v turns a hull broadside to its path (the hull's and the rudder's lift
keep a course-stable boat straight: :mod:`.hull_lift`, :mod:`.rudder`), and Y = -A11 u r is
the added mass's share of the centripetal force in a turn. Newman (1977), "Marine
Hydrodynamics", sec. 4.13; Fossen 2005, "A nonlinear unified state-space model for ship
maneuvering and control in a seaway" (the manoeuvring model's C_A(nu) beside the seakeeping
memory).

Left out, stated: Q of the heave, roll and pitch motion. Its part linear in the speed U (heave
U A11 q, pitch U (A33 - A11) w: slender-body theory's speed terms in the body frame) does the
work U A33 w q, which its quadratic part returns as the surge force -A33 w q (the radiated
waves' added resistance); with A_inf in place of A(omega) the two together slowed the default
box driven into its sea from 3.9 to 1.7 m/s, and the linear part alone pitched it to 39 deg in
a following sea. Without them, the body-frame Cummins equation still
carries strip theory's heave-from-pitch speed terms (:mod:`.seakeeping`), and Journee's (1992)
Wigley I and III towed at Fn 0.2 and 0.3 heave within 20 % of the towing tank
(tests/boat_dynamics/physics/experiments/test_towing_tank.py); no pitch was measured at speed, so
the pitch-from-heave (Munk) terms stay out until a measurement says what they change.
The velocity is the hull's relative to the current, not to the waves' orbital motion (the
wave-body interaction is the Froude-Krylov, diffraction and radiation forces).
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench, cross

__all__ = ["added_mass_coriolis", "kirchhoff"]

#: Which of (surge, sway, heave, roll, pitch, yaw) are the horizontal plane.
_HORIZONTAL = np.array([1.0, 1.0, 0.0, 0.0, 0.0, 1.0])


def kirchhoff(added_mass: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """(B, 6) Q(nu) = -C_A(nu) nu, force then torque (module docstring).

    Args:
        added_mass: (B, 6, 6) kg, kg m, kg m^2, about the centres of mass, body axes.
        nu: (B, 6) m/s and rad/s, body frame: [v, w].
    """
    momentum = np.einsum("bij,bj->bi", added_mass, nu)
    a1, a2, v, w = momentum[:, :3], momentum[:, 3:], nu[:, :3], nu[:, 3:]
    return np.concatenate([cross(a1, w), cross(a1, v) + cross(a2, w)], axis=1)


def added_mass_coriolis(added_mass: np.ndarray, velocity: np.ndarray,
                        angular_velocity: np.ndarray, carried: np.ndarray | None = None
                        ) -> Wrench:
    """Q of the horizontal-plane motion (surge, sway, yaw), on those three dofs.

    Compiled (:func:`.memory_kernel.kirchhoff_f64`; ``_added_mass_coriolis_numpy`` its oracle).

    Args:
        added_mass: (B, 6, 6) kg, kg m, kg m^2.
        velocity: (B, 3) m/s, body frame, relative to the current.
        angular_velocity: (B, 3) rad/s, body frame.
        carried: (B,) in [0, 1], the share of ``added_mass`` each hull carries; None: 1.

    Returns:
        (B, 3) N and (B, 3) N m, body frame, about the centres of mass.
    """
    from boat_dynamics.physics.potential_flow.memory_kernel import kirchhoff_f64

    added = np.ascontiguousarray(added_mass, dtype=float)
    share = np.ones(added.shape[0]) if carried is None else np.asarray(carried, dtype=float)
    return Wrench(*kirchhoff_f64(added, share, np.ascontiguousarray(velocity, dtype=float),
                                 np.ascontiguousarray(angular_velocity, dtype=float)))


def _added_mass_coriolis_numpy(added_mass: np.ndarray, velocity: np.ndarray,
                               angular_velocity: np.ndarray) -> Wrench:
    """:func:`added_mass_coriolis` in numpy: the compiled kernel's oracle."""
    nu = np.concatenate([velocity, angular_velocity], axis=1) * _HORIZONTAL
    q = kirchhoff(added_mass, nu) * _HORIZONTAL
    return Wrench(q[:, :3], q[:, 3:])
