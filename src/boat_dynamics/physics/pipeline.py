"""The physics pipeline: ``init`` and ``step`` over a :class:`~.system.System` of boats.

In the style of brax's pipeline: ``init(system, state, sea)`` prepares a state (boats start
afloat), ``step(system, state, inputs, sea, dt)`` advances every boat by ``dt``. Both are pure
functions over frozen dataclasses: what a step computes that another part needs (the forces
for ``wrench/*``, the surface contact for ``/diagnostics``) is in the :class:`Step` it
returns. The step only sums the force models' outputs (one module each) and integrates;
control modes other than ``dynamic`` are applied by :mod:`.modes` after the integration.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics import contact as _contact
from boat_dynamics.physics.buoyancy import sample_point_group
from boat_dynamics.physics.contact import Contact, GroupContact
from boat_dynamics.physics.damping import damping, velocity_decay
from boat_dynamics.physics.hull_drag import hull_drag_in_motion
from boat_dynamics.physics.keel import reflect_off_keel
from boat_dynamics.physics.mesh_buoyancy import pressure_wrenches
from boat_dynamics.physics.modes import apply_modes, pd_torques
from boat_dynamics.physics.propulsion import lagged_throttle, thrust
from boat_dynamics.physics.rigid_body import integrate, rotation_matrix
from boat_dynamics.physics.rudder import rudder_wrench
from boat_dynamics.physics.system import FleetForces, FleetInputs, FleetState, System
from boat_dynamics.physics.wrench import Wrench
from ocean_sim.physics.waves import WaveField, slope_orbit_velocity

__all__ = ["Step", "forces", "init", "step"]


@dataclass(frozen=True)
class Step:
    """What one :func:`step` computed.

    Attributes:
        state: the boats' state at t + dt.
        forces: the wrenches that acted during the step (body frames, about the centres of
            mass), evaluated at the start of the step.
        contact: the surface contact at the start of the step, which the forces came from.
    """

    state: FleetState
    forces: FleetForces
    contact: Contact


def init(system: System, state: FleetState, sea: WaveField) -> FleetState:
    """``state`` with each boat's velocity set to what it has after floating a while.

    Released at rest over ground, a boat in waves lacks the orbital velocity its buoyancy would
    give it, and with quadratic surge drag alone it keeps that offset as a drift for minutes.
    So: vertically, the surface water's velocity at the hull reference point; horizontally,
    the slope's push for the models whose force follows the surface (``mesh``,
    ``sample_points`` along the ``normal``), the orbital velocity of
    :func:`ocean_sim.physics.waves.slope_orbit_velocity` (linear theory); none for sample
    points pushed straight ``up``, which the waves do not move sideways. Exactly zero in still
    water. Position, attitude and angular velocity are kept.

    Args:
        system: the boats.
        state: their state (velocities ignored).
        sea: the wave field at ``state.t``.

    Returns:
        The state with those velocities (body frames).
    """
    world = np.zeros((system.count, 3))
    for c in _contact.contact(system, state, sea).groups:
        g = c.group
        at = c.at_reference
        world[g.index, 2] = at.velocities[:, 2]
        if g.mesh is not None or g.points.direction == "normal":
            world[g.index, :2] = slope_orbit_velocity(sea.filtered(g.min_wavelength),
                                                      at.rest_xy, state.t)
    body = np.einsum("bji,bj->bi", rotation_matrix(state.orientation), world)
    body[~world.any(axis=1)] = 0.0  # still water: +0.0, not the rotation's -0.0
    return replace(state, velocity=body)


def forces(system: System, state: FleetState, inputs: FleetInputs, contact: Contact
           ) -> tuple[FleetForces, np.ndarray]:
    """Every force model's wrench on every boat at ``state``, and their sum.

    Args:
        system: the boats.
        state: their state.
        inputs: their validated commands.
        contact: the surface contact at ``state`` (:func:`.contact.contact`).

    Returns:
        The forces (body frames, about the centres of mass), and (B, 3) the surface normal
        at each boat's hull reference point, world frame.
    """
    b = system.count
    rot = contact.rotation
    water_velocity, normals_ref = _at_reference(system, contact)
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
    push = _per_group(system, lambda g: thrust(g.propulsion, state.throttle[g.index],
                                               inputs.rudder[g.index], com[g.index]))
    steer = _per_group(system, lambda g: rudder_wrench(
        g.rudder, inputs.rudder[g.index], relative[g.index, 0],
        system.water_density[g.index], com[g.index]))
    weight = Wrench((system.mass * system.gravity)[:, None] * -rot[:, 2, :], np.zeros((b, 3)))
    buoy, drag = Wrench(*buoy), Wrench(*drag)
    total = buoy + damp + drag + push + steer + weight
    return FleetForces(buoy, damp, drag, push, steer, weight, total), normals_ref


def step(system: System, state: FleetState, inputs: FleetInputs, sea: WaveField, dt: float,
         contact: Contact | None = None) -> Step:
    """Advance every boat by ``dt`` s (semi-implicit Euler), with one surface query.

    Args:
        system: the boats.
        state: their state at time t.
        inputs: their validated commands, held over the step.
        sea: the wave field.
        dt: s, > 0.
        contact: the surface contact at ``state`` if already known (the /diagnostics of
            ``state`` computed it); None = computed here.

    Returns:
        The state at t + dt, the forces that acted and the contact they came from.

    Raises:
        ValueError: ``contact`` belongs to another state or sea.
    """
    throttle = np.empty(system.count)
    for g in system.groups:
        throttle[g.index] = lagged_throttle(g.propulsion, state.throttle[g.index],
                                            inputs.throttle[g.index], dt)
    state = replace(state, throttle=throttle)
    if contact is None:
        contact = _contact.contact(system, state, sea)
    elif not contact.belongs_to(system, state, sea):
        raise ValueError("contact: computed for another system, state or sea than the one "
                         "stepped")
    acting, normals = forces(system, state, inputs, contact)
    torque = pd_torques(system, state, acting.total.torque, normals, dt)
    p, q, v, w = integrate(state.position, state.orientation, state.velocity,
                           state.angular_velocity, acting.total.force, torque,
                           system.effective_mass, system.effective_inertia, dt,
                           system.inertia_products)
    v = reflect_off_keel(v, system.keel_rate, dt)
    if system.decay is not None:
        v, w = velocity_decay(v, w, system.decay, dt)
    after = FleetState(state.t + dt, p, q, v, w, throttle, state.control_weight)
    return Step(apply_modes(system, state, after, sea, dt), acting, contact)


def _at_reference(system: System, contact: Contact) -> tuple[np.ndarray, np.ndarray]:
    """Water velocity and surface normal at the boats' hull reference points.

    Returns:
        (B, 3) m/s, the water the damping is taken against (the surface water particle's
        velocity, plus the sea's Stokes drift for boats with ``stokes_drift``), and (B, 3)
        unit normals; world frame.
    """
    water_velocity = np.zeros((system.count, 3))
    normals = np.zeros((system.count, 3))
    for c in contact.groups:
        g = c.group
        water_velocity[g.index] = c.at_reference.velocities
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
