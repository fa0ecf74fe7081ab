"""The rudder's lift and a thruster's push on a group of boats, compiled, boat by boat.

:func:`rudder_lift_f64` is the ``lift`` model of
:func:`boat_dynamics.physics.force_models.rudder.rudder_wrench` (F_y = -1/2 rho C V_R
(A (u_R sin delta + v_R cos delta) + A_s v_R) at the rudder; Fossen 2021, sec. 9.5);
:func:`thrust_f64` is :func:`boat_dynamics.physics.force_models.propulsion.thrust`. Their
numpy implementations (``rudder._lift_numpy``, ``propulsion._thrust_numpy``) are the tests'
oracles (within 1e-12 relative). The parameters come stacked per boat, as a group holds them.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["rudder_lift_f64", "stacked", "thrust_f64", "warm"]


@kernel
def rudder_lift_f64(angle, velocity, angular_velocity, density, lift_coefficient, area,
                    skeg_area, position, center_of_mass):  # pragma: no cover  (compiled)
    """(G, 3) N force and (G, 3) N m torque of the rudders, body frames, about the CoMs.

    Args:
        angle: (G,) rad, + turns the bow to port.
        velocity: (G, 3) m/s, through the water at the centres of mass, body frames.
        angular_velocity: (G, 3) rad/s, body frames.
        density: (G,) kg/m^3.
        lift_coefficient: (G,) 1/rad.
        area: (G,) m^2.
        skeg_area: (G,) m^2.
        position: (G, 3) m, the rudders, body frames (from the hull reference points).
        center_of_mass: (G, 3) m, body frames.
    """
    count = angle.shape[0]
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    for b in range(count):
        a0 = position[b, 0] - center_of_mass[b, 0]
        a1 = position[b, 1] - center_of_mass[b, 1]
        a2 = position[b, 2] - center_of_mass[b, 2]
        w0, w1, w2 = angular_velocity[b, 0], angular_velocity[b, 1], angular_velocity[b, 2]
        u = velocity[b, 0] + (w1 * a2 - w2 * a1)
        v = velocity[b, 1] + (w2 * a0 - w0 * a2)
        side = (-0.5 * density[b] * lift_coefficient[b] * math.sqrt(u * u + v * v)
                * (area[b] * (u * math.sin(angle[b]) + v * math.cos(angle[b]))
                   + skeg_area[b] * v))
        force[b, 1] = side
        torque[b, 0] = -a2 * side
        torque[b, 2] = a0 * side
    return force, torque


@kernel
def thrust_f64(throttle, nozzle_angle, max_thrust, direction, position, center_of_mass,
               steerable, at_center_of_mass):  # pragma: no cover  (compiled)
    """(G, 3) N force and (G, 3) N m torque of one thruster per boat, body frames.

    Args:
        throttle: (G,) -1..1, the actual fraction of max thrust.
        nozzle_angle: (G,) rad, the steering angle (a steerable thruster turns by -angle).
        max_thrust: (G,) N.
        direction: (G, 3) unit vectors, body frames, along positive throttle.
        position: (G, 3) m, application points, body frames.
        center_of_mass: (G, 3) m, body frames.
        steerable: the thruster turns with the angle.
        at_center_of_mass: applied at the centre of mass (no moment).
    """
    count = throttle.shape[0]
    force, torque = np.empty((count, 3)), np.zeros((count, 3))
    for b in range(count):
        d0, d1, d2 = direction[b, 0], direction[b, 1], direction[b, 2]
        if steerable:
            c, s = math.cos(-nozzle_angle[b]), math.sin(-nozzle_angle[b])
            d0, d1 = c * d0 - s * d1, s * d0 + c * d1
        magnitude = throttle[b] * max_thrust[b]
        f0, f1, f2 = magnitude * d0, magnitude * d1, magnitude * d2
        force[b, 0], force[b, 1], force[b, 2] = f0, f1, f2
        if not at_center_of_mass:
            a0 = position[b, 0] - center_of_mass[b, 0]
            a1 = position[b, 1] - center_of_mass[b, 1]
            a2 = position[b, 2] - center_of_mass[b, 2]
            torque[b, 0] = a1 * f2 - a2 * f1
            torque[b, 1] = a2 * f0 - a0 * f2
            torque[b, 2] = a0 * f1 - a1 * f0
    return force, torque


def stacked(value, count: int, width: int | None = None) -> np.ndarray:
    """``value`` as a C-contiguous float64 (count,) or (count, width) array for the kernels.

    A group's stacked parameter (already of that shape) is passed as it is; a scalar or a
    single vector (one boat's parameters, a shared value) is repeated for every boat.
    """
    shape = (count,) if width is None else (count, width)
    value = np.asarray(value, dtype=float)
    if value.shape == shape and value.flags.c_contiguous:
        return value
    return np.ascontiguousarray(np.broadcast_to(value, shape))


def warm() -> float:
    """Compile (or load from the cache) this module's kernels; returns the s it took."""
    start = time.perf_counter()
    one, three = np.ones(1), np.ones((1, 3))
    rudder_lift_f64(one, three, three, one, one, one, one, three, three)
    thrust_f64(one, one, one, three, three, three, True, False)
    return time.perf_counter() - start
