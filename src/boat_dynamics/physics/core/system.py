"""The batched core's data: a frozen :class:`System` of B boats and their state, inputs, forces.

A boat step costs a few hundred numpy calls whatever the boat; called per boat, their fixed
cost (about 1-3 us each) dominates. So the pipeline (:mod:`boat_dynamics.physics.core.pipeline`)
steps every boat at once: boats that take the same code path (same buoyancy model and options,
thruster and rudder kinds, ...) form a :class:`Group` whose parameters are stacked ((G,) and
(G, 3) arrays) and whose hull triangles or sample points are concatenated, each element tagged
with its boat (``owner``); per-boat sums come from
:func:`boat_dynamics.physics.body.wrench.sum_by_owner`.

Parameters (:class:`System`) are kept apart from the state (:class:`FleetState`), as in brax's
``System`` and ``State``. Everything here is frozen and holds no cache.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from boat_dynamics.physics.body.rigid_body import inertia_tensor
from boat_dynamics.physics.body.wrench import Wrench
from boat_dynamics.physics.core.model import (
    BoatInputs,
    BoatParams,
    BoatState,
    Forces,
    WaterVelocity,
    hull_mesh,
)
from boat_dynamics.physics.force_models.anchor_line import AnchorLine
from boat_dynamics.physics.force_models.buoyancy import SamplePointBuoyancy
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.force_models.mooring import Mooring
from boat_dynamics.physics.force_models.propulsion import MAX_THRUSTERS, Propulsion
from boat_dynamics.physics.force_models.rudder import Rudder
from boat_dynamics.physics.potential_flow.hull_lift import HullLift
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from boat_dynamics.physics.potential_flow.radiation import MAX_ORDER, RadiationMemory
from boat_dynamics.physics.wave_making.interaction import MadeWaves, made_waves_build
from boat_dynamics.physics.world.footprints import Footprints
from ocean_sim.physics.waves import Precision

__all__ = ["DIVERGED_RATE", "DIVERGED_SPEED", "ExcitationBatch", "FleetForces", "FleetInputs",
           "FleetState", "Group", "System"]

#: m/s and rad/s beyond which a boat's state has diverged (:meth:`FleetState.diverged`).
DIVERGED_SPEED = 1000.0
DIVERGED_RATE = 1000.0


@dataclass(frozen=True)
class FleetState:
    """The states of B boats at one time ``t``.

    Attributes:
        t: s, simulation time (shared).
        position: (B, 3) m, centres of mass, world frame (ENU).
        orientation: (B, 4) unit quaternions (x, y, z, w), body (FLU) to world.
        velocity: (B, 3) m/s, body frame.
        angular_velocity: (B, 3) rad/s, body frame.
        throttle: (B, T) actual thrust fractions, thruster j of a boat in column j
            (T = :data:`~.propulsion.MAX_THRUSTERS`; columns past a boat's thrusters unused).
        control_weight: (B,) 0..1, how far each control mode has taken over.
        memory: (B, N) complex, the boats' radiation memory states
            (:mod:`boat_dynamics.physics.potential_flow.radiation`), or None: all calm (zero).
        slamming: (B, 2) the wetted added mass (kg) of each hull at the previous step and that
            step's time (s) (:mod:`boat_dynamics.physics.force_models.slamming`), or None: no
            previous step.
        swept: (B, F, 3) m^3/s, Kerner's S_i v_i of each hull triangle at the previous step
            (padded with zeros to the largest mesh), or None.
    """

    t: float
    position: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    throttle: np.ndarray
    control_weight: np.ndarray
    memory: np.ndarray | None = None
    slamming: np.ndarray | None = None
    swept: np.ndarray | None = None

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
                   np.array([_per_thruster(s.throttle) for s in states]),
                   np.array([s.control_weight for s in states], dtype=float),
                   _stack_memory([s.memory for s in states]),
                   None if all(s.slamming is None for s in states) else np.array(
                       [(0.0, states[0].t) if s.slamming is None else s.slamming
                        for s in states], dtype=float),
                   _stack_swept([s.swept for s in states]))

    def diverged(self) -> np.ndarray:
        """(B,) bool: the boats whose state diverged.

        A NaN or infinite pose, velocity or radiation memory, or a speed over
        :data:`DIVERGED_SPEED` or a rate over :data:`DIVERGED_RATE`, which no boat reaches (an
        unstable integration passes them a step or two before it overflows).
        """
        with np.errstate(all="ignore"):  # a NaN or an infinity anywhere makes the sum one
            v2 = np.einsum("ij,ij->i", self.velocity, self.velocity)
            w2 = np.einsum("ij,ij->i", self.angular_velocity, self.angular_velocity)
            total = self.position.sum(axis=1) + self.orientation.sum(axis=1) + v2 + w2
            if self.memory is not None:
                total += self.memory.view(float).sum(axis=1)
            return ~np.isfinite(total) | (v2 > DIVERGED_SPEED**2) | (w2 > DIVERGED_RATE**2)

    def held(self, before: FleetState, boats: np.ndarray) -> FleetState:
        """This state with the rows of ``boats`` ((B,) bool) as in ``before``, at rest.

        A boat whose state went non-finite is stopped so: where it last was, its velocities,
        thrust and radiation memory zero; the others' rows are this state's.
        """
        def pick(now: np.ndarray | None, then: np.ndarray | None, zero: bool = False):
            if now is None or then is None:
                return now
            mask = boats.reshape((-1,) + (1,) * (now.ndim - 1))
            return np.where(mask, np.zeros_like(then) if zero else then, now)

        return replace(self, position=pick(self.position, before.position),
                       orientation=pick(self.orientation, before.orientation),
                       velocity=pick(self.velocity, before.velocity, True),
                       angular_velocity=pick(self.angular_velocity, before.angular_velocity,
                                             True),
                       throttle=pick(self.throttle, before.throttle, True),
                       control_weight=pick(self.control_weight, before.control_weight),
                       memory=pick(self.memory, before.memory, True),
                       slamming=pick(self.slamming, before.slamming),
                       swept=pick(self.swept, before.swept, True))

    def boat(self, i: int) -> BoatState:
        """Boat ``i``'s state (arrays are copies: the fleet state stays frozen)."""
        return BoatState(self.t, self.position[i].copy(), self.orientation[i].copy(),
                         self.velocity[i].copy(), self.angular_velocity[i].copy(),
                         self.throttle[i].copy(), float(self.control_weight[i]),
                         None if self.memory is None else self.memory[i].copy(),
                         None if self.slamming is None else self.slamming[i].copy(),
                         None if self.swept is None else self.swept[i].copy())


def _per_thruster(values) -> np.ndarray:
    """(T,) one value per thruster slot: a number for every thruster, or one per thruster."""
    v = np.asarray(values, dtype=float)
    if v.ndim == 0:
        return np.full(MAX_THRUSTERS, float(v))
    out = np.zeros(MAX_THRUSTERS)
    out[:v.shape[0]] = v
    return out


def _stack_swept(swept: Sequence[np.ndarray | None]) -> np.ndarray | None:
    """(B, F, 3) Kerner's swept volumes, padded with zeros; None when no boat has them."""
    if all(x is None for x in swept):
        return None
    size = max(x.shape[0] for x in swept if x is not None)
    out = np.zeros((len(swept), size, 3))
    for i, x in enumerate(swept):
        if x is not None:
            out[i, :x.shape[0]] = x
    return out


def _stack_memory(memories: Sequence[np.ndarray | None]) -> np.ndarray | None:
    """(B, N) complex memory states, a calm boat's (None) as zeros; None when all are calm."""
    if all(m is None for m in memories):
        return None
    sizes = {m.shape for m in memories if m is not None}
    if len(sizes) != 1:
        raise ValueError(f"radiation memories of different sizes {sorted(sizes)}")
    zero = np.zeros(sizes.pop(), dtype=complex)
    return np.array([zero if m is None else m for m in memories], dtype=complex)


@dataclass(frozen=True)
class FleetInputs:
    """Validated commands of B boats.

    Attributes:
        throttle: (B,) throttle fractions (every thruster of a boat), or (B, T) per thruster.
        rudder: (B,) rudder angles, rad.
        thruster_angle: (B, T) rad, steering angles of steerable thrusters of thruster
            lists, or None: the rudder angles.
    """

    throttle: np.ndarray
    rudder: np.ndarray
    thruster_angle: np.ndarray | None = None

    @classmethod
    def stack(cls, inputs: Sequence[BoatInputs]) -> FleetInputs:
        """From one BoatInputs per boat."""
        angles = None
        if any(u.thruster_angle is not None for u in inputs):
            angles = np.array([_per_thruster(u.rudder if u.thruster_angle is None
                                             else u.thruster_angle) for u in inputs])
        if all(np.ndim(u.throttle) == 0 for u in inputs):
            return cls(np.array([u.throttle for u in inputs], dtype=float),
                       np.array([u.rudder for u in inputs], dtype=float), angles)
        return cls(np.array([_per_thruster(u.throttle) for u in inputs]),
                   np.array([u.rudder for u in inputs], dtype=float), angles)

    def throttle_of(self, j: int) -> np.ndarray:
        """(B,) the throttle commands of every boat's thruster ``j``."""
        return self.throttle if self.throttle.ndim == 1 else self.throttle[:, j]

    def angle_of(self, j: int) -> np.ndarray:
        """(B,) rad, the steering angles of every boat's thruster ``j`` (if steerable)."""
        return self.rudder if self.thruster_angle is None else self.thruster_angle[:, j]


@dataclass(frozen=True)
class FleetForces(Forces):
    """:class:`~.model.Forces` of B boats: each wrench holds (B, 3) arrays."""

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
    The numeric fields of the parameter dataclasses are typed ``Real`` (a float for one boat,
    a (G,) array for a group; :data:`boat_dynamics.physics.body.wrench.Real`), so the stacked
    object is of its declared type.
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
    return (kind, _structure(b), tuple(_structure(t) for t in p.thrusters), _structure(p.rudder),
            p.stokes_drift, p.min_wavelength, p.wave_precision, p.water_velocity)


@dataclass(frozen=True)
class Group:
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
        propulsion: the thrusters, each stacked over the group's boats.
        rudder: stacked rudder parameters.
        length: (G,) m, hull lengths.
        stokes_drift: add the Stokes drift of the (filtered) sea to the water velocity.
        min_wavelength: m, the group's wave filter.
        wave_precision: the precision of the group's surface queries.
        water_velocity: where its damping takes the water's velocity.
        face_local: (F,) int, each triangle's index in its own boat's mesh (mesh group).
    """

    index: np.ndarray
    mesh: MeshBuoyancy | None
    points: SamplePointBuoyancy | None
    body: np.ndarray
    owner: np.ndarray
    faces: np.ndarray | None
    face_owner: np.ndarray | None
    propulsion: tuple[Propulsion, ...]
    rudder: Rudder
    length: np.ndarray
    stokes_drift: bool
    min_wavelength: float
    wave_precision: Precision
    water_velocity: WaterVelocity
    face_local: np.ndarray | None = None

    @classmethod
    def build(cls, params: Sequence[BoatParams], index: np.ndarray) -> Group:
        """The group of boats ``params`` (same :func:`_group_key`) at fleet places ``index``."""
        first = params[0]
        if isinstance(first.buoyancy, MeshBuoyancy):
            meshes = [p.buoyancy.mesh for p in params]
            counts = [m.vertices.shape[0] for m in meshes]
            offsets = np.cumsum([0, *counts[:-1]])
            faces = np.concatenate([m.faces + o for m, o in zip(meshes, offsets, strict=True)])
            face_owner = np.concatenate([np.full(m.faces.shape[0], i, dtype=np.intp)
                                         for i, m in enumerate(meshes)])
            face_local = np.concatenate([np.arange(m.faces.shape[0]) for m in meshes])
            mesh = replace(first.buoyancy, drag=_stack([p.buoyancy.drag for p in params]),
                           slamming=_stack([p.buoyancy.slamming for p in params]))
            body = np.concatenate([m.vertices for m in meshes])
            points = None
        else:
            models = [p.buoyancy for p in params]
            counts = [m.points.shape[0] for m in models]
            body = np.concatenate([m.points for m in models])
            points = replace(_stack(models, skip=("points",)), points=body)
            mesh = faces = face_owner = face_local = None
        owner = np.concatenate([np.full(n, i, dtype=np.intp) for i, n in enumerate(counts)])
        return cls(index, mesh, points, body, owner, faces, face_owner,
                   tuple(_stack([p.thrusters[j] for p in params])
                         for j in range(len(first.thrusters))),
                   _stack([p.rudder for p in params]),
                   np.array([p.hull.length for p in params]), first.stokes_drift,
                   first.min_wavelength, first.wave_precision, first.water_velocity,
                   face_local)


@dataclass(frozen=True)
class System:
    """B boats prepared for stepping together: parameters stacked once, per group and fleet-wide.

    Build with :meth:`build`; a boat whose parameters change (its control mode, say) needs a
    new System. Per-boat arrays are (B,) or (B, 3), in the order of ``params``.

    Attributes:
        params: the boats' parameters.
        count: B, the number of boats.
        groups: the boats grouped by code path.
        mass: (B,) kg.
        center_of_mass: (B, 3) m, body frame, from the hull reference point.
        inertia: (B, 3) kg m^2, principal moments.
        effective_mass: (B, 3) kg, mass plus surge/sway/heave added mass.
        effective_inertia: (B, 3) kg m^2, moments plus roll/pitch/yaw added inertia.
        inertia_products: (B, 3) kg m^2, or None when every boat's are zero.
        decay: (B, 6) 1/s, the notes' velocity decay, or None when off for every boat.
        radiation: (B, 6) wave radiation damping on the body velocity, or None when zero for
            every boat.
        damping_linear: (B, 6) N/(m/s), N m/(rad/s).
        damping_quadratic: (B, 6) N/(m/s)^2, N m/(rad/s)^2.
        water_density: (B,) kg/m^3.
        gravity: (B,) m/s^2.
        keel_rate: (B,) 1/s.
        special: the boats not in ``dynamic`` control mode.
        diffracting: the boats with potential-flow coefficients (a diffraction force).
        excitation: those boats in batches evaluated in one call each: boats sharing a
            coefficient set, a wave filter and a pressure model (:class:`ExcitationBatch`).
        coupled: the boats with a 6 x 6 added mass (``added_mass_matrix``), integrated with
            :func:`boat_dynamics.physics.body.rigid_body.integrate_coupled`.
        mass_matrix_inverse: (C, 6, 6) (M_RB + A)^-1 of the ``coupled`` boats, or None.
        added_mass_matrix: (C, 6, 6) their added mass A, or None.
        rigid_mass_matrix: (C, 6, 6) their M_RB, or None.
        inertia_tensor: (C, 3, 3) kg m^2, their rigid-body inertia tensors, or None.
        memory: the boats' radiation memories stacked and padded to N =
            :data:`~boat_dynamics.physics.potential_flow.radiation.MAX_ORDER` modes, or the most
            any boat has (a file with gap modes: up to 96) ((B, N) poles, (B, N, 6)
            input, (B, 6, N) output; zero for a boat without one), or None when no boat has
            one.
        mooring: the boats' moorings stacked ((B, 3) anchor, stiffness, damping; zero for a
            boat not moored), or None when no boat is moored.
        anchor_lines: the boats' anchor lines stacked ((B, 3) anchor and fairlead, (B,)
            length, stiffness, damping; slack and stiffness zero for a boat without one), or
            None when no boat has one.
        windage: (B, 6) A_F, A_L, L_oa, c_x, c_y, c_n (:mod:`.wind`; zero for a boat without
            windage), or None when no boat has any.
        windage_centre: (B, 3) m, body frames, where the wind's force acts, or None.
        towed: the boats on a towing carriage (:mod:`.carriage`).
        lift: the boats' trailing sections stacked ((B, 2) kg/m a22, (B, 2, 3) m positions;
            zero for a boat without hull lift), or None when no boat has any
            (:mod:`.hull_lift`).
        made_waves: the boats that make waves and those that feel them
            (:mod:`.interaction`), or None when no boat feels another's waves (a lone
            boat, or none making any).
    """

    params: tuple[BoatParams, ...]
    count: int
    groups: tuple[Group, ...]
    mass: np.ndarray
    center_of_mass: np.ndarray
    inertia: np.ndarray
    effective_mass: np.ndarray
    effective_inertia: np.ndarray
    inertia_products: np.ndarray | None
    decay: np.ndarray | None
    radiation: np.ndarray | None
    damping_linear: np.ndarray
    damping_quadratic: np.ndarray
    water_density: np.ndarray
    gravity: np.ndarray
    keel_rate: np.ndarray
    special: tuple[int, ...]
    diffracting: tuple[int, ...]
    excitation: tuple[ExcitationBatch, ...] = ()
    coupled: tuple[int, ...] = ()
    mass_matrix_inverse: np.ndarray | None = None
    added_mass_matrix: np.ndarray | None = None
    rigid_mass_matrix: np.ndarray | None = None
    inertia_tensor: np.ndarray | None = None
    memory: RadiationMemory | None = None
    mooring: Mooring | None = None
    anchor_lines: AnchorLine | None = None
    windage: np.ndarray | None = None
    windage_centre: np.ndarray | None = None
    towed: tuple[int, ...] = ()
    lift: HullLift | None = None
    made_waves: MadeWaves | None = None

    @cached_property
    def footprints(self) -> Footprints:
        """The hulls as contact and the lidars see them (their convex prisms), once, when used.

        Derived from the boats' own hulls (constant: a System is frozen); a lone boat in a
        world without obstacles never asks, and pays nothing.
        """
        return Footprints.build([hull_mesh(p).vertices for p in self.params])

    def apart(self) -> System:
        """The same boats, each on a sea of its own: none feels the waves another makes.

        For boats stepped together that are separate experiments (copies of one boat in
        :func:`.trials.sea_trials`, the environments of a vectorised Gymnasium env).
        """
        return self if self.made_waves is None else replace(self, made_waves=None)

    @classmethod
    def build(cls, params: Sequence[BoatParams]) -> System:
        """The system of boats ``params`` (at least one)."""
        ps = tuple(params)
        keys: dict[tuple, list[int]] = {}
        for i, p in enumerate(ps):
            keys.setdefault(_group_key(p), []).append(i)
        groups = tuple(Group.build([ps[i] for i in members], np.array(members, dtype=np.intp))
                       for members in keys.values())
        mass = np.array([p.mass for p in ps])
        inertia = np.array([p.inertia for p in ps], dtype=float)
        added = np.array([p.added_mass for p in ps], dtype=float)
        products = np.array([p.inertia_products for p in ps], dtype=float)
        decay = np.array([p.damping_decay for p in ps], dtype=float)
        radiation = np.array([p.radiation_damping for p in ps], dtype=float)
        return cls(
            params=ps, count=len(ps), groups=groups, mass=mass,
            center_of_mass=np.array([p.center_of_mass for p in ps], dtype=float),
            inertia=inertia, effective_mass=mass[:, None] + added[:, :3],
            effective_inertia=inertia + added[:, 3:],
            inertia_products=products if np.any(products != 0.0) else None,
            decay=decay if np.any(decay > 0.0) else None,
            radiation=radiation if np.any(radiation > 0.0) else None,
            damping_linear=np.array([p.damping_linear for p in ps], dtype=float),
            damping_quadratic=np.array([p.damping_quadratic for p in ps], dtype=float),
            water_density=np.array([p.water_density for p in ps]),
            gravity=np.array([p.gravity for p in ps]),
            keel_rate=np.array([p.keel_rate for p in ps]),
            special=tuple(i for i, p in enumerate(ps) if p.control.mode != "dynamic"),
            diffracting=tuple(i for i, p in enumerate(ps) if p.hydro is not None),
            excitation=_excitation_batches(ps),
            **_coupling(ps),
            mooring=_moorings(ps),
            anchor_lines=_anchor_lines(ps),
            **_windages(ps),
            towed=tuple(i for i, p in enumerate(ps) if p.carriage is not None),
            lift=_lifts(ps),
            made_waves=made_waves_build(ps) if len(ps) > 1 else None,
        )


@dataclass(frozen=True)
class ExcitationBatch:
    """Boats whose wave excitation is evaluated in one call (:attr:`System.excitation`).

    Attributes:
        index: (K,) int, the boats' places in the fleet.
        hydro: their shared coefficients.
        min_wavelength: m, their wave filter.
        linear: their pressure is ``linear`` (the incident waves' Froude-Krylov force comes
            from the coefficients too).
    """

    index: np.ndarray
    hydro: HydroCoefficients
    min_wavelength: float
    linear: bool


def _excitation_batches(ps: Sequence[BoatParams]) -> tuple[ExcitationBatch, ...]:
    """The boats with coefficients, batched by coefficient set, wave filter and pressure."""
    batches: dict[tuple[int, float, bool], list[int]] = {}
    for i, p in enumerate(ps):
        if p.hydro is not None:
            linear = isinstance(p.buoyancy, MeshBuoyancy) and p.buoyancy.pressure == "linear"
            batches.setdefault((id(p.hydro), p.min_wavelength, linear), []).append(i)
    return tuple(ExcitationBatch(np.array(members, dtype=np.intp), ps[members[0]].hydro,
                                 ps[members[0]].min_wavelength, linear)
                 for (_, _, linear), members in batches.items())


def _lifts(ps: Sequence[BoatParams]) -> HullLift | None:
    """The boats' trailing sections stacked, or None when no boat has hull lift."""
    if all(p.hull_lift is None for p in ps):
        return None
    none = HullLift(np.zeros(2), np.zeros((2, 3)))
    lifts = [none if p.hull_lift is None else p.hull_lift for p in ps]
    return HullLift(np.array([h.added_mass for h in lifts], dtype=float),
                    np.array([h.position for h in lifts], dtype=float))


def _windages(ps: Sequence[BoatParams]) -> dict:
    """The :class:`System` fields of the boats' windage (None when no boat has any)."""
    if all(p.windage is None for p in ps):
        return {}
    rows = np.zeros((len(ps), 6))
    centres = np.zeros((len(ps), 3))
    for i, p in enumerate(ps):
        w = p.windage
        if w is not None:
            rows[i] = [w.frontal_area, w.lateral_area, w.length, *w.coefficients]
            centres[i] = w.centre
    return {"windage": rows, "windage_centre": centres}


def _moorings(ps: Sequence[BoatParams]) -> Mooring | None:
    """The boats' moorings stacked ((B, 3) each), or None when none is moored."""
    if all(p.mooring is None for p in ps):
        return None
    free = Mooring(np.zeros(3), np.zeros(3), np.zeros(3))
    moorings = [free if p.mooring is None else p.mooring for p in ps]
    return Mooring(*(np.array([getattr(m, f) for m in moorings], dtype=float)
                     for f in ("anchor", "stiffness", "damping")))


def _anchor_lines(ps: Sequence[BoatParams]) -> AnchorLine | None:
    """The boats' anchor lines stacked, or None when no boat has one."""
    if all(p.anchor_line is None for p in ps):
        return None
    free = AnchorLine(np.zeros(3), np.zeros(3), 1.0, 0.0, 0.0)
    lines = [free if p.anchor_line is None else p.anchor_line for p in ps]
    return AnchorLine(*(np.array([getattr(m, f) for m in lines], dtype=float)
                        for f in ("anchor", "fairlead", "length", "stiffness", "damping")))


def _coupling(ps: Sequence[BoatParams]) -> dict:
    """The :class:`System` fields of boats with a 6 x 6 added mass and a radiation memory."""
    coupled = tuple(i for i, p in enumerate(ps) if p.added_mass_matrix is not None)
    out: dict = {"coupled": coupled}
    if coupled:
        tensors = np.array([inertia_tensor(ps[i].inertia, ps[i].inertia_products)
                            for i in coupled])
        rigid = np.zeros((len(coupled), 6, 6))
        for k, i in enumerate(coupled):
            rigid[k, :3, :3] = ps[i].mass * np.eye(3)
            rigid[k, 3:, 3:] = tensors[k]
        added = np.array([ps[i].added_mass_matrix for i in coupled], dtype=float)
        out.update(mass_matrix_inverse=np.linalg.inv(rigid + added), inertia_tensor=tensors,
                   added_mass_matrix=added, rigid_mass_matrix=rigid)
    memories = [p.radiation_memory for p in ps]
    if any(m is not None for m in memories):
        calm = RadiationMemory(np.zeros(0, complex), np.zeros((0, 6), complex),
                               np.zeros((6, 0), complex), 0.0)
        order = max(MAX_ORDER, *(m.poles.shape[0] for m in memories if m is not None))
        memories = [(calm if m is None else m).padded(order) for m in memories]
        out["memory"] = RadiationMemory(np.array([m.poles for m in memories]),
                                        np.array([m.input for m in memories]),
                                        np.array([m.output for m in memories]),
                                        max(m.error for m in memories))
    return out
