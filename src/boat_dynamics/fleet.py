"""Many boats stepped as one: every force model evaluated with numpy over all boats at once.

A boat step costs a few hundred numpy calls whatever the boat; called per boat, their fixed
cost (about 1-3 us each) dominates. Here boats that take the same code path (same buoyancy
model and options, thruster and rudder kinds, ...) form a *group* whose parameters are stacked
((B,) and (B, 3) arrays) and whose hull triangles or sample points are concatenated, each
element tagged with its boat (``owner``); per-boat sums come from ``wrench.sum_by_owner``. The
rigid-body integration runs once over the whole fleet. Control modes other than ``dynamic``
(rare, arcade) are applied boat by boat after the integration.

:func:`boat_dynamics.boat.step`, ``step_many`` and ``evaluate_forces`` are this module with
one or several boats: there is one implementation of the physics.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.buoyancy import SamplePointBuoyancy, sample_point_wrenches
from boat_dynamics.control import Pose as _Pose
from boat_dynamics.control import align_with_normal, apply_mode, pd_gains, stable_pd_torque
from boat_dynamics.damping import damping, velocity_decay
from boat_dynamics.hull_drag import hull_drag
from boat_dynamics.keel import reflect_off_keel
from boat_dynamics.mesh_buoyancy import (
    MeshBuoyancy,
    SubmergedTriangles,
    clip_hulls,
    pressure_wrenches,
)
from boat_dynamics.model import BoatInputs, BoatParams, BoatState, Forces
from boat_dynamics.propulsion import lagged_throttle, thrust
from boat_dynamics.rigid_body import integrate, rotation_matrix
from boat_dynamics.rudder import rudder_wrench
from boat_dynamics.wrench import Wrench, cross
from ocean_sim.waves import (
    SurfaceSample,
    WaveField,
    sample_surface,
    slope_orbit_velocity,
    stokes_drift,
)

__all__ = [
    "Contact",
    "Fleet",
    "FleetForces",
    "FleetInputs",
    "FleetState",
    "contacts",
    "fleet_afloat",
    "fleet_forces",
    "fleet_step",
    "reference_points",
]

@dataclass(frozen=True)
class FleetState:
    """The states of B boats at one time ``t``.

    Attributes:
        t: s, simulation time (shared).
        position: (B, 3) m, centres of mass, world frame (ENU).
        orientation: (B, 4) unit quaternions (x, y, z, w), body (FLU) to world.
        velocity: (B, 3) m/s, body frame.
        angular_velocity: (B, 3) rad/s, body frame.
        throttle: (B,) actual thrust fractions.
        control_weight: (B,) 0..1, how far each control mode has taken over.
    """

    t: float
    position: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    throttle: np.ndarray
    control_weight: np.ndarray

    @classmethod
    def stack(cls, states: Sequence[BoatState]) -> FleetState:
        """The fleet state of boats that share a time (raises ValueError otherwise)."""
        times = {s.t for s in states}
        if len(times) != 1:
            raise ValueError(f"a fleet steps boats at one time; got times {sorted(times)}")
        return cls(states[0].t, np.array([s.position for s in states], dtype=float),
                   np.array([s.orientation for s in states], dtype=float),
                   np.array([s.velocity for s in states], dtype=float),
                   np.array([s.angular_velocity for s in states], dtype=float),
                   np.array([s.throttle for s in states], dtype=float),
                   np.array([s.control_weight for s in states], dtype=float))

    def boat(self, i: int) -> BoatState:
        """Boat ``i``'s state (arrays are copies: the fleet state stays frozen)."""
        return BoatState(self.t, self.position[i].copy(), self.orientation[i].copy(),
                         self.velocity[i].copy(), self.angular_velocity[i].copy(),
                         float(self.throttle[i]), float(self.control_weight[i]))


@dataclass(frozen=True)
class FleetInputs:
    """Validated commands of B boats: (B,) throttle fractions and (B,) rudder angles, rad."""

    throttle: np.ndarray
    rudder: np.ndarray

    @classmethod
    def stack(cls, inputs: Sequence[BoatInputs]) -> FleetInputs:
        """From one BoatInputs per boat."""
        return cls(np.array([u.throttle for u in inputs], dtype=float),
                   np.array([u.rudder for u in inputs], dtype=float))


@dataclass(frozen=True)
class FleetForces(Forces):
    """:class:`~boat_dynamics.model.Forces` of B boats: each wrench holds (B, 3) arrays."""

    def boat(self, i: int) -> Forces:
        """Boat ``i``'s forces."""
        return Forces(*(Wrench(w.force[i].copy(), w.torque[i].copy())
                        for w in (getattr(self, f.name) for f in dataclasses.fields(self))))


def _structure(obj) -> tuple:
    """The non-numeric fields of a parameter dataclass: what decides its code path."""
    out = []
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        if value is None or isinstance(value, bool | str):
            out.append((f.name, value))
        elif dataclasses.is_dataclass(value):
            out.append((f.name, _structure(value)))
    return tuple(out)


def _stack(items: Sequence, skip: tuple[str, ...] = ()):
    """One dataclass whose numeric fields are the items' values stacked along a first axis.

    Non-numeric fields (equal across the items: they are part of the group key) are kept.
    """
    first = items[0]
    changes = {}
    for f in dataclasses.fields(first):
        value = getattr(first, f.name)
        if f.name in skip or value is None or isinstance(value, bool | str):
            continue
        if dataclasses.is_dataclass(value):
            changes[f.name] = _stack([getattr(i, f.name) for i in items])
        else:
            changes[f.name] = np.array([getattr(i, f.name) for i in items], dtype=float)
    return replace(first, **changes)


def _group_key(p: BoatParams) -> tuple:
    b = p.buoyancy
    kind = "mesh" if isinstance(b, MeshBuoyancy) else "points"
    return (kind, _structure(b), _structure(p.propulsion), _structure(p.rudder),
            p.stokes_drift, p.min_wavelength, p.wave_precision)


@dataclass(frozen=True)
class _Group:
    """Boats that take the same code path, their parameters stacked.

    Attributes:
        index: (G,) int, the boats' places in the fleet.
        mesh: the buoyancy parameters (first boat's; ``drag`` stacked) for a mesh group.
        points: the sample-point parameters, numeric fields stacked and ``points``
            concatenated, for a sample-point group.
        body: (E, 3) m, hull vertices or sample points of every boat, body frames.
        owner: (E,) int, the boat (0..G-1) of each vertex / point.
        faces: (F, 3) int, mesh triangles indexing ``body`` (mesh group).
        face_owner: (F,) int, the boat of each triangle (mesh group).
        propulsion: stacked thruster parameters.
        rudder: stacked rudder parameters.
        length: (G,) m, hull lengths.
        stokes_drift: add the Stokes drift of the (filtered) sea to the water velocity.
        min_wavelength: m, the group's wave filter.
        wave_precision: ``float64`` or ``float32``, of the group's surface queries.
    """

    index: np.ndarray
    mesh: MeshBuoyancy | None
    points: SamplePointBuoyancy | None
    body: np.ndarray
    owner: np.ndarray
    faces: np.ndarray | None
    face_owner: np.ndarray | None
    propulsion: object
    rudder: object
    length: np.ndarray
    stokes_drift: bool
    min_wavelength: float
    wave_precision: str

    @classmethod
    def build(cls, params: Sequence[BoatParams], index: np.ndarray) -> _Group:
        first = params[0]
        counts = []
        if isinstance(first.buoyancy, MeshBuoyancy):
            meshes = [p.buoyancy.mesh for p in params]
            counts = [m.vertices.shape[0] for m in meshes]
            offsets = np.cumsum([0, *counts[:-1]])
            faces = np.concatenate([m.faces + o for m, o in zip(meshes, offsets, strict=True)])
            face_owner = np.concatenate([np.full(m.faces.shape[0], i, dtype=np.intp)
                                         for i, m in enumerate(meshes)])
            mesh = replace(first.buoyancy, drag=_stack([p.buoyancy.drag for p in params]))
            body = np.concatenate([m.vertices for m in meshes])
            points = None
        else:
            models = [p.buoyancy for p in params]
            counts = [m.points.shape[0] for m in models]
            body = np.concatenate([m.points for m in models])
            points = replace(_stack(models, skip=("points",)), points=body)
            mesh = faces = face_owner = None
        owner = np.concatenate([np.full(n, i, dtype=np.intp) for i, n in enumerate(counts)])
        return cls(index, mesh, points, body, owner, faces, face_owner,
                   _stack([p.propulsion for p in params]), _stack([p.rudder for p in params]),
                   np.array([p.hull.length for p in params]), first.stokes_drift,
                   first.min_wavelength, first.wave_precision)


class Fleet:
    """Boats prepared for stepping together: parameters stacked once, per group and fleet-wide.

    Args:
        params: the boats' parameters (build once; a boat whose parameters change, e.g. its
            control mode, needs a new Fleet).
    """

    def __init__(self, params: Sequence[BoatParams]) -> None:
        self.params = tuple(params)
        self.count = len(self.params)
        keys: dict[tuple, list[int]] = {}
        for i, p in enumerate(self.params):
            keys.setdefault(_group_key(p), []).append(i)
        self.groups = [_Group.build([self.params[i] for i in members],
                                    np.array(members, dtype=np.intp))
                       for members in keys.values()]
        ps = self.params
        self.mass = np.array([p.mass for p in ps])
        self.center_of_mass = np.array([p.center_of_mass for p in ps], dtype=float)
        self.inertia = np.array([p.inertia for p in ps], dtype=float)
        added = np.array([p.added_mass for p in ps], dtype=float)
        self.effective_mass = self.mass[:, None] + added[:, :3]
        self.effective_inertia = self.inertia + added[:, 3:]
        products = np.array([p.inertia_products for p in ps], dtype=float)
        self.inertia_products = products if np.any(products != 0.0) else None
        decay = np.array([p.damping_decay for p in ps], dtype=float)
        self.decay = decay if np.any(decay > 0.0) else None
        self.damping_linear = np.array([p.damping_linear for p in ps], dtype=float)
        self.damping_quadratic = np.array([p.damping_quadratic for p in ps], dtype=float)
        self.water_density = np.array([p.water_density for p in ps])
        self.gravity = np.array([p.gravity for p in ps])
        self.keel_rate = np.array([p.keel_rate for p in ps])
        self.special = [i for i, p in enumerate(ps) if p.control.mode != "dynamic"]
        self.memo: tuple | None = None  # the last contacts(): (key, result)


@dataclass(frozen=True)
class Contact:
    """Where one group's hulls meet the water, at one state.

    Attributes:
        group: the group.
        rotation: (G, 3, 3) the group's body-to-world rotations.
        world: (E, 3) m, its hull vertices or sample points, world frame.
        depths: (E,) m, their depths below the surface (> 0 = submerged).
        surface: the surface at those points.
        at_reference: the surface at the boats' hull reference points.
        wet: the clipped hull triangles (mesh group; None for sample points).
        wet_owner: (T,) int, the boat (0..G-1) of each wet triangle (mesh group).
    """

    group: _Group
    rotation: np.ndarray
    world: np.ndarray
    depths: np.ndarray
    surface: SurfaceSample
    at_reference: SurfaceSample
    wet: SubmergedTriangles | None
    wet_owner: np.ndarray | None


def contacts(fleet: Fleet, state: FleetState, sea: WaveField) -> list[Contact]:
    """Every group's :class:`Contact` at ``state``: one surface query per wave filter.

    The last result is kept on the fleet: the forces of a step and the /diagnostics about the
    same state share one surface query and one clip. It is reused only for the very same
    state arrays, time and sea (states are never modified in place).
    """
    return _contacts(fleet, state, sea)[1]


def _contacts(fleet: Fleet, state: FleetState, sea: WaveField
              ) -> tuple[np.ndarray, list[Contact]]:
    """(B, 3, 3) body-to-world rotations and :func:`contacts`."""
    memo = fleet.memo
    if memo is not None:
        position, orientation, t, of_sea = memo[0]
        if (position is state.position and orientation is state.orientation and t == state.t
                and of_sea is sea):
            return memo[1]
    rot, ref = reference_points(fleet, state)
    queries = _world_points(fleet, rot, ref)
    out = []
    for (g, world), (surface, at_ref) in zip(queries, _sample(sea, state.t, queries, ref),
                                             strict=True):
        rot_g = rot[g.index]
        depths = surface.heights - world[:, 2]
        wet = wet_owner = None
        if g.mesh is not None:
            wet = clip_hulls(g.faces, world, depths)
            wet_owner = g.face_owner.take(wet.faces)
        out.append(Contact(g, rot_g, world, depths, surface, at_ref, wet, wet_owner))
    fleet.memo = ((state.position, state.orientation, state.t, sea), (rot, out))
    return rot, out


def fleet_forces(fleet: Fleet, state: FleetState, inputs: FleetInputs, sea: WaveField
                 ) -> tuple[FleetForces, np.ndarray]:
    """Every force model's wrench on every boat at ``state``.

    Returns:
        The forces, and (B, 3) the surface normal at each boat's hull reference point.
    """
    b = fleet.count
    rot, touching = _contacts(fleet, state, sea)
    sums = {s: (np.zeros((b, 3)), np.zeros((b, 3))) for s in ("buoyancy", "drag")}
    water_velocity, normals_ref = _at_reference(fleet, touching, sea)
    relative = state.velocity - np.einsum("bji,bj->bi", rot, water_velocity)  # body frame
    for c in touching:
        _buoyancy_and_drag(fleet, c, state, relative, sums)
    com = fleet.center_of_mass
    damp = damping(fleet.damping_linear, fleet.damping_quadratic, relative,
                   state.angular_velocity)
    push = _per_group(fleet, lambda g: thrust(g.propulsion, state.throttle[g.index],
                                              inputs.rudder[g.index], com[g.index]))
    steer = _per_group(fleet, lambda g: rudder_wrench(
        g.rudder, inputs.rudder[g.index], relative[g.index, 0],
        fleet.water_density[g.index], com[g.index]))
    weight = Wrench((fleet.mass * fleet.gravity)[:, None] * -rot[:, 2, :], np.zeros((b, 3)))
    buoy, drag = (Wrench(*sums[s]) for s in ("buoyancy", "drag"))
    total = buoy + damp + drag + push + steer + weight
    return FleetForces(buoy, damp, drag, push, steer, weight, total), normals_ref


def fleet_afloat(fleet: Fleet, state: FleetState, sea: WaveField) -> FleetState:
    """``state`` with each boat's velocity set to what it has after floating a while.

    Vertically, the surface water's at the hull reference point. Horizontally, what the
    boat's buoyancy gives it: the slope's push for the models whose force follows the surface
    (``mesh``, ``sample_points`` along the ``normal``), the orbital velocity of
    :func:`ocean_sim.waves.slope_orbit_velocity`; none for sample points pushed straight
    ``up``, which the waves do not move sideways. Exactly zero in still water. Position,
    attitude and angular velocity are kept (see :func:`boat_dynamics.boat.afloat`).
    """
    world = np.zeros((fleet.count, 3))
    for c in _contacts(fleet, state, sea)[1]:
        g = c.group
        at = c.at_reference
        world[g.index, 2] = at.velocities[:, 2]
        if g.mesh is not None or g.points.direction == "normal":
            world[g.index, :2] = slope_orbit_velocity(sea.filtered(g.min_wavelength),
                                                      at.rest_xy, state.t)
    body = np.einsum("bji,bj->bi", rotation_matrix(state.orientation), world)
    body[~world.any(axis=1)] = 0.0  # still water: +0.0, not the rotation's -0.0
    return replace(state, velocity=body)


def _at_reference(fleet: Fleet, touching: list[Contact], sea: WaveField
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Water velocity and surface normal at the boats' hull reference points.

    Returns:
        (B, 3) m/s, the water the damping is taken against (the surface water particle's
        velocity, plus the sea's Stokes drift for boats with ``stokes_drift``), and (B, 3)
        unit normals; world frame.
    """
    water_velocity = np.zeros((fleet.count, 3))
    normals = np.zeros((fleet.count, 3))
    for c in touching:
        g = c.group
        water_velocity[g.index] = c.at_reference.velocities
        normals[g.index] = c.at_reference.normals
        if g.stokes_drift:
            water_velocity[g.index] += _stokes(sea.filtered(g.min_wavelength))
    return water_velocity, normals


def reference_points(fleet: Fleet, state: FleetState) -> tuple[np.ndarray, np.ndarray]:
    """(B, 3, 3) body-to-world rotations and (B, 3) m world hull reference points."""
    rot = rotation_matrix(state.orientation)
    return rot, state.position - np.einsum("bij,bj->bi", rot, fleet.center_of_mass)


def _world_points(fleet: Fleet, rot: np.ndarray, ref: np.ndarray) -> list:
    """(group, (E, 3) m world positions of its vertices / points) for every group."""
    return [(g, ref[g.index][g.owner] + np.einsum("eij,ej->ei", rot[g.index][g.owner], g.body))
            for g in fleet.groups]


def _per_group(fleet: Fleet, model) -> Wrench:
    """A force model evaluated group by group, gathered into (B, 3) force and torque."""
    if len(fleet.groups) == 1:
        return model(fleet.groups[0])
    force, torque = np.zeros((fleet.count, 3)), np.zeros((fleet.count, 3))
    for g in fleet.groups:
        w = model(g)
        force[g.index], torque[g.index] = w.force, w.torque
    return Wrench(force, torque)


def _sample(sea: WaveField, t: float, queries: list, ref: np.ndarray) -> list:
    """The surface at every query's points and at its boats' reference points.

    Groups sharing a wave filter and precision share one sample_surface call (its fixed cost
    is paid once).
    """
    by_filter: dict[tuple[float, str], list[int]] = {}
    for k, (g, _) in enumerate(queries):
        by_filter.setdefault((g.min_wavelength, g.wave_precision), []).append(k)
    out: list = [None] * len(queries)
    for (min_wavelength, precision), members in by_filter.items():
        xy = np.concatenate([a for k in members
                             for a in (queries[k][1][:, :2], ref[queries[k][0].index, :2])])
        surface = sample_surface(sea, xy, t, min_wavelength=min_wavelength,
                                 precision=precision)
        start = 0
        for k in members:
            n, m = queries[k][1].shape[0], queries[k][0].index.shape[0]
            out[k] = (surface.rows(start, start + n), surface.rows(start + n, start + n + m))
            start += n + m
    return out


def _buoyancy_and_drag(fleet: Fleet, c: Contact, state: FleetState, relative: np.ndarray,
                       sums: dict) -> None:
    """Buoyancy (and hull drag) of one group's boats, added into ``sums`` (body frames)."""
    g = c.group
    i = g.index
    count = i.shape[0]
    rot_g = c.rotation
    rho_g = fleet.water_density[i] * fleet.gravity[i]
    if g.mesh is not None:
        wet, owner = c.wet, c.wet_owner
        force, torque = pressure_wrenches(wet, owner, count, state.position[i], rho_g)
        _add_world(sums["buoyancy"], i, rot_g, force, torque)
        drag = g.mesh.drag
        if drag.viscous or drag.pressure:
            omega_world = np.einsum("bij,bj->bi", rot_g, state.angular_velocity[i])
            flow_body = np.einsum("bij,bj->bi", rot_g, relative[i])
            centroids = wet.centroids
            flow = flow_body[owner] + cross(omega_world[owner],
                                            centroids - state.position[i][owner])
            speed = np.sqrt(np.einsum("bi,bi->b", relative[i], relative[i]))
            force, torque = hull_drag(drag, wet, owner, count, flow, speed, g.length,
                                      fleet.water_density[i], state.position[i])
            _add_world(sums["drag"], i, rot_g, force, torque)
        return
    model = g.points
    com = fleet.center_of_mass[i]
    point_velocities = None
    if np.any(np.asarray(model.point_damping) > 0.0):
        arms = model.points - com[g.owner]
        v_points = state.velocity[i][g.owner] + cross(state.angular_velocity[i][g.owner], arms)
        point_velocities = (np.einsum("eij,ej->ei", rot_g[g.owner], v_points)
                            - c.surface.velocities)
    force, torque = sample_point_wrenches(model, g.owner, count, c.depths, rot_g, com, rho_g,
                                          c.surface.normals, point_velocities, fleet.mass[i])
    sums["buoyancy"][0][i] += force
    sums["buoyancy"][1][i] += torque


def _add_world(into: tuple[np.ndarray, np.ndarray], index: np.ndarray, rot: np.ndarray,
               force: np.ndarray, torque: np.ndarray) -> None:
    """Add world-frame (G, 3) force and torque, turned into the boats' body frames."""
    into[0][index] += np.einsum("bji,bj->bi", rot, force)
    into[1][index] += np.einsum("bji,bj->bi", rot, torque)


def fleet_step(fleet: Fleet, state: FleetState, inputs: FleetInputs, sea: WaveField,
               dt: float) -> tuple[FleetState, FleetForces]:
    """Advance every boat by ``dt`` s (semi-implicit Euler), with one surface query.

    Args:
        fleet: the boats.
        state: their state at time t.
        inputs: their validated commands, held over the step.
        sea: the wave field.
        dt: s, > 0.

    Returns:
        The state at t + dt, and the forces that acted during the step.
    """
    throttle = np.empty(fleet.count)
    for g in fleet.groups:
        throttle[g.index] = lagged_throttle(g.propulsion, state.throttle[g.index],
                                            inputs.throttle[g.index], dt)
    state = replace(state, throttle=throttle)
    forces, normals = fleet_forces(fleet, state, inputs, sea)
    torque = forces.total.torque
    pd = [i for i in fleet.special if fleet.params[i].control.mode == "kinematic"
          and fleet.params[i].control.attitude == "pd"]
    if pd:
        torque = torque.copy()
        for i in pd:
            torque[i] += _pd_torque(fleet.params[i], state, i, normals[i], dt)
    p, q, v, w = integrate(state.position, state.orientation, state.velocity,
                           state.angular_velocity, forces.total.force, torque,
                           fleet.effective_mass, fleet.effective_inertia, dt,
                           fleet.inertia_products)
    v = reflect_off_keel(v, fleet.keel_rate, dt)
    if fleet.decay is not None:
        v, w = velocity_decay(v, w, fleet.decay, dt)
    after = FleetState(state.t + dt, p, q, v, w, throttle, state.control_weight)
    if fleet.special:
        after = _apply_modes(fleet, state, after, sea, dt)
    return after, forces


def _pd_torque(params: BoatParams, state: FleetState, i: int, normal: np.ndarray,
               dt: float) -> np.ndarray:
    """Roll and pitch torque of the stable PD attitude controller (kinematic, attitude: pd)."""
    control = params.control
    kp, kd = pd_gains(control.pd_frequency, control.pd_damping)
    target = align_with_normal(state.orientation[i], normal)
    pd = stable_pd_torque(state.orientation[i], state.angular_velocity[i], target,
                          params.inertia, kp, kd, dt)
    return pd * np.array([1.0, 1.0, 0.0])


def _apply_modes(fleet: Fleet, before: FleetState, after: FleetState, sea: WaveField,
                 dt: float) -> FleetState:
    """The control modes of the boats not in ``dynamic`` mode, boat by boat."""
    p, q = after.position.copy(), after.orientation.copy()
    v, w = after.velocity.copy(), after.angular_velocity.copy()
    weights = after.control_weight.copy()
    for i in fleet.special:
        params = fleet.params[i]
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
    return FleetState(after.t, p, q, v, w, after.throttle, weights)


def _pose(params: BoatParams, state: FleetState, i: int) -> _Pose:
    rot = rotation_matrix(state.orientation[i])
    return _Pose(state.position[i] - rot @ params.center_of_mass, state.orientation[i],
                 rot @ state.velocity[i], state.angular_velocity[i])


def _stokes(sea: WaveField) -> np.ndarray:
    """(3,) m/s, the sea's surface Stokes drift (cached on the sea)."""
    key = ("stokes_drift",)
    if key not in sea._cache:
        sea._cache[key] = np.array([*stokes_drift(sea), 0.0])
    return sea._cache[key]
