"""A boat: parameters, state, inputs, the force sum and the step.

``step(params, state, inputs, sea, dt) -> state`` is a pure function over frozen dataclasses
(Gymnasium functional-env / brax pipeline style): this module only evaluates the force models
(one module each), sums them and integrates. It never imports rclpy.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from boat_dynamics.buoyancy import SamplePointBuoyancy, sample_point_buoyancy
from boat_dynamics.control import (
    ControlSettings,
    Pose,
    align_with_normal,
    apply_mode,
    pd_gains,
    stable_pd_torque,
)
from boat_dynamics.damping import damping
from boat_dynamics.hull import BoxHull
from boat_dynamics.hull_drag import hull_drag
from boat_dynamics.keel import reflect_off_keel
from boat_dynamics.mesh_buoyancy import MeshBuoyancy, mesh_buoyancy, submerged_triangles
from boat_dynamics.propulsion import Propulsion, lagged_throttle, thrust
from boat_dynamics.rigid_body import integrate, quat_from_euler, rotation_matrix
from boat_dynamics.rudder import Rudder, rudder_wrench
from boat_dynamics.wrench import Wrench, cross
from ocean_sim.constants import GRAVITY, WATER_DENSITY
from ocean_sim.waves import WaveField, sample_surface, stokes_drift

__all__ = [
    "BoatInputs",
    "BoatParams",
    "BoatState",
    "Forces",
    "evaluate_forces",
    "initial_state",
    "reference_pose",
    "step",
]


@dataclass(frozen=True)
class BoatParams:
    """Everything constant about one boat.

    Attributes:
        hull: the hull's bounding box (the hull itself for a box hull).
        mass: kg, > 0.
        center_of_mass: (3,) m, body frame, relative to the hull reference point.
        inertia: (3,) kg m^2, principal moments about the centre of mass (body axes).
        buoyancy: the buoyancy model: mesh (pressure on hull triangles) or sample points.
        damping_linear: (6,) N/(m/s) and N m/(rad/s), per body DOF.
        damping_quadratic: (6,) N/(m/s)^2 and N m/(rad/s)^2, per body DOF.
        added_mass: (6,) kg and kg m^2, per body DOF (diagonal).
        propulsion: the thruster.
        rudder: the rudder.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.
    """

    hull: BoxHull
    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    buoyancy: MeshBuoyancy | SamplePointBuoyancy
    damping_linear: np.ndarray
    damping_quadratic: np.ndarray
    added_mass: np.ndarray
    propulsion: Propulsion
    rudder: Rudder
    water_density: float = WATER_DENSITY
    gravity: float = GRAVITY
    min_wavelength: float = 0.0
    keel_rate: float = 0.0
    stokes_drift: bool = False
    control: ControlSettings = field(default_factory=ControlSettings)


@dataclass(frozen=True)
class BoatState:
    """The state of one boat at time ``t``.

    Attributes:
        t: s, simulation time.
        position: (3,) m, centre of mass, world frame (ENU).
        orientation: (4,) unit quaternion (x, y, z, w), body (FLU) to world.
        velocity: (3,) m/s, velocity of the centre of mass, body frame.
        angular_velocity: (3,) rad/s, body frame.
        throttle: -1..1, the actual thrust fraction (lags the command with a time constant).
        control_weight: 0..1, how far the control mode has taken over since it was selected.
    """

    t: float
    position: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    throttle: float = 0.0
    control_weight: float = 1.0


@dataclass(frozen=True)
class BoatInputs:
    """Actuator commands, already validated and within range.

    Attributes:
        throttle: -1..1, commanded fraction of max thrust (negative = reverse).
        rudder: rad, + turns the bow to port (rudder and/or steerable nozzle).
    """

    throttle: float = 0.0
    rudder: float = 0.0


@dataclass(frozen=True)
class Forces:
    """Every wrench acting on the boat, body frame, about the centre of mass.

    ``total`` is the net wrench (the sources plus gravity) that the integrator uses.
    """

    buoyancy: Wrench
    damping: Wrench
    drag: Wrench
    thrust: Wrench
    rudder: Wrench
    gravity: Wrench
    total: Wrench


def initial_state(
    params: BoatParams,
    position: np.ndarray,
    roll: float = 0.0,
    pitch: float = 0.0,
    yaw: float = 0.0,
    t: float = 0.0,
) -> BoatState:
    """State at rest with the hull reference point at ``position`` (m, world) and given attitude.

    Args:
        params: the boat.
        position: (3,) m, world position of the hull reference point.
        roll: rad.
        pitch: rad.
        yaw: rad.
        t: s.

    Returns:
        The state (centre of mass placed from the reference point and attitude).
    """
    q = quat_from_euler(roll, pitch, yaw)
    com = np.asarray(position, dtype=float) + rotation_matrix(q) @ params.center_of_mass
    return BoatState(t, com, q, np.zeros(3), np.zeros(3))


def reference_pose(params: BoatParams, state: BoatState) -> tuple[np.ndarray, np.ndarray]:
    """World position (3,) m of the hull reference point, and the orientation (4,)."""
    r = rotation_matrix(state.orientation)
    return state.position - r @ params.center_of_mass, state.orientation


def evaluate_forces(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField
) -> Forces:
    """Evaluate every force model at ``state`` and sum them.

    Args:
        params: the boat.
        state: its state.
        inputs: validated actuator commands.
        sea: the wave field.

    Returns:
        Each source's wrench and the total, body frame, about the centre of mass.
    """
    rot = rotation_matrix(state.orientation)
    com = params.center_of_mass
    ref = state.position - rot @ com
    model = params.buoyancy
    is_mesh = isinstance(model, MeshBuoyancy)
    pts_world = ref + (model.mesh.vertices if is_mesh else model.points) @ rot.T
    # One surface query: the hull vertices / sample points, then the hull reference point.
    query = np.vstack([pts_world[:, :2], ref[None, :2]])
    surface = sample_surface(sea, query, state.t, min_wavelength=params.min_wavelength)
    depths = surface.heights[:-1] - pts_world[:, 2]
    water_velocity = surface.velocities[-1]
    if params.stokes_drift:
        water_velocity = water_velocity + _stokes(sea.filtered(params.min_wavelength))
    relative_velocity = state.velocity - rot.T @ water_velocity

    drag = Wrench(np.zeros(3), np.zeros(3))
    if is_mesh:
        wet = submerged_triangles(model, pts_world, depths, rot)
        buoy = mesh_buoyancy(model, pts_world, depths, rot, state.position,
                             params.water_density, params.gravity, wet=wet)
        if model.drag.viscous or model.drag.pressure:
            omega_world = rot @ state.angular_velocity
            centroids = wet.corners.mean(axis=1)
            flow = (rot @ relative_velocity
                    + cross(omega_world, centroids - state.position))
            drag = hull_drag(model.drag, wet.corners, wet.normals, wet.areas, flow,
                             float(np.linalg.norm(relative_velocity)), params.hull.length,
                             params.water_density, state.position, rot)
    else:
        point_velocities = None
        if model.point_damping > 0.0:
            arms = model.points - com
            v_points = state.velocity + cross(state.angular_velocity, arms)
            point_velocities = v_points @ rot.T - surface.velocities[:-1]
        buoy = sample_point_buoyancy(model, depths, rot, com, params.water_density,
                                     params.gravity, normals=surface.normals[:-1],
                                     point_velocities=point_velocities, mass=params.mass)
    damp = damping(
        params.damping_linear, params.damping_quadratic, relative_velocity, state.angular_velocity
    )
    push = thrust(params.propulsion, state.throttle, inputs.rudder, com)
    steer = rudder_wrench(
        params.rudder, inputs.rudder, float(relative_velocity[0]), params.water_density, com
    )
    weight = Wrench(params.mass * params.gravity * -rot[2, :], np.zeros(3))
    total = buoy + damp + drag + push + steer + weight
    return Forces(buoy, damp, drag, push, steer, weight, total)


def step(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField, dt: float
) -> BoatState:
    """Advance one boat by ``dt`` seconds (semi-implicit Euler).

    Args:
        params: the boat.
        state: its state at time t.
        inputs: validated actuator commands, held over the step.
        sea: the wave field.
        dt: s, > 0.

    Returns:
        The state at t + dt.
    """
    throttle = lagged_throttle(params.propulsion, state.throttle, inputs.throttle, dt)
    state = replace(state, throttle=throttle)
    total = evaluate_forces(params, state, inputs, sea).total
    control = params.control
    torque = total.torque
    if control.mode == "kinematic" and control.attitude == "pd":
        normal = _surface_at_reference(params, state, sea, state.t).normals[0]
        kp, kd = pd_gains(control.pd_frequency, control.pd_damping)
        target = align_with_normal(state.orientation, normal)
        pd = stable_pd_torque(state.orientation, state.angular_velocity, target,
                              params.inertia, kp, kd, dt)
        torque = torque + pd * np.array([1.0, 1.0, 0.0])  # roll and pitch only
    p, q, v, w = integrate(
        state.position,
        state.orientation,
        state.velocity,
        state.angular_velocity,
        total.force,
        torque,
        params.mass + params.added_mass[:3],
        params.inertia + params.added_mass[3:],
        dt,
    )
    v = reflect_off_keel(v, params.keel_rate, dt)
    after = replace(state, t=state.t + dt, position=p, orientation=q, velocity=v,
                    angular_velocity=w)
    if control.mode == "dynamic":
        return after
    weight = 1.0 if control.transition <= 0 else min(1.0, state.control_weight
                                                       + dt / control.transition)
    surface = _surface_at_reference(params, after, sea, after.t)
    pose = apply_mode(control, _pose(params, state), _pose(params, after), weight,
                      float(surface.heights[0]), surface.normals[0],
                      float(surface.velocities[0, 2]), dt)
    rot = rotation_matrix(pose.orientation)
    return replace(after, position=pose.ref + rot @ params.center_of_mass,
                   orientation=pose.orientation, velocity=rot.T @ pose.velocity,
                   angular_velocity=pose.angular_velocity, control_weight=weight)


def _pose(params: BoatParams, state: BoatState) -> Pose:
    rot = rotation_matrix(state.orientation)
    return Pose(state.position - rot @ params.center_of_mass, state.orientation,
                rot @ state.velocity, state.angular_velocity)


def _surface_at_reference(params: BoatParams, state: BoatState, sea: WaveField, t: float):
    ref, _ = reference_pose(params, state)
    return sample_surface(sea, ref[None, :2], t, min_wavelength=params.min_wavelength)


def _stokes(sea: WaveField) -> np.ndarray:
    """(3,) m/s, the sea's surface Stokes drift (cached on the sea)."""
    key = ("stokes_drift",)
    if key not in sea._cache:
        sea._cache[key] = np.array([*stokes_drift(sea), 0.0])
    return sea._cache[key]
