"""Control modes over a fleet: the boats not in ``dynamic`` mode, corrected after the step.

The modes themselves (one boat's pose correction, the PD attitude controller) are
:mod:`boat_dynamics.physics.force_models.control`; here they are applied to the boats of a
:class:`~boat_dynamics.physics.core.system.System` that need them (rare, arcade), boat by boat.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.system import FleetState, System
from boat_dynamics.physics.force_models.control import (
    Pose,
    align_with_normal,
    apply_mode,
    pd_gains,
    stable_pd_torque,
)
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["apply_modes", "pd_torques"]


def pd_torques(system: System, state: FleetState, torque: np.ndarray, normals: np.ndarray,
               dt: float) -> np.ndarray:
    """``torque`` plus the PD attitude torque of the boats in ``kinematic`` mode with ``pd``.

    Args:
        system: the boats.
        state: their state at the start of the step.
        torque: (B, 3) N m, the total torques of the forces, body frames.
        normals: (B, 3) surface normals at the hull reference points, world frame.
        dt: s.

    Returns:
        (B, 3) N m; ``torque`` itself when no boat has a PD controller.
    """
    pd = [i for i in system.special if system.params[i].control.mode == "kinematic"
          and system.params[i].control.attitude == "pd"]
    if not pd:
        return torque
    torque = torque.copy()
    for i in pd:
        torque[i] += _pd_torque(system.params[i], state, i, normals[i], dt)
    return torque


def _pd_torque(params: BoatParams, state: FleetState, i: int, normal: np.ndarray,
               dt: float) -> np.ndarray:
    """Roll and pitch torque of the stable PD attitude controller (kinematic, attitude: pd)."""
    control = params.control
    kp, kd = pd_gains(control.pd_frequency, control.pd_damping)
    target = align_with_normal(state.orientation[i], normal)
    pd = stable_pd_torque(state.orientation[i], state.angular_velocity[i], target,
                          params.inertia, kp, kd, dt)
    return pd * np.array([1.0, 1.0, 0.0])


def apply_modes(system: System, before: FleetState, after: FleetState, sea: WaveField,
                dt: float) -> FleetState:
    """``after`` with the control modes of the boats not in ``dynamic`` mode applied.

    Args:
        system: the boats.
        before: their state at the start of the step.
        after: the dynamic step's result.
        sea: the wave field (each boat's own surface query at its new reference point).
        dt: s.

    Returns:
        The corrected state (``after`` itself when every boat is dynamic).
    """
    if not system.special:
        return after
    p, q = after.position.copy(), after.orientation.copy()
    v, w = after.velocity.copy(), after.angular_velocity.copy()
    weights = after.control_weight.copy()
    for i in system.special:
        params = system.params[i]
        control = params.control
        weight = 1.0 if control.transition <= 0 else min(1.0, before.control_weight[i]
                                                           + dt / control.transition)
        pose_after = _pose(params, after, i)
        surface = sample_surface(sea, pose_after.ref[None, :2], after.t,
                                 min_wavelength=params.min_wavelength,
                                 precision=params.wave_precision)
        pose = apply_mode(control, _pose(params, before, i), pose_after, weight,
                          float(surface.heights[0]), surface.normals[0],
                          float(surface.velocities[0, 2]), dt)
        rot = rotation_matrix(pose.orientation)
        p[i] = pose.ref + rot @ params.center_of_mass
        q[i], v[i], w[i] = pose.orientation, rot.T @ pose.velocity, pose.angular_velocity
        weights[i] = weight
    return replace(after, position=p, orientation=q, velocity=v, angular_velocity=w,
                   control_weight=weights)


def _pose(params: BoatParams, state: FleetState, i: int) -> Pose:
    rot = rotation_matrix(state.orientation[i])
    return Pose(state.position[i] - rot @ params.center_of_mass, state.orientation[i],
                rot @ state.velocity[i], state.angular_velocity[i])
