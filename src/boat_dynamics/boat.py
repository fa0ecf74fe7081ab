"""A boat: parameters, state, inputs, the force sum and the step.

``step(params, state, inputs, sea, dt) -> state`` is a pure function over frozen dataclasses
(Gymnasium functional-env / brax pipeline style): this module only evaluates the force models
(one module each), sums them and integrates. It never imports rclpy.
"""

from __future__ import annotations

from collections.abc import Sequence
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
from ocean_sim.waves import SurfaceSample, WaveField, sample_surface, stokes_drift

__all__ = [
    "BoatInputs",
    "BoatParams",
    "BoatState",
    "Forces",
    "SurfaceQuery",
    "evaluate_forces",
    "forces_on_surface",
    "initial_state",
    "reference_pose",
    "step",
    "step_many",
    "surface_query",
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
    query = surface_query(params, state)
    surface = sample_surface(sea, query.xy, state.t, min_wavelength=params.min_wavelength)
    return forces_on_surface(params, state, inputs, sea, query, surface)


@dataclass(frozen=True)
class SurfaceQuery:
    """Where a boat needs the surface: its hull vertices or sample points, then its reference.

    Attributes:
        rotation: (3, 3) body-to-world rotation.
        points: (N, 3) m, hull vertices / sample points, world frame.
        xy: (N + 1, 2) m, their horizontal positions and the hull reference point's.
    """

    rotation: np.ndarray
    points: np.ndarray
    xy: np.ndarray


def surface_query(params: BoatParams, state: BoatState) -> SurfaceQuery:
    """The points at which :func:`forces_on_surface` needs the water surface."""
    rot = rotation_matrix(state.orientation)
    ref = state.position - rot @ params.center_of_mass
    model = params.buoyancy
    body = model.mesh.vertices if isinstance(model, MeshBuoyancy) else model.points
    pts_world = ref + body @ rot.T
    return SurfaceQuery(rot, pts_world, np.vstack([pts_world[:, :2], ref[None, :2]]))


def forces_on_surface(params: BoatParams, state: BoatState, inputs: BoatInputs,
                      sea: WaveField, query: SurfaceQuery, surface: SurfaceSample) -> Forces:
    """Every force model's wrench, given the surface at the query points (see evaluate_forces).

    Args:
        params: the boat.
        state: its state.
        inputs: validated actuator commands.
        sea: the wave field (for the Stokes drift option).
        query: from :func:`surface_query`.
        surface: the surface at ``query.xy`` and time ``state.t``.
    """
    rot, pts_world = query.rotation, query.points
    com = params.center_of_mass
    model = params.buoyancy
    is_mesh = isinstance(model, MeshBuoyancy)
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
    return step_many([params], [state], [inputs], sea, dt)[0][0]


def step_many(params: Sequence[BoatParams], states: Sequence[BoatState],
              inputs: Sequence[BoatInputs], sea: WaveField, dt: float
              ) -> list[tuple[BoatState, Forces]]:
    """Advance several boats by ``dt`` s, with one surface query for all of them.

    Boats sharing a ``min_wavelength`` (usually all) share one :func:`sample_surface` call, so
    its per-call cost is paid once per step instead of once per boat. Each boat is otherwise
    exactly :func:`step` (the forces differ from a lone query by rounding only, about 1e-15
    relative, because the phase reduction is centred on the whole batch).

    Returns:
        For each boat, its state at t + dt and the forces that acted during the step.
    """
    prepared = []
    for p, s, u in zip(params, states, inputs, strict=True):
        s = replace(s, throttle=lagged_throttle(p.propulsion, s.throttle, u.throttle, dt))
        prepared.append((p, s, u, surface_query(p, s)))
    surfaces = _batched_surfaces(prepared, sea)
    out = []
    for (p, s, u, query), surface in zip(prepared, surfaces, strict=True):
        forces = forces_on_surface(p, s, u, sea, query, surface)
        out.append((_integrate_boat(p, s, sea, forces.total, surface.normals[-1], dt), forces))
    return out


def _batched_surfaces(prepared: list, sea: WaveField) -> list[SurfaceSample]:
    """One sample_surface per (time, min_wavelength) group; results split back per boat."""
    groups: dict[tuple[float, float], list[int]] = {}
    for i, (p, s, _, _) in enumerate(prepared):
        groups.setdefault((s.t, p.min_wavelength), []).append(i)
    out: list[SurfaceSample | None] = [None] * len(prepared)
    for (t, min_wavelength), members in groups.items():
        xy = np.vstack([prepared[i][3].xy for i in members])
        surface = sample_surface(sea, xy, t, min_wavelength=min_wavelength)
        start = 0
        for i in members:
            n = prepared[i][3].xy.shape[0]
            rows = slice(start, start + n)
            out[i] = SurfaceSample(surface.heights[rows], surface.normals[rows],
                                   surface.velocities[rows], surface.accelerations[rows],
                                   surface.rest_xy[rows])
            start += n
    return out


def _integrate_boat(params: BoatParams, state: BoatState, sea: WaveField, total: Wrench,
                    normal: np.ndarray, dt: float) -> BoatState:
    """Integrate one boat under ``total``, then apply its keel and control mode.

    ``normal`` is the surface normal at the hull reference point at the start of the step.
    """
    control = params.control
    torque = total.torque
    if control.mode == "kinematic" and control.attitude == "pd":
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
