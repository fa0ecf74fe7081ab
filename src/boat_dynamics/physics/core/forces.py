"""The force sum: every force model's wrench on every boat of a system at one state.

Each force model is a function in its own module returning force and torque (buoyancy:
:mod:`.mesh_buoyancy` and :mod:`.buoyancy`; :mod:`.hull_drag`, :mod:`.damping`,
:mod:`.propulsion`, :mod:`.rudder`, :mod:`.added_mass`); this module only evaluates them
group by group, from the surface contact of the state, and adds them up.
:func:`boat_dynamics.physics.core.pipeline.step` integrates the total; :mod:`.tuning` reads the
buoyancy of trial poses from here.
"""

from __future__ import annotations

import math

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench
from boat_dynamics.physics.core.contact import Contact, GroupContact
from boat_dynamics.physics.core.system import FleetForces, FleetInputs, FleetState, System
from boat_dynamics.physics.force_models.anchor_line import anchor_line_wrench
from boat_dynamics.physics.force_models.buoyancy import sample_point_group
from boat_dynamics.physics.force_models.collision import (
    BoatKinematics,
    Touches,
    collision_wrench,
    hull_contact_wrench,
    hull_touches,
    touches,
)
from boat_dynamics.physics.force_models.damping import damping, radiation_damping
from boat_dynamics.physics.force_models.hull_drag import hull_drag_in_motion
from boat_dynamics.physics.force_models.mesh_buoyancy import pressure_wrenches
from boat_dynamics.physics.force_models.mooring import mooring_wrench
from boat_dynamics.physics.force_models.propulsion import thrusters_wrench
from boat_dynamics.physics.force_models.rudder import rudder_wrench
from boat_dynamics.physics.force_models.slamming import kerner_wrench, slamming_wrench
from boat_dynamics.physics.force_models.wind import wind_wrench
from boat_dynamics.physics.potential_flow.added_mass import added_mass_coriolis
from boat_dynamics.physics.potential_flow.diffraction import excitation_wrench
from boat_dynamics.physics.potential_flow.hull_lift import hull_lift
from boat_dynamics.physics.potential_flow.radiation import memory_wrench
from boat_dynamics.physics.wave_making.interaction import made_waves_wrench
from boat_dynamics.physics.world.obstacles import World
from ocean_sim.physics.constants import AIR_DENSITY
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.waves import WaveField

__all__ = ["forces", "previous_swept", "touches_of"]


def forces(system: System, state: FleetState, inputs: FleetInputs, contact: Contact,
           environment: Environment | None = None, world: World | None = None
           ) -> tuple[FleetForces, np.ndarray]:
    """Every force model's wrench on every boat at ``state``, and their sum.

    Args:
        system: the boats.
        state: their state.
        inputs: their validated commands.
        contact: the surface contact at ``state`` (:func:`.contact.contact`).
        environment: the current (it moves the water the damping, drag and rudder see) and
            the wind (:mod:`.wind`), or None: neither.
        world: the fixed obstacles the hulls meet (:mod:`.collision`), or None: none.

    Returns:
        The forces (body frames, about the centres of mass), and (B, 3) the surface normal
        at each boat's hull reference point, world frame.
    """
    b = system.count
    rot = contact.rotation
    water_velocity, normals_ref = _at_reference(system, contact)
    if environment is not None and environment.current_speed > 0.0:
        water_velocity = water_velocity + environment.current
    relative = state.velocity - np.einsum("bji,bj->bi", rot, water_velocity)  # body frame
    buoy, drag = (np.zeros((b, 3)), np.zeros((b, 3))), (np.zeros((b, 3)), np.zeros((b, 3)))
    for c in contact.groups:
        _add(buoy, c.group.index, *_buoyancy(system, c, state))
        mesh = c.group.mesh
        if mesh is not None and (mesh.drag.viscous or mesh.drag.pressure):
            _add(drag, c.group.index, *_hull_drag(system, c, state, relative))
    com = system.center_of_mass
    damp = damping(system.damping_linear, system.damping_quadratic, relative,
                   state.angular_velocity)
    if system.radiation is not None:  # potential-flow coefficients: on the body's velocity
        damp = damp + radiation_damping(system.radiation, state.velocity,
                                        state.angular_velocity)
    carried = contact.immersion  # a hull out of the water leaves its fluid behind
    if system.memory is not None and state.memory is not None:  # Cummins: the waves made
        damp = damp + Wrench(*memory_wrench(system.memory.output, state.memory, carried))
    if system.coupled:  # a 6 x 6 added mass at forward speed: the Munk moment
        damp = damp + _added_mass_at_speed(system, state, rot, environment, carried)
    if system.lift is not None:  # the trailing section's lift at speed
        lift = hull_lift(system.lift.added_mass * carried[:, None], system.lift.position,
                         _through_current(state.velocity, rot, environment),
                         state.angular_velocity, com)
        damp = damp + lift
    push = _per_group(system, lambda g: thrusters_wrench(
        g.propulsion, state.throttle[g.index],
        [inputs.angle_of(j)[g.index] for j in range(len(g.propulsion))], com[g.index]))
    steer = _per_group(system, lambda g: rudder_wrench(
        g.rudder, inputs.rudder[g.index], relative[g.index], state.angular_velocity[g.index],
        system.water_density[g.index], com[g.index]))
    weight = Wrench((system.mass * system.gravity)[:, None] * -rot[:, 2, :], np.zeros((b, 3)))
    buoy, drag = Wrench(*buoy), Wrench(*drag)
    total = buoy + damp + drag + push + steer + weight
    scattered = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if system.diffracting:  # potential-flow coefficients: per coefficient set
        scattered, incident = _excitation(system, state, contact)
        total = total + scattered
        if incident is not None:  # linear pressure: the incident waves' Froude-Krylov force
            buoy = buoy + incident
            total = total + incident
    slam = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if state.slamming is not None and any(_slams(c) for c in contact.groups):
        slam = _slamming(system, state, contact)
        total = total + slam
    tether = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if system.mooring is not None:  # held on station: RAO runs
        m = system.mooring
        tether = mooring_wrench(m.stiffness, m.damping, m.anchor, state.position, rot,
                                state.velocity, state.angular_velocity)
        total = total + tether
    if system.anchor_lines is not None:  # buoys, anchored boats
        line = anchor_line_wrench(system.anchor_lines, state.position, rot, state.velocity,
                                  state.angular_velocity, com)
        tether = tether + line
        total = total + line
    blow = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if (environment is not None and environment.wind.speed > 0.0
            and system.windage is not None):  # in calm air no load (no air drag either)
        wind_body = np.einsum("bji,j->bi", rot, environment.wind.velocity(state.t))
        blow = wind_wrench(system.windage, system.windage_centre, wind_body, state.velocity,
                           com, AIR_DENSITY)
        total = total + blow
    bump = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if world is not None and world.contact is not None and (world.obstacles
                                                            or system.count > 1):
        bump = _collision(system, state, contact, world)
        total = total + bump
    made = Wrench(np.zeros((b, 3)), np.zeros((b, 3)))
    if system.made_waves is not None:  # boats that feel each other's waves
        made = _made_waves(system, state, rot, environment, contact.sea)
        total = total + made
    return (FleetForces(buoyancy=buoy, damping=damp, drag=drag, thrust=push, rudder=steer,
                        diffraction=scattered, slamming=slam, mooring=tether, wind=blow,
                        collision=bump, made_waves=made, gravity=weight, total=total),
            normals_ref)


def _made_waves(system: System, state: FleetState, rot: np.ndarray,
                environment: Environment | None, sea: WaveField) -> Wrench:
    """(B, 3) the waves other boats make: their force and torque, body frames."""
    ref = state.position - np.einsum("bij,bj->bi", rot, system.center_of_mass)
    over_ground = np.einsum("bij,bj->bi", rot, state.velocity)[:, :2]
    through = over_ground
    if environment is not None and environment.current_speed > 0.0:
        through = over_ground - environment.current[:2]
    return made_waves_wrench(system.made_waves, ref[:, :2], np.arctan2(rot[:, 1, 0], rot[:, 0, 0]),
                             over_ground, through, state.t, system.count, sea)


def touches_of(system: System, state: FleetState, contact: Contact, world: World) -> Touches:
    """Each boat's deepest point in an obstacle or another boat at ``state`` (contact events).

    Returns:
        :class:`~boat_dynamics.physics.force_models.collision.Touches` of the B boats:
        ``other`` is an obstacle's index in ``world.obstacles``, or len(world.obstacles)
        plus another boat's index, whichever is deeper; -1 touching nothing.
    """
    b = system.count
    out = Touches.empty(b)
    k = _kinematics(system, state, contact)
    found = []
    if world.obstacles:
        near = _near_obstacles(world, system, k)
        found.append((0, near, touches(world, *_world_points(system, k, near), near.shape[0],
                                       k.rotation[near], k.center_of_mass[near],
                                       k.velocity[near], k.angular_velocity[near])))
    if b > 1:
        found.append((len(world.obstacles), np.arange(b), hull_touches(system.footprints, k)))
    for offset, rows, t in found:
        deeper = (t.other >= 0) & (t.depth > out.depth[rows])
        i = rows[deeper]
        out.other[i] = t.other[deeper] + offset
        out.point[i], out.normal[i] = t.point[deeper], t.normal[deeper]
        out.depth[i], out.approach_speed[i] = t.depth[deeper], t.approach_speed[deeper]
    return out


def _collision(system: System, state: FleetState, contact: Contact, world: World) -> Wrench:
    """(B, 3) the obstacles' and the other boats' force and torque on each hull, body frames."""
    b = system.count
    k = _kinematics(system, state, contact)
    force, torque = np.zeros((b, 3)), np.zeros((b, 3))
    if world.obstacles:
        near = _near_obstacles(world, system, k)
        if near.shape[0]:
            force[near], torque[near] = collision_wrench(
                world, *_world_points(system, k, near), near.shape[0], k.rotation[near],
                k.center_of_mass[near], k.velocity[near], k.angular_velocity[near],
                system.mass[near])
    if b > 1:
        pushed = hull_contact_wrench(world.contact, system.footprints, k)
        force, torque = force + pushed[0], torque + pushed[1]
    return Wrench(force, torque)


def _kinematics(system: System, state: FleetState, contact: Contact) -> BoatKinematics:
    """Every boat's pose, motion and contact points (:attr:`System.footprints`)."""
    rot = contact.rotation
    ref = contact.position - np.einsum("bij,bj->bi", rot, system.center_of_mass)
    return BoatKinematics(rot, ref, system.center_of_mass, state.velocity,
                          state.angular_velocity, system.mass, system.footprints.points,
                          system.footprints.starts)


def _near_obstacles(world: World, system: System, k: BoatKinematics) -> np.ndarray:
    """(N,) int, the boats whose footprint's circle reaches the obstacles' bounding box."""
    x0, x1, y0, y1, _ = world.bounds
    r, p = system.footprints.radius, k.reference
    if math.isfinite(world.shelving):  # a shelving shore reaches out as far as a keel does
        r = r + (r + np.maximum(-p[:, 2], 0.0)) / world.shelving
    return np.flatnonzero((p[:, 0] + r >= x0) & (p[:, 0] - r <= x1) & (p[:, 1] + r >= y0)
                          & (p[:, 1] - r <= y1))


def _world_points(system: System, k: BoatKinematics, boats: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``boats``' contact points: (E, 3) m world, (E, 3) m body, (E,) int owner in 0..N-1."""
    parts = [k.points(int(i)) for i in boats]
    owner = np.repeat(np.arange(len(parts)), [w.shape[0] for w, _ in parts])
    if not parts:
        return np.zeros((0, 3)), np.zeros((0, 3)), owner
    return (np.concatenate([w for w, _ in parts]), np.concatenate([b for _, b in parts]),
            owner)


def _added_mass_at_speed(system: System, state: FleetState, rot: np.ndarray,
                         environment: Environment | None, carried: np.ndarray) -> Wrench:
    """(B, 3) the ``coupled`` boats' added-mass forces at speed (:mod:`.added_mass`).

    The horizontal -C_A(nu) nu, nu relative to the current (not to the waves' orbital motion),
    of the added mass each hull carries (``carried``: :func:`.contact.immersion`); zero for
    the other boats.
    """
    i = np.array(system.coupled, dtype=np.intp)
    velocity = _through_current(state.velocity[i], rot[i], environment)
    total = added_mass_coriolis(system.added_mass_matrix, velocity, state.angular_velocity[i],
                                carried[i])
    if i.shape[0] == system.count:
        return total
    force, torque = np.zeros((system.count, 3)), np.zeros((system.count, 3))
    force[i], torque[i] = total.force, total.torque
    return Wrench(force, torque)


def _through_current(velocity: np.ndarray, rot: np.ndarray,
                    environment: Environment | None) -> np.ndarray:
    """(B, 3) m/s, body velocities relative to the current (the velocities without one)."""
    if environment is None or environment.current_speed <= 0.0:
        return velocity
    return velocity - np.einsum("bji,j->bi", rot, environment.current)


def _excitation(system: System, state: FleetState, contact: Contact
                ) -> tuple[Wrench, Wrench | None]:
    """The diffraction wrench, and the linear Froude-Krylov one, of the boats with coefficients.

    The diffraction at each boat's encounter frequencies (its velocity over ground).

    (B, 3) forces and torques, body frames; the Froude-Krylov wrench only for boats with
    ``linear`` pressure (None when there is none). Boats sharing a coefficient set, a wave
    filter and a pressure model are evaluated in one call.
    """
    force, torque = np.zeros((system.count, 3)), np.zeros((system.count, 3))
    fk_force, fk_torque, linear = np.zeros((system.count, 3)), np.zeros((system.count, 3)), False
    for batch in system.excitation:
        idx = batch.index
        rot = contact.rotation[idx]
        ref = state.position[idx] - np.einsum("bij,bj->bi", rot, system.center_of_mass[idx])
        args = (batch.hydro, contact.sea.filtered(batch.min_wavelength), ref[:, :2],
                np.arctan2(rot[:, 1, 0], rot[:, 0, 0]), state.t)
        moving = np.einsum("bij,bj->bi", rot, state.velocity[idx])[:, :2]  # over ground
        if batch.linear:
            scattered, incident = excitation_wrench(*args, "both", moving)
            force[idx], torque[idx] = scattered[:, :3], scattered[:, 3:]
            fk_force[idx], fk_torque[idx] = incident[:, :3], incident[:, 3:]
            linear = True
        else:
            force[idx], torque[idx] = excitation_wrench(*args, "diffraction", moving)
    return Wrench(force, torque), (Wrench(fk_force, fk_torque) if linear else None)


def _slams(c: GroupContact) -> bool:
    """Whether the group's hulls have a slamming model."""
    return c.group.mesh is not None and c.group.mesh.slamming.model != "none"


def _slamming(system: System, state: FleetState, contact: Contact) -> Wrench:
    """(B, 3) slamming force and torque (body frames) of the hulls with a slamming model."""
    force, torque = np.zeros((system.count, 3)), np.zeros((system.count, 3))
    elapsed = state.t - state.slamming[:, 1]
    for c in contact.groups:
        if not _slams(c):
            continue
        i, g = c.group.index, c.group
        com = state.position[i]
        if c.waterline is not None:  # momentum theory
            added, centroid = c.waterline
            w = (np.einsum("gij,gj->gi", c.rotation, state.velocity[i])[:, 2]
                 - c.at_reference.velocities[:, 2])
            wrench = slamming_wrench(added, state.slamming[i, 0], elapsed[i], w, centroid,
                                     com, c.rotation)
        else:  # Kerner
            before = c.swept[0] if state.swept is None else previous_swept(state, c)
            wrench = kerner_wrench(g.mesh.slamming, c.swept, before, g.face_owner, elapsed[i],
                                   system.mass[i], com, c.rotation)
        force[i], torque[i] = wrench.force, wrench.torque
    return Wrench(force, torque)


def previous_swept(state: FleetState, c: GroupContact) -> np.ndarray:
    """(F, 3) the group's S_i v_i at the previous step, from ``state.swept`` (zeros if short)."""
    g = c.group
    rows, cols = g.index[g.face_owner], g.face_local
    if state.swept.shape[1] <= cols.max():
        return np.zeros((cols.shape[0], 3))
    return state.swept[rows, cols]


def _at_reference(system: System, contact: Contact) -> tuple[np.ndarray, np.ndarray]:
    """The water velocity the damping is taken against, and the surface normals.

    Returns:
        (B, 3) m/s, the water's velocity (over the wetted hull, or the surface water
        particle's above the hull reference point: ``water_velocity``), plus the sea's Stokes
        drift for boats with ``stokes_drift``; and (B, 3) unit normals at the reference
        points; world frame.
    """
    water_velocity = np.zeros((system.count, 3))
    normals = np.zeros((system.count, 3))
    for c in contact.groups:
        g = c.group
        water_velocity[g.index] = (c.at_reference.velocities if c.water_velocity is None
                                   else c.water_velocity)
        normals[g.index] = c.at_reference.normals
        if g.stokes_drift:
            water_velocity[g.index] += contact.sea.filtered(g.min_wavelength
                                                            ).surface_stokes_drift
    return water_velocity, normals


def _buoyancy(system: System, c: GroupContact, state: FleetState
              ) -> tuple[np.ndarray, np.ndarray]:
    """(G, 3) buoyancy force and torque of one group's boats, body frames."""
    i = c.group.index
    rho_g = system.water_density[i] * system.gravity[i]
    if c.group.mesh is not None:
        force, torque = pressure_wrenches(c.wet, c.wet_owner, i.shape[0], state.position[i],
                                          rho_g)
        return _to_body(c.rotation, force), _to_body(c.rotation, torque)
    return sample_point_group(c.group.points, c.group.owner, i.shape[0], c.depths, c.rotation,
                              system.center_of_mass[i], rho_g, c.surface.normals,
                              c.surface.velocities, state.velocity[i],
                              state.angular_velocity[i], system.mass[i])


def _hull_drag(system: System, c: GroupContact, state: FleetState, relative: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """(G, 3) hull drag force and torque of one mesh group's boats, body frames."""
    i = c.group.index
    force, torque = hull_drag_in_motion(c.group.mesh.drag, c.wet, c.wet_owner, i.shape[0],
                                        c.rotation, relative[i], state.angular_velocity[i],
                                        state.position[i], c.group.length,
                                        system.water_density[i])
    return _to_body(c.rotation, force), _to_body(c.rotation, torque)


def _to_body(rotation: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """(G, 3) world-frame vectors in the boats' body frames (R^T v)."""
    return np.einsum("bji,bj->bi", rotation, vectors)


def _add(into: tuple[np.ndarray, np.ndarray], index: np.ndarray, force: np.ndarray,
         torque: np.ndarray) -> None:
    """Add a group's (G, 3) force and torque into the fleet's (B, 3) sums."""
    into[0][index] += force
    into[1][index] += torque


def _per_group(system: System, model) -> Wrench:
    """A force model evaluated group by group, gathered into (B, 3) force and torque."""
    if len(system.groups) == 1:
        return model(system.groups[0])
    force, torque = np.zeros((system.count, 3)), np.zeros((system.count, 3))
    for g in system.groups:
        w = model(g)
        force[g.index], torque[g.index] = w.force, w.torque
    return Wrench(force, torque)
