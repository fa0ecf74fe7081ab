"""The physics pipeline: ``init`` and ``step`` over a :class:`~.system.System` of boats.

In the style of brax's pipeline: ``init(system, state, sea)`` derives what the boats' own
hydrostatics fix (their equilibrium, the damping a scenario left to derive) and sets them
afloat; ``step(system, state, inputs, sea, dt)`` advances every boat by ``dt``. Both are pure
functions over frozen dataclasses: what a step computes that another part needs (the forces
for ``wrench/*``, the surface contact for ``/diagnostics``) is in the :class:`Step` it
returns. The step only sums the force models' outputs (:mod:`.forces`) and integrates;
control modes other than ``dynamic`` are applied by :mod:`.modes` after the integration.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from boat_dynamics.physics.body.rigid_body import (
    advance_pose,
    integrate,
    integrate_coupled,
    mass_matrix,
    quat_to_euler,
    rotation_matrix,
)
from boat_dynamics.physics.core import contact as _contact
from boat_dynamics.physics.core.contact import Contact
from boat_dynamics.physics.core.forces import forces
from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.modes import apply_modes, pd_torques
from boat_dynamics.physics.core.system import FleetForces, FleetInputs, FleetState, System
from boat_dynamics.physics.core.tuning import derive
from boat_dynamics.physics.force_models.carriage import towed_velocity
from boat_dynamics.physics.force_models.damping import velocity_decay
from boat_dynamics.physics.force_models.keel import reflect_off_keel
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy, panelled
from boat_dynamics.physics.force_models.propulsion import lagged_throttle
from boat_dynamics.physics.potential_flow.radiation import advance
from boat_dynamics.physics.world.obstacles import World
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.errors import InvalidValueError
from ocean_sim.physics.waves import WaveField, slope_orbit_velocity

if TYPE_CHECKING:
    from boat_dynamics.physics.scenario import BoatSpec, Scenario

__all__ = ["InitError", "Step", "afloat", "init", "init_scenario", "start", "step"]


class InitError(InvalidValueError):
    """A boat that cannot be initialized (its hull sinks).

    Attributes:
        boat: the boat's place in the system.
        key: the parameter at fault (``mass``).
        value: its value.
        allowed: what would have been accepted.
    """

    def __init__(self, boat: int, key: str, value: object, allowed: str) -> None:
        self.boat = boat
        super().__init__(key, value, allowed,
                         f"boat {boat}: {key}: {value!r} is not allowed: {allowed}")


@dataclass(frozen=True)
class Step:
    """What one :func:`step` computed.

    Attributes:
        state: the boats' state at t + dt.
        forces: the wrenches that acted during the step (body frames, about the centres of
            mass), evaluated at the start of the step.
        contact: the surface contact at the start of the step, which the forces came from.
        towing: (B, 3) the towing carriages' force along and across their lines (N) and yaw
            moment (N m), world frame, over the step (the towed boats' resistance; zero for
            a boat not towed), or None when no boat is towed (:mod:`.carriage`).
    """

    state: FleetState
    forces: FleetForces
    contact: Contact
    towing: np.ndarray | None = None


def init(system: System, state: FleetState, sea: WaveField) -> tuple[System, FleetState]:
    """The system with its derived parameters, and the state afloat.

    Each boat's :class:`~.model.Derivation` is computed once (:func:`.tuning.derive`: its
    flat-water equilibrium height, the damping left to derive); a mesh hull with
    ``froude_krylov`` pressure is refined for the shortest wave of ``sea`` acting on it
    (:func:`.mesh_buoyancy.panelled`; a later change of the sea keeps that mesh); then
    :func:`afloat`.

    Args:
        system: the boats, as a scenario gives them.
        state: their state (velocities ignored).
        sea: the wave field at ``state.t``.

    Returns:
        The system to step (nothing left to derive) and the state to start from.

    Raises:
        InitError: a boat's hull sinks.
    """
    params = []
    derived: dict[int, BoatParams] = {}  # by id: boats sharing their parameters derive once
    for i, p in enumerate(system.params):
        if id(p) not in derived:
            try:
                derived[id(p)] = _panelled(derive(p), sea)
            except ValueError as exc:
                raise InitError(i, "mass", p.mass, str(exc)) from exc
        params.append(derived[id(p)])
    params = [_anchored(p, state, i) for i, p in enumerate(params)]
    if any(a is not b for a, b in zip(params, system.params, strict=True)):
        system = System.build(params)
    return system, afloat(system, state, sea)


def _anchored(params: BoatParams, state: FleetState, i: int) -> BoatParams:
    """``params`` with its mooring or carriage still to place held where boat i starts.

    The ``mooring`` key's anchor, and the ``carriage`` key's line: the world x, y (m) of the
    boat's centre of mass and its heading (rad) in ``state``.
    """
    moor = params.mooring is not None and np.isnan(params.mooring.anchor).any()
    tow = params.carriage is not None and math.isnan(params.carriage.heading)
    if not (moor or tow):  # nearly every boat: no attitude to convert at start-up
        return params
    heading = quat_to_euler(state.orientation[i])[2]
    if moor:
        anchor = np.array([state.position[i, 0], state.position[i, 1], heading])
        params = replace(params, mooring=replace(params.mooring, anchor=anchor))
    if tow:
        params = replace(params, carriage=replace(
            params.carriage, origin=state.position[i, :2].copy(), heading=heading))
    return params


def _panelled(params: BoatParams, sea: WaveField) -> BoatParams:
    """``params`` with its mesh refined for the shortest wave acting on it.

    Only for ``froude_krylov`` pressure (:func:`.mesh_buoyancy.panelled`).
    """
    if not isinstance(params.buoyancy, MeshBuoyancy):
        return params
    acting = sea.filtered(params.min_wavelength).components
    shortest = min((c.wavelength for c in acting if c.amplitude > 0.0), default=math.inf)
    model = panelled(params.buoyancy, shortest)
    return params if model is params.buoyancy else replace(params, buoyancy=model)


def start(boats: Sequence[BoatSpec], sea: WaveField, t: float = 0.0
          ) -> tuple[System, FleetState]:
    """:func:`init` of a scenario's boats at time ``t`` (s), from their initial poses.

    Afloat (:func:`afloat`), each boat's own ``velocity`` (m/s, body frame: a towing-tank run
    starting at speed) added to the waves' motion, its angular velocity kept.

    Raises:
        InitError: a boat's hull sinks (``boat`` is its place in ``boats``).
    """
    system, state = init(System.build([b.params for b in boats]),
                         FleetState.stack([replace(b.initial, t=t) for b in boats]), sea)
    own = np.array([b.velocity for b in boats], dtype=float).reshape(len(boats), 3)
    if own.any():  # else untouched: + 0.0 would turn a -0.0 into 0.0
        state = replace(state, velocity=state.velocity + own)
    return system, state


def init_scenario(scenario: Scenario, t: float = 0.0) -> Scenario:
    """``scenario`` with its boats initialized by :func:`start` at time ``t`` (s).

    Each boat's parameters are derived (nothing left in ``derive``) and its initial state is
    afloat: what the dynamics node steps, and what tests step one boat at a time.

    Raises:
        InitError: a boat's hull sinks.
    """
    system, state = start(scenario.boats, scenario.sea, t)
    return replace(scenario, boats=tuple(
        replace(b, params=system.params[i], initial=state.boat(i))
        for i, b in enumerate(scenario.boats)))


def afloat(system: System, state: FleetState, sea: WaveField) -> FleetState:
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


def step(system: System, state: FleetState, inputs: FleetInputs, sea: WaveField, dt: float,
         contact: Contact | None = None, environment: Environment | None = None,
         world: World | None = None) -> Step:
    """Advance every boat by ``dt`` s (semi-implicit Euler), with one surface query.

    Args:
        system: the boats.
        state: their state at time t.
        inputs: their validated commands, held over the step.
        sea: the wave field.
        dt: s, > 0.
        contact: the surface contact at ``state`` if already known (the /diagnostics of
            ``state`` computed it); None = computed here.
        environment: the current and the wind (:mod:`ocean_sim.physics.environment`), or
            None: neither.
        world: the fixed obstacles (:mod:`boat_dynamics.physics.world`), or None: none.

    Returns:
        The state at t + dt, the forces that acted, the contact they came from and the
        towing carriages' force (:mod:`.carriage`).

    Raises:
        ValueError: ``contact`` belongs to another state or sea.
    """
    throttle = np.zeros_like(state.throttle)  # slots past a boat's thrusters: unused, 0
    for g in system.groups:
        for j, model in enumerate(g.propulsion):
            throttle[g.index, j] = lagged_throttle(model, state.throttle[g.index, j],
                                                   inputs.throttle_of(j)[g.index], dt)
    state = replace(state, throttle=throttle)
    if contact is None:
        contact = _contact.contact(system, state, sea)
    elif not contact.belongs_to(system, state, sea):
        raise ValueError("contact: computed for another system, state or sea than the one "
                         "stepped")
    acting, normals = forces(system, state, inputs, contact, environment, world)
    torque = acting.total.torque
    if system.special:  # control modes: rare, arcade
        torque = pd_torques(system, state, torque, normals, dt)
    if len(system.coupled) == system.count:  # every boat has a 6 x 6 added mass
        p, q, v, w = integrate_coupled(state.position, state.orientation, state.velocity,
                                       state.angular_velocity, acting.total.force, torque,
                                       system.mass, system.inertia_tensor,
                                       _mass_inverse(system, contact.immersion), dt)
    else:
        p, q, v, w = integrate(state.position, state.orientation, state.velocity,
                               state.angular_velocity, acting.total.force, torque,
                               system.effective_mass, system.effective_inertia, dt,
                               system.inertia_products)
        if system.coupled:
            _integrate_coupled(system, state, acting.total.force, torque, dt, (p, q, v, w),
                               contact.immersion)
    v = reflect_off_keel(v, system.keel_rate, dt)
    if system.decay is not None:
        v, w = velocity_decay(v, w, system.decay, dt)
    towing = _towed(system, state, (p, q, v, w), contact.immersion, dt) if system.towed else None
    after = FleetState(state.t + dt, p, q, v, w, throttle, state.control_weight)
    if system.special:
        after = apply_modes(system, state, after, sea, dt)
    if system.memory is not None:
        after = replace(after, memory=_memory_after(system, state, after, dt))
    slamming = [c for c in contact.groups
                if c.group.mesh is not None and c.group.mesh.slamming.model != "none"]
    if slamming:
        after = replace(after, slamming=_waterline_now(system, state, slamming),
                        swept=_swept_now(system, state, slamming))
    return Step(after, acting, contact, towing)


def _towed(system: System, state: FleetState, into: tuple[np.ndarray, ...],
           immersion: np.ndarray, dt: float) -> np.ndarray:
    """Overwrite the towed boats' rows of ``into`` (p, q, v, w) by the carriage's constraint.

    Their velocities are constrained (:func:`.carriage.towed_velocity`, with the mass matrix
    the step integrated with) and their poses advanced again from ``state`` with them.

    Returns:
        (B, 3) the carriages' force along and across their lines (N) and yaw moment (N m),
        world frame; zero for a boat not towed.
    """
    p, q, v, w = into
    out = np.zeros((system.count, 3))
    for i in system.towed:
        params = system.params[i]
        if i in system.coupled:
            k = system.coupled.index(i)
            mass = system.rigid_mass_matrix[k] + immersion[i] * system.added_mass_matrix[k]
        else:
            mass = (mass_matrix(params.mass, params.inertia, params.inertia_products)
                    + np.diag(params.added_mass))
        nu, out[i] = towed_velocity(params.carriage, mass, rotation_matrix(q[i]), p[i],
                                    np.concatenate([v[i], w[i]]), dt)
        p[i], q[i], v[i], w[i] = advance_pose(state.position[i], state.orientation[i],
                                              nu[:3], nu[3:], dt)
    return out


def _waterline_now(system: System, state: FleetState, groups: list) -> np.ndarray:
    """(B, 2) the wetted added mass of each momentum-slamming hull at ``state``, its time."""
    out = np.zeros((system.count, 2))
    out[:, 1] = state.t
    for c in groups:
        if c.waterline is not None:
            out[c.group.index, 0] = c.waterline[0]
    return out


def _swept_now(system: System, state: FleetState, groups: list) -> np.ndarray | None:
    """(B, F, 3) Kerner's S_i v_i of each Kerner hull's triangles at ``state``, or None."""
    kerner = [c for c in groups if c.swept is not None]
    if not kerner:
        return None
    size = max(int(c.group.face_local.max()) + 1 for c in kerner)
    out = np.zeros((system.count, size, 3))
    for c in kerner:
        g = c.group
        out[g.index[g.face_owner], g.face_local] = c.swept[0]
    return out


def _integrate_coupled(system: System, state: FleetState, force: np.ndarray,
                       torque: np.ndarray, dt: float, into: tuple[np.ndarray, ...],
                       immersion: np.ndarray) -> None:
    """Overwrite the ``coupled`` boats' rows of ``into`` (p, q, v, w) by the 6 x 6 step."""
    i = np.array(system.coupled, dtype=np.intp)
    new = integrate_coupled(state.position[i], state.orientation[i], state.velocity[i],
                            state.angular_velocity[i], force[i], torque[i], system.mass[i],
                            system.inertia_tensor, _mass_inverse(system, immersion), dt)
    for array, rows in zip(into, new, strict=True):
        array[i] = rows


def _mass_inverse(system: System, immersion: np.ndarray) -> np.ndarray:
    """(C, 6, 6) (M_RB + s A)^-1 of the ``coupled`` boats, s their immersion (:mod:`.contact`).

    The precomputed inverse while every one of them is afloat (s = 1).
    """
    s = immersion[np.array(system.coupled, dtype=np.intp)]
    if np.all(s == 1.0):
        return system.mass_matrix_inverse
    return np.linalg.inv(system.rigid_mass_matrix + s[:, None, None] * system.added_mass_matrix)


def _memory_after(system: System, state: FleetState, after: FleetState, dt: float
                  ) -> np.ndarray:
    """(B, N) radiation memory states at t + dt (:func:`.radiation.advance`)."""
    memory = system.memory
    z = state.memory if state.memory is not None else np.zeros(memory.poles.shape, complex)
    if z.shape != memory.poles.shape:
        raise ValueError(f"state.memory: shape {z.shape}, the system's memory has "
                         f"{memory.poles.shape}")
    before = np.concatenate([state.velocity, state.angular_velocity], axis=1)
    now = np.concatenate([after.velocity, after.angular_velocity], axis=1)
    return advance(memory.poles, memory.input, z, before, now, dt)
