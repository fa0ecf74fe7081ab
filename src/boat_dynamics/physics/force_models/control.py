"""Control modes: how much of the boat's vertical motion and attitude physics decides.

The seed notes' "Dynamic vs kinematic" section, as modes applied after the dynamic step:

- ``dynamic`` (default): forces decide everything.
- ``kinematic``: the height follows the surface (plus the floating offset) and the attitude
  follows the surface normal, both with first-order smoothing (time constant ``smoothing``);
  with ``attitude: pd`` the attitude is driven instead by the stable backwards PD controller.
  Surge, sway and yaw stay dynamic (thrust, rudder, damping), so the boat is still driven.
- ``kinematic_heave``: kinematic height, dynamic rotation (buoyancy torques).
- ``constrained``: dynamic with the safety net: the height kept within ``depth_band`` of the
  floating height, the angular velocity clamped to ``max_angular_velocity``, and a rescue to
  the surface with zero vertical velocity when deeper than ``rescue_depth``.
- ``blend``: height = blend * dynamic + (1 - blend) * kinematic.

A mode switch never jumps: the mode's correction is ramped in over ``transition`` seconds
(``BoatState.control_weight`` goes 0 -> 1), and leaving a mode hands the current pose and
velocity to the dynamics unchanged.

The PD controller is David Wu's stable backwards PD ("Stable Backwards PD Controllers",
2011; the seed notes' listing): g = 1 / (1 + kd dt + kp dt^2), torque = I (kp g e +
(kd + kp dt) g e_dot). Gains: kp = (6 f)^2 / 4 as in the notes, and kd = 2 zeta sqrt(kp)
= 6 f zeta, which is critical at zeta = 1. The notes' kd = 4.5 f zeta gives an actual damping
ratio of 0.75 zeta (2.8 % overshoot at "critical"); it stays available as
``pd_gains(..., variant="notes")`` (tests measure both against the closed form).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_multiply, rotation_matrix

__all__ = [
    "ATTITUDES",
    "CONTROL_MODES",
    "Attitude",
    "ControlMode",
    "ControlSettings",
    "Pose",
    "align_with_normal",
    "apply_mode",
    "pd_gains",
    "slerp_toward",
    "stable_pd_torque",
    "world_rotation_rate",
]

#: How much of the vertical motion and attitude physics decides (see the module docstring).
ControlMode = Literal["dynamic", "kinematic", "kinematic_heave", "constrained", "blend"]
CONTROL_MODES: tuple[ControlMode, ...] = get_args(ControlMode)
#: How the kinematic mode sets the attitude: slerp toward the normal, or the PD torque.
Attitude = Literal["smooth", "pd"]
ATTITUDES: tuple[Attitude, ...] = get_args(Attitude)


@dataclass(frozen=True)
class ControlSettings:
    """Control-mode parameters of one boat.

    Attributes:
        mode: one of :data:`CONTROL_MODES`.
        height_offset: m, height of the hull reference point above the surface when floating
            (the flat-water equilibrium); kinematic modes track surface + this.
        smoothing: s, > 0, time constant of kinematic height and attitude tracking.
        attitude: ``smooth`` (slerp toward the normal) or ``pd`` (PD torque), kinematic mode.
        pd_frequency: Hz, bandwidth of the PD attitude controller.
        pd_damping: damping ratio of the PD controller (1 = critical).
        blend: weight of the dynamic height in ``blend`` mode, 0..1.
        depth_band: m, ``constrained``: largest distance from the floating height.
        max_angular_velocity: rad/s, ``constrained``: clamp of |angular velocity|.
        rescue_depth: m, ``constrained``: below surface - this, the boat is put back on top.
        transition: s, time over which a newly selected mode takes over.
    """

    mode: ControlMode = "dynamic"
    height_offset: float = 0.0
    smoothing: float = 0.3
    attitude: Attitude = "smooth"
    pd_frequency: float = 1.0
    pd_damping: float = 1.0
    blend: float = 0.7
    depth_band: float = 1.0
    max_angular_velocity: float = 3.0
    rescue_depth: float = 3.0
    transition: float = 1.0


def pd_gains(frequency: float, damping: float, variant: str = "critical"
             ) -> tuple[float, float]:
    """(kp, kd) for a bandwidth ``frequency`` (Hz) and damping ratio ``damping``.

    kp = (6 f)^2 / 4 (the seed notes); kd = 2 zeta sqrt(kp) = 6 f zeta (``critical``: the
    damping ratio really is zeta), or the notes' kd = 4.5 f zeta (``notes``: 0.75 zeta).
    """
    kp = (6.0 * frequency) ** 2 * 0.25
    if variant == "notes":
        return kp, 4.5 * frequency * damping
    if variant != "critical":
        raise ValueError(f"variant {variant!r} is not allowed: 'critical' or 'notes'")
    return kp, 2.0 * damping * math.sqrt(kp)


def _quat_conjugate(q: np.ndarray) -> np.ndarray:
    return np.array([-q[0], -q[1], -q[2], q[3]])


def _rotation_vector(q: np.ndarray) -> np.ndarray:
    """Axis * angle (rad) of a unit quaternion, angle in [-pi, pi]."""
    if q[3] < 0.0:
        q = -q
    s = float(np.linalg.norm(q[:3]))
    if s < 1e-12:
        return 2.0 * q[:3]
    return q[:3] / s * 2.0 * math.atan2(s, q[3])


def _quat_from_rotation_vector(v: np.ndarray) -> np.ndarray:
    angle = float(np.linalg.norm(v))
    if angle < 1e-12:
        q = np.array([*(0.5 * v), 1.0])
        return q / np.linalg.norm(q)
    return np.array([*(v / angle * math.sin(angle / 2)), math.cos(angle / 2)])


def align_with_normal(q: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The orientation nearest to ``q`` whose body z axis is ``normal`` (heading kept).

    The shortest rotation taking the current body z axis onto the normal, applied to ``q``.
    """
    z = rotation_matrix(q)[:, 2]
    axis = np.cross(z, normal)
    s = float(np.linalg.norm(axis))
    c = float(np.dot(z, normal))
    if s < 1e-12:
        return q if c > 0 else quat_multiply(np.array([1.0, 0.0, 0.0, 0.0]), q)
    rot = _quat_from_rotation_vector(axis / s * math.atan2(s, c))
    return quat_multiply(rot, q)


def stable_pd_torque(q: np.ndarray, angular_velocity: np.ndarray, q_target: np.ndarray,
                     inertia: np.ndarray, kp: float, kd: float, dt: float) -> np.ndarray:
    """Stable backwards PD torque (3,) N m, body frame, toward ``q_target`` (at rest).

    Args:
        q: (4,) current orientation.
        angular_velocity: (3,) rad/s, body frame.
        q_target: (4,) target orientation.
        inertia: (3,) kg m^2, principal moments (body axes).
        kp: 1/s^2, proportional gain.
        kd: 1/s, derivative gain.
        dt: s, the step the torque is held for.
    """
    g = 1.0 / (1.0 + kd * dt + kp * dt * dt)
    ksg, kdg = kp * g, (kd + kp * dt) * g
    error_world = _rotation_vector(quat_multiply(q_target, _quat_conjugate(q)))
    error_body = rotation_matrix(q).T @ error_world
    return inertia * (ksg * error_body - kdg * angular_velocity)


def slerp_toward(q: np.ndarray, target: np.ndarray, fraction: float) -> np.ndarray:
    """Rotate ``q`` by ``fraction`` of the way to ``target`` (shortest arc)."""
    delta = _rotation_vector(quat_multiply(target, _quat_conjugate(q)))
    out = quat_multiply(_quat_from_rotation_vector(fraction * delta), q)
    return out / np.linalg.norm(out)


def world_rotation_rate(q_from: np.ndarray, q_to: np.ndarray, dt: float) -> np.ndarray:
    """(3,) rad/s, world-frame angular velocity taking q_from to q_to in dt."""
    return _rotation_vector(quat_multiply(q_to, _quat_conjugate(q_from))) / dt


@dataclass(frozen=True)
class Pose:
    """A boat's kinematic state as the control modes see it (world frame).

    Attributes:
        ref: (3,) m, hull reference point.
        orientation: (4,) unit quaternion.
        velocity: (3,) m/s, world velocity of the centre of mass.
        angular_velocity: (3,) rad/s, body frame.
    """

    ref: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray


def apply_mode(settings: ControlSettings, before: Pose, after: Pose, weight: float,
               surface_height: float, surface_normal: np.ndarray, water_vz: float,
               dt: float) -> Pose:
    """Correct the dynamic step ``before`` -> ``after`` according to the control mode.

    Args:
        settings: the boat's control settings.
        before: the pose at the start of the step.
        after: the pose the dynamics produced.
        weight: 0..1, how far the mode has taken over since it was selected.
        surface_height: m, surface height at the reference point after the step.
        surface_normal: (3,) unit surface normal there.
        water_vz: m/s, vertical velocity of the surface water there.
        dt: s.

    Returns:
        The corrected pose (``after`` itself in dynamic mode).
    """
    mode = settings.mode
    if mode == "dynamic":
        return after
    ref, q = after.ref.copy(), after.orientation
    v, w = after.velocity.copy(), after.angular_velocity.copy()
    floating = surface_height + settings.height_offset
    alpha = 1.0 - math.exp(-dt / settings.smoothing)
    if mode in ("kinematic", "kinematic_heave"):
        z_kin = before.ref[2] + alpha * (floating - before.ref[2])
        vz_kin = (z_kin - before.ref[2]) / dt
        ref[2] += weight * (z_kin - ref[2])
        v[2] += weight * (vz_kin - v[2])
    if mode == "kinematic" and settings.attitude == "smooth":
        q_kin = slerp_toward(q, align_with_normal(q, surface_normal), alpha)
        w_kin = rotation_matrix(q_kin).T @ world_rotation_rate(before.orientation, q_kin, dt)
        q = slerp_toward(q, q_kin, weight)
        w = w + weight * (w_kin - w)
    if mode == "blend":
        z_mix = settings.blend * ref[2] + (1.0 - settings.blend) * floating
        vz_mix = settings.blend * v[2] + (1.0 - settings.blend) * water_vz
        ref[2] += weight * (z_mix - ref[2])
        v[2] += weight * (vz_mix - v[2])
    if mode == "constrained":
        speed = float(np.linalg.norm(w))
        if speed > settings.max_angular_velocity:
            w = w * (settings.max_angular_velocity / speed)
        if ref[2] < surface_height - settings.rescue_depth:
            ref[2], v[2] = floating, 0.0  # rescue: back on top, no vertical velocity
        elif abs(ref[2] - floating) > settings.depth_band:
            side = math.copysign(1.0, ref[2] - floating)
            ref[2] = floating + side * settings.depth_band
            if v[2] * side > 0.0:
                v[2] = 0.0
    return Pose(ref, q, v, w)
