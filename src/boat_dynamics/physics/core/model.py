"""A boat's parameters, state, inputs and forces: the frozen dataclasses of the core.

SI units, body frame FLU, world frame ENU (REP-103). :mod:`boat_dynamics.physics.core.boat` steps
them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from boat_dynamics.physics.body.hull import BoxHull, HullMesh, box_mesh
from boat_dynamics.physics.body.rigid_body import mass_matrix, quat_from_euler, rotation_matrix
from boat_dynamics.physics.body.wrench import Wrench
from boat_dynamics.physics.force_models.anchor_line import AnchorLine
from boat_dynamics.physics.force_models.buoyancy import SamplePointBuoyancy
from boat_dynamics.physics.force_models.carriage import Carriage
from boat_dynamics.physics.force_models.control import ControlSettings
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.force_models.mooring import Mooring
from boat_dynamics.physics.force_models.propulsion import Propulsion
from boat_dynamics.physics.force_models.rudder import Rudder
from boat_dynamics.physics.force_models.wind import Windage
from boat_dynamics.physics.potential_flow.hull_lift import HullLift
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients, hydro_key
from boat_dynamics.physics.potential_flow.radiation import RadiationMemory
from boat_dynamics.physics.wave_making.interaction import MadeWavesModel
from boat_dynamics.physics.wave_making.kelvin_wake import ThinShip
from ocean_sim.physics.constants import GRAVITY, WATER_DENSITY
from ocean_sim.physics.waves import Precision

__all__ = [
    "RADIATION_MODELS",
    "BoatInputs",
    "BoatParams",
    "BoatState",
    "Derivation",
    "Forces",
    "RadiationModel",
    "coefficients_key",
    "hull_mesh",
    "initial_state",
    "reference_pose",
]


#: How a boat with potential-flow coefficients feels its own waves: ``cummins``, the 6 x 6
#: infinite-frequency added mass and the fitted radiation memory (:mod:`.radiation`);
#: ``resonance``, constant diagonal added mass and damping at the natural frequencies
#: (:func:`boat_dynamics.physics.core.tuning.potential_flow_at_resonance`), for comparison.
RadiationModel = Literal["cummins", "resonance"]
RADIATION_MODELS: tuple[RadiationModel, ...] = ("cummins", "resonance")


#: The water velocity the damping, hull drag and rudder take the boat's velocity against:
#: ``hull``, the mean over the wetted hull (or submerged sample points) of linear theory's
#: orbital velocity at each part's depth (:func:`ocean_sim.physics.waves.orbital_velocity`);
#: ``reference_point``, the surface water particle's above the hull reference point (the seed
#: notes' models' default: their hydrostatic hull has no wave excitation but that velocity;
#: ``hull`` is the default of a hull under the waves' pressure, ``froude_krylov`` or
#: ``linear``).
WaterVelocity = Literal["hull", "reference_point"]
WATER_VELOCITIES: tuple[WaterVelocity, ...] = ("hull", "reference_point")


@dataclass(frozen=True)
class Derivation:
    """What :func:`boat_dynamics.physics.core.pipeline.init` derives for a boat, once.

    From the boat's own buoyancy model in flat water (:mod:`boat_dynamics.physics.core.tuning`):
    always its equilibrium height (``control.height_offset``, which the kinematic modes
    track; a hull that sinks is refused), and the damping a scenario left to derive.

    Attributes:
        critical_ratio: (3,) damping ratios [heave, roll, pitch] whose critical damping
            2 zeta sqrt(k m) is added to ``damping_linear``; None = none.
        quadratic: replace ``damping_quadratic`` by the default drag of the hull at its
            equilibrium draft (:func:`boat_dynamics.physics.core.tuning.default_drag`).
        added_mass: set ``added_mass`` from the boat's ``hydro`` coefficients: heave, roll and
            pitch at their natural frequencies, surge, sway and yaw at infinite frequency.
        radiation_damping: set ``radiation_damping`` to B_ii at the natural frequency in
            heave, roll and pitch (from ``hydro``).
        memory: set ``added_mass_matrix`` to ``hydro``'s A_inf and ``radiation_memory`` to
            its fitted memory (the Cummins equation).
        estimate: the key of a hull that asked for its coefficient file (``coefficients:
            auto``) and has none: ``hydro`` becomes :func:`.hydro.estimate` at its equilibrium.
        windage: the boat's windage with NaN where it is to be derived from the hull above
            its equilibrium waterline (:func:`.wind.windage_of_hull`), or None: none.
        mooring_period: s, the natural period of a soft mooring (:func:`.mooring.soft_mooring`,
            with the derived added mass) holding the boat where it starts, or None: free.
        hull_lift: set ``hull_lift`` from the hull at its equilibrium and the coefficients'
            A22 (:func:`.hull_lift.trailing_sections`); needs ``memory``.
        thin_ship: set ``thin_ship`` from the hull at its equilibrium
            (:func:`.kelvin_wake.thin_ship`): the boat makes a wake.
    """

    critical_ratio: np.ndarray | None = None
    quadratic: bool = False
    added_mass: bool = False
    radiation_damping: bool = False
    memory: bool = False
    estimate: str | None = None
    windage: Windage | None = None
    mooring_period: float | None = None
    hull_lift: bool = False
    thin_ship: bool = False


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
        propulsion: the thruster, or a tuple of thrusters (at most
            :data:`~.propulsion.MAX_THRUSTERS`); :attr:`thrusters` is always the tuple.
        rudder: the rudder.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.
        min_wavelength: m, wave components shorter than this do not act on the boat.
        wave_precision: ``float64`` or ``float32``, precision of the boat's surface queries
            (:func:`ocean_sim.physics.waves.sample_surface`).
        keel_rate: 1/s, the keel's velocity reflection (0 = off).
        stokes_drift: add the sea's Stokes drift to the water velocity.
        control: the control mode and its settings.
        damping_decay: (6,) 1/s, the seed notes' (Unity's) per-step velocity decay per body
            DOF, v <- v / (1 + dt c), applied after each integration step (arcade; not a
            force, so not in wrench/damping); zeros = off.
        inertia_products: (3,) kg m^2, products of inertia [Ixy, Ixz, Iyz] = integral(x y dm),
            ... about the centre of mass (body axes); the tensor holds them negated.
        derive: what ``pipeline.init`` still has to derive (a scenario's boats), or None once
            derived (or for parameters given in full).
        radiation_damping: (6,) N/(m/s) and N m/(rad/s), wave radiation damping per body dof,
            on the body's own velocity
            (:func:`boat_dynamics.physics.force_models.damping.radiation_damping`).
        hydro: the hull's potential-flow coefficients
        (:mod:`boat_dynamics.physics.potential_flow.hydro`),
            or None: the diffraction force, and the added mass and radiation damping
            ``derive`` may ask for.
        added_mass_matrix: (6, 6) kg, kg m, kg m^2, the full added mass about the centre of
            mass (body axes), or None; when set it replaces ``added_mass`` and the boat is
            integrated with the coupled mass matrix
            (:func:`boat_dynamics.physics.body.rigid_body.integrate_coupled`).
        radiation_memory: the Cummins radiation memory
        (:mod:`boat_dynamics.physics.potential_flow.radiation`),
            or None.
        mooring: a soft mooring holding the boat on station (:mod:`.mooring`; the RAO runs
            of :mod:`.seakeeping`, the ``mooring`` key), or None.
        carriage: a towing carriage prescribing its speed along a line, heave, roll and
            pitch free (:mod:`.carriage`, the ``carriage`` key), or None.
        anchor_line: an elastic line to an anchor on the sea floor (:mod:`.anchor_line`: a
            buoy's mooring, an anchored boat; the ``anchor_line`` key), or None.
        water_velocity: where the water velocity of the damping is taken
            (:data:`WaterVelocity`).
        windage: what the wind acts on (:mod:`.wind`), or None: no wind load.
        hull_lift: the trailing sections whose lift acts at speed (:mod:`.hull_lift`), or
            None: no hull lift.
        made_waves: the waves the boat makes that the other boats feel
            (:mod:`.interaction`).
        thin_ship: its hull's half-breadths for its Kelvin wake (:mod:`.kelvin_wake`), or
            None: derived by ``pipeline.init`` when ``derive.thin_ship`` asks, else no wake.
    """

    hull: BoxHull
    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    buoyancy: MeshBuoyancy | SamplePointBuoyancy
    damping_linear: np.ndarray
    damping_quadratic: np.ndarray
    added_mass: np.ndarray
    propulsion: Propulsion | tuple[Propulsion, ...]
    rudder: Rudder
    water_density: float = WATER_DENSITY
    gravity: float = GRAVITY
    min_wavelength: float = 0.0
    wave_precision: Precision = "float64"
    keel_rate: float = 0.0
    stokes_drift: bool = False
    control: ControlSettings = field(default_factory=ControlSettings)
    inertia_products: np.ndarray = field(default_factory=lambda: np.zeros(3))
    damping_decay: np.ndarray = field(default_factory=lambda: np.zeros(6))
    derive: Derivation | None = None
    radiation_damping: np.ndarray = field(default_factory=lambda: np.zeros(6))
    hydro: HydroCoefficients | None = None
    added_mass_matrix: np.ndarray | None = None
    radiation_memory: RadiationMemory | None = None
    mooring: Mooring | None = None
    carriage: Carriage | None = None
    anchor_line: AnchorLine | None = None
    water_velocity: WaterVelocity = "reference_point"
    windage: Windage | None = None
    hull_lift: HullLift | None = None
    made_waves: MadeWavesModel = "none"
    thin_ship: ThinShip | None = None

    @property
    def thrusters(self) -> tuple[Propulsion, ...]:
        """Every thruster of the boat (one for a single ``propulsion``)."""
        p = self.propulsion
        return p if isinstance(p, tuple) else (p,)


@dataclass(frozen=True)
class BoatState:
    """The state of one boat at time ``t``.

    Attributes:
        t: s, simulation time.
        position: (3,) m, centre of mass, world frame (ENU).
        orientation: (4,) unit quaternion (x, y, z, w), body (FLU) to world.
        velocity: (3,) m/s, velocity of the centre of mass, body frame.
        angular_velocity: (3,) rad/s, body frame.
        throttle: -1..1, the actual thrust fraction (lags the command with a time constant):
            one for every thruster, or (T,) per thruster.
        control_weight: 0..1, how far the control mode has taken over since it was selected.
        memory: (N,) complex, the state of the boat's radiation memory
            (:mod:`boat_dynamics.physics.potential_flow.radiation`), or None: calm (all zero).
        slamming: (2,) the hull's wetted added mass (kg) at the previous step and that step's
            time (s) (:mod:`boat_dynamics.physics.force_models.slamming`), or None: no previous
            step.
        swept: (F, 3) m^3/s, Kerner's S_i v_i per hull triangle at the previous step, or None.
    """

    t: float
    position: np.ndarray
    orientation: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    throttle: float | np.ndarray = 0.0
    control_weight: float = 1.0
    memory: np.ndarray | None = None
    slamming: np.ndarray | None = None
    swept: np.ndarray | None = None


@dataclass(frozen=True)
class BoatInputs:
    """Actuator commands, already validated and within range.

    Attributes:
        throttle: -1..1, commanded fraction of max thrust (negative = reverse): one for every
            thruster, or one per thruster (a sequence, thruster j at j).
        rudder: rad, + turns the bow to port (rudder and/or steerable nozzle).
        thruster_angle: rad per thruster, the steering angles of steerable thrusters of a
            thruster list, or None: the rudder angle.
    """

    throttle: float | Sequence[float] = 0.0
    rudder: float = 0.0
    thruster_angle: Sequence[float] | None = None


@dataclass(frozen=True)
class Forces:
    """Every wrench acting on the boat, body frame, about the centre of mass.

    ``total`` is the net wrench (the sources plus gravity) that the integrator uses;
    ``diffraction`` is zero for a boat without potential-flow coefficients, ``slamming`` for a
    hull without a slamming model or not slamming, ``mooring`` for a boat not moored, ``wind``
    in calm air or for a boat without windage, ``collision`` for a boat touching no obstacle,
    ``made_waves`` (the other boats' waves, :mod:`.interaction`) for a lone boat, one
    without coefficients, or where no other boat's waves reach.
    """

    buoyancy: Wrench
    damping: Wrench
    drag: Wrench
    thrust: Wrench
    rudder: Wrench
    diffraction: Wrench
    slamming: Wrench
    mooring: Wrench
    wind: Wrench
    collision: Wrench
    made_waves: Wrench
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


def hull_mesh(params: BoatParams) -> HullMesh:
    """The boat's hull mesh: the mesh model's, or the box of a sample-point boat."""
    if isinstance(params.buoyancy, MeshBuoyancy):
        return params.buoyancy.mesh
    return box_mesh(params.hull)


def coefficients_key(params: BoatParams, depth: float) -> str:
    """The key of the boat's potential-flow coefficient file (:func:`.hydro.hydro_key`).

    Of the parameters as a scenario gives them: ``pipeline.init`` may refine a
    ``froude_krylov`` hull's mesh, which is the same hull.

    Args:
        params: the boat, before ``pipeline.init``.
        depth: m, the water depth (inf = deep).
    """
    mesh = hull_mesh(params)
    return hydro_key(mesh.vertices, mesh.faces, params.mass, params.center_of_mass,
                     mass_matrix(params.mass, params.inertia, params.inertia_products),
                     params.water_density, params.gravity, depth)

