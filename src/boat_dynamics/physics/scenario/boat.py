"""One boat of ``boats``: its blocks read in the order of the keys, into a :class:`BoatSpec`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from boat_dynamics.physics.body.hull import (
    BoxHull,
    HullMesh,
    HullMeshError,
    box_mesh,
    cylinder_mesh,
    load_mesh,
)
from boat_dynamics.physics.body.rigid_body import inertia_tensor
from boat_dynamics.physics.core.commands import CommandScript
from boat_dynamics.physics.core.model import (
    RADIATION_MODELS,
    WATER_VELOCITIES,
    BoatParams,
    BoatState,
    Derivation,
    RadiationModel,
    WaterVelocity,
    coefficients_key,
    initial_state,
)
from boat_dynamics.physics.force_models.anchor_line import AnchorLine
from boat_dynamics.physics.force_models.carriage import Carriage
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.force_models.wind import DEFAULT_WIND_COEFFICIENTS, Windage
from boat_dynamics.physics.potential_flow.hull_lift import HULL_LIFT_MODELS
from boat_dynamics.physics.potential_flow.hydro import (
    HydroCoefficients,
    HydroFileError,
    coefficient_directories,
    find_coefficients,
    load_coefficients,
)
from boat_dynamics.physics.scenario.models import (
    buoyancy_block,
    control_block,
    keel_block,
    propulsion_block,
    rudder_block,
)
from boat_dynamics.physics.scenario.read import (
    ROS_NAME_RULE,
    choice,
    describe,
    flag,
    integer,
    is_ros_name,
    mapping,
    number,
    only,
    vector,
)
from boat_dynamics.physics.scenario.sensors import sensors_block
from boat_dynamics.physics.scenario.specs import BoatSpec, ScenarioError, SimulationSettings
from boat_dynamics.physics.wave_making.interaction import (
    MADE_WAVES_MODELS,
    MadeWavesModel,
)

#: Damping ratios [heave, roll, pitch] of the default linear damping (critical-damping helper).
DEFAULT_CRITICAL_RATIO = (0.2, 0.1, 0.2)

#: The same with potential-flow coefficients, whose radiation damps the waves a hull makes: the
#: viscous share potential flow lacks, flow separation at the bilges and skin friction, about
#: 10 % of critical in roll for a hull with sharp bilges and no bilge keels (Ikeda, Himeno &
#: Tanaka 1978; Journee & Massie 2001, "Offshore Hydromechanics", sec. 8.3); none in heave and
#: pitch, where the radiation dominates (strip theory adds none; the quadratic heave drag of
#: ``damping.quadratic``, C_d 1 on L B, takes a flat bottom's vortices). Journee's (1992) Wigley I
#: towed at Fn 0.3 into a head sea of 1.25 L heaved 2.52 m/m; with 10 % of critical in heave and
#: pitch it heaved 1.28, without 2.45 (tests/boat_dynamics/physics/experiments/test_towing_tank.py).
RADIATING_CRITICAL_RATIO = (0.0, 0.1, 0.0)


#: The hull types, and the keys each reads.
HULL_TYPES = ("box", "cylinder", "mesh")
_HULL_TYPE_KEYS = {"box": ("length", "beam", "height", "subdivisions"),
                   "cylinder": ("radius", "height", "subdivisions"), "mesh": ("path", "scale")}


_BOAT_KEYS = ("name", "hull", "mass", "density", "center_of_mass", "inertia", "buoyancy",
              "damping", "added_mass", "propulsion", "rudder", "control_mode", "initial_pose",
              "commands", "min_wavelength", "keel", "stokes_drift", "control",
              "inertia_scale", "inertia_products", "hydrodynamics", "sensors", "windage",
              "mooring", "carriage", "anchor_line")


#: A boat's keys that leave its parameters (BoatParams) alone.
_PER_BOAT_KEYS = frozenset({"name", "initial_pose", "commands", "sensors"})


def boat_block(raw: Any, key: str, sim: SimulationSettings, lone: bool,
               base_dir: Path, depth: float = math.inf,
               loaded: dict[Path, HydroCoefficients] | None = None,
               alike: dict[str, tuple[BoatParams, tuple[str, ...]]] | None = None) -> BoatSpec:
    """One boat of ``boats``: each block read and checked in turn, in the order of the keys.

    ``depth`` (m) is the sea's: a coefficient file is keyed by it (``coefficients: auto``).
    ``loaded``: the coefficient files the scenario's other boats read, by resolved path;
    a boat naming one of them shares its coefficients (one file read, and the boats'
    diffraction evaluated together). ``alike``: the parameters (and thruster names) of the
    boats read before, by their parameter blocks; a boat whose blocks equal an earlier one's
    takes that boat's parameters, the same object (1000 alike boats: read in 0.1 s instead
    of 0.9 s, and ``pipeline.init`` derives them once).
    """
    d = mapping(raw, key)
    only(d, key, _BOAT_KEYS)
    name = _boat_name(d, key, lone)
    same = repr({k: v for k, v in d.items() if k not in _PER_BOAT_KEYS})
    if alike is not None and same in alike:
        params, thruster_names = alike[same]
    else:
        params, thruster_names = _boat_params(d, key, sim, base_dir, depth, loaded)
        if alike is not None:
            alike[same] = params, thruster_names
    ik = f"{key}.initial_pose"
    idd = mapping(d.get("initial_pose"), ik)
    only(idd, ik, ("position", "roll_deg", "pitch_deg", "yaw_deg", "velocity",
                   "angular_velocity_deg"))
    return BoatSpec(name=name, params=params, initial=_initial(params, idd, ik),
                    velocity=_bounded_vector(idd, "velocity", ik, MAX_SPEED,
                                             "m/s, body frame (x forward, y to port, z up), "
                                             "added to the waves' motion at the start"),
                    commands=_commands(d.get("commands"), f"{key}.commands",
                                       params.rudder.max_angle),
                    sensors=sensors_block(d.get("sensors"), f"{key}.sensors", sim.rate_hz),
                    thrusters=thruster_names)


def _boat_params(d: Mapping[str, Any], key: str, sim: SimulationSettings, base_dir: Path,
                 depth: float, loaded: dict[Path, HydroCoefficients] | None
                 ) -> tuple[BoatParams, tuple[str, ...]]:
    """A boat's parameters and thruster names: every block but its own (name, pose, ...)."""
    hull, mesh = _hull(mapping(d.get("hull"), f"{key}.hull"), f"{key}.hull", base_dir)
    mass, com, inertia, products = _mass_properties(d, key, sim, mesh)
    buoyancy = buoyancy_block(mapping(d.get("buoyancy"), f"{key}.buoyancy"), f"{key}.buoyancy",
                              hull, mesh)
    dk = f"{key}.damping"
    dd = mapping(d.get("damping"), dk)
    linear, quadratic, decay, ratio = _damping(dd, dk)
    rudder = rudder_block(mapping(d.get("rudder"), f"{key}.rudder"), f"{key}.rudder", hull)
    propulsion, thruster_names = propulsion_block(d.get("propulsion"), f"{key}.propulsion", hull)
    params = BoatParams(
        hull=hull, mass=mass, center_of_mass=com, inertia=inertia, inertia_products=products,
        buoyancy=buoyancy,
        damping_linear=linear, damping_quadratic=quadratic, damping_decay=decay,
        added_mass=vector(d, "added_mass", key, 6, [0.0] * 6, low=0.0),
        propulsion=propulsion,
        rudder=rudder, water_density=sim.water_density, gravity=sim.gravity,
        min_wavelength=number(d, "min_wavelength", key, 0.0, 0.0, 1e4, unit="m"),
        wave_precision=sim.wave_precision,
        keel_rate=keel_block(mapping(d.get("keel"), f"{key}.keel"), f"{key}.keel"),
        stokes_drift=flag(d, "stokes_drift", key, False),
        control=control_block(d, key),
        water_velocity=_water_velocity(dd, dk, buoyancy),
        carriage=_carriage(d.get("carriage"), f"{key}.carriage"),
    )
    params = replace(params, anchor_line=_anchor_line(
        d.get("anchor_line"), f"{key}.anchor_line", params, mesh, sim.rate_hz, depth))
    params = _with_hydrodynamics(params, d, key, dd, ratio, base_dir, depth,
                                 {} if loaded is None else loaded)
    params = replace(params, derive=replace(params.derive, windage=_windage(
        mapping(d.get("windage"), f"{key}.windage"), f"{key}.windage"),
        mooring_period=_mooring_period(d.get("mooring"), f"{key}.mooring",
                                       params.carriage is not None)))
    return params, tuple(thruster_names)


def _water_velocity(dd: Mapping[str, Any], dk: str, buoyancy) -> WaterVelocity:
    """``damping.water_velocity``: ``hull`` under the waves' pressure, else ``reference_point``.

    The waves excite a ``froude_krylov`` or ``linear`` hull through their pressure, so its
    damping must act on the velocity through the water over the hull; taken at one surface
    point, the orbital velocity drives the hull a second time: Journee's Wigley III at zero
    speed heaved 0.409 m/m in a head sea of one boat length against 0.29 measured and 0.259
    with ``hull`` (tests/boat_dynamics/physics/experiments/test_towing_tank.py).
    """
    excited = isinstance(buoyancy, MeshBuoyancy) and buoyancy.pressure != "hydrostatic"
    default = "hull" if excited else "reference_point"
    path = f"{dk}.water_velocity"
    allowed = f"one of: {', '.join(WATER_VELOCITIES)}"
    describe(path, default, allowed, default_doc="hull with the mesh model's froude_krylov or "
             "linear pressure (the default model); reference_point with hydrostatic pressure "
             "and sample points (the seed notes' models)")
    value = dd.get("water_velocity", default)
    if value not in WATER_VELOCITIES:
        raise ScenarioError(path, value, f"must be {allowed}")
    return value


def _carriage(raw: Any, key: str) -> Carriage | None:
    """``carriage``: towed at ``speed`` m/s along the line it starts on; None without the block.

    A towing tank's carriage (:mod:`boat_dynamics.physics.force_models.carriage`): heave, roll and
    pitch free, sway and yaw held; its force, the resistance, is :attr:`.pipeline.Step.towing`.
    """
    cd = mapping(raw, key)
    only(cd, key, ("speed",))
    speed = number(cd, "speed", key, 0.0, -MAX_SPEED, MAX_SPEED, unit="m/s",
                   default_doc="0 with a carriage block; without one the boat is free")
    return None if raw is None else Carriage(speed, np.full(2, np.nan), math.nan)


#: An anchor line's stiffest spring: its natural frequency on the boat's mass at most
#: simulation.rate_hz / 10 (as the contact's, :data:`.world.MAX_FREQUENCY_SHARE`).
LINE_FREQUENCY_SHARE = 0.1
#: An anchor line's default damping: this share of critical on the boat's mass.
LINE_DAMPING_RATIO = 0.1


def _anchor_line(raw: Any, key: str, params: BoatParams, mesh: HullMesh, rate_hz: float,
                 depth: float) -> AnchorLine | None:
    """``anchor_line``: an elastic line to an anchor on the sea floor; None without the block.

    (:mod:`boat_dynamics.physics.force_models.anchor_line`.) Its spring may be no stiffer than
    a natural frequency of rate_hz / 10 on the boat's mass (the step resolves it).
    """
    ad = mapping(raw, key)
    only(ad, key, ("anchor", "fairlead", "length", "stiffness", "damping"))
    if raw is not None and "anchor" not in ad:
        raise ScenarioError(f"{key}.anchor", None, "is required: [x, y, z] m, world frame")
    anchor = vector(ad, "anchor", key, 3, [0.0, 0.0, -10.0], bound=MAX_POSITION,
                    unit="m, world frame, z in [-ocean.depth, 0)",
                    default_doc="required with an anchor_line block")
    if raw is not None and not -depth <= anchor[2] < 0.0:
        raise ScenarioError(f"{key}.anchor", ad.get("anchor"), f"z must be under the surface "
                            f"and not below the sea floor: in [{-depth:g}, 0) m")
    bottom = float(mesh.vertices[:, 2].min())
    fairlead = vector(ad, "fairlead", key, 3, [0.0, 0.0, bottom], unit="m, body frame",
                      default_doc="the middle of the hull's bottom")
    if np.any(np.abs(fairlead) > COM_REACH * float(np.max(mesh.extents))):
        raise ScenarioError(f"{key}.fairlead", ad.get("fairlead"),
                            f"must lie within {COM_REACH:g} hull sizes of its reference point")
    length = number(ad, "length", key, 10.0, 0.0, 1e4, low_open=True, unit="m, unstretched",
                    default_doc="required with an anchor_line block")
    if raw is not None and "length" not in ad:
        raise ScenarioError(f"{key}.length", None, "is required: m, the unstretched line")
    stiffest = params.mass * (2 * math.pi * LINE_FREQUENCY_SHARE * rate_hz) ** 2
    stiffness = number(ad, "stiffness", key, min(2e4, stiffest), 0.0, 1e12, low_open=True,
                       unit="N/m (EA / length)", default_doc="min(2e4, the stiffest)",
                       range_doc="(0, mass x (2 pi simulation.rate_hz / 10)^2] N/m")
    if stiffness > stiffest:
        raise ScenarioError(f"{key}.stiffness", stiffness, f"must be at most {stiffest:.6g} N/m"
                            f" = mass x (2 pi simulation.rate_hz / 10)^2: a stiffer line "
                            "rings faster than the step resolves (raise rate_hz, or soften it)")
    damping = number(ad, "damping", key, 2 * LINE_DAMPING_RATIO * math.sqrt(stiffness
                     * params.mass), 0.0, 1e9, unit="N s/m",
                     default_doc=f"{LINE_DAMPING_RATIO:g} of critical on the boat's mass")
    return None if raw is None else AnchorLine(anchor, fairlead, length, stiffness, damping)


def _mooring_period(raw: Any, key: str, towed: bool) -> float | None:
    """``mooring``: a soft mooring's natural period, s; None without the block (free).

    A towing tank's soft springs on x, y and heading, anchored where the boat starts
    (:mod:`boat_dynamics.physics.force_models.mooring`): for seakeeping at zero speed, a period of
    many wave periods so that they leave the wave-frequency motion alone.
    """
    md = mapping(raw, key)
    only(md, key, ("period",))
    if raw is not None and towed:
        raise ScenarioError(key, raw, "absent: a boat on a carriage is held by the carriage")
    period = number(md, "period", key, 60.0, 5.0, 3600.0, unit="s",
                    default_doc="60 with a mooring block; without one the boat is free")
    return None if raw is None else period


def _with_hydrodynamics(params: BoatParams, d: Mapping[str, Any], key: str,
                        dd: Mapping[str, Any], ratio: np.ndarray | None, base_dir: Path,
                        depth: float, loaded: dict[Path, HydroCoefficients]) -> BoatParams:
    """``params`` with its coefficient file (if any) and what ``pipeline.init`` derives."""
    coefficients, model, missing = _hydrodynamics(d.get("hydrodynamics"),
                                                  f"{key}.hydrodynamics", base_dir, params,
                                                  depth, loaded)
    if model == "resonance" and "critical_ratio" not in dd:
        ratio = None  # the radiation damping at resonance replaces the default ratio
    elif model is not None and "critical_ratio" not in dd:
        # the radiation damps the waves made; the viscous share potential flow lacks stays
        ratio = None if "linear" in dd else np.array(RADIATING_CRITICAL_RATIO)
    radiation = model == "resonance" and "linear" not in dd and "critical_ratio" not in dd
    if (isinstance(params.buoyancy, MeshBuoyancy) and params.buoyancy.pressure == "linear"
            and model is None):
        raise ScenarioError(f"{key}.buoyancy.pressure", "linear",
                            "needs hydrodynamics.coefficients (a file, or auto): the incident "
                            "waves' force comes from the hull's potential-flow coefficients")
    if model == "cummins" and np.any(params.added_mass != 0.0):
        raise ScenarioError(f"{key}.added_mass", d.get("added_mass"),
                            "must be zero (or absent) with hydrodynamics.radiation cummins, "
                            "which takes the added mass from the coefficients; or choose "
                            "radiation: resonance")
    made = _made_waves(d.get("hydrodynamics"), f"{key}.hydrodynamics")
    return replace(params, hydro=coefficients, made_waves=made, derive=Derivation(
        critical_ratio=ratio, quadratic="quadratic" not in dd,
        added_mass=model == "resonance" and "added_mass" not in d,
        radiation_damping=radiation, memory=model == "cummins", estimate=missing,
        hull_lift=_hull_lift(d.get("hydrodynamics"), f"{key}.hydrodynamics", model),
        thin_ship=made in ("all", "wake")))


def _made_waves(raw: Any, key: str) -> MadeWavesModel:
    """``hydrodynamics.made_waves``: the waves the boat makes that the others feel.

    :mod:`.interaction`: its Kelvin wake (``wake``; ``all`` is every kind modelled) or
    ``none``. Only boats with coefficients feel them; a boat without makes them all the same.
    """
    d = {} if raw is None else mapping(raw, key)
    return choice(d, "made_waves", key, "all", MADE_WAVES_MODELS)  # type: ignore[return-value]


def _hull_lift(raw: Any, key: str, model: RadiationModel | None) -> bool:
    """``hydrodynamics.hull_lift``: the trailing section's lift (:mod:`.hull_lift`) or none.

    Only with ``radiation: cummins`` (it completes the Munk moment of the added mass that
    radiation carries). Default ``none`` until it is validated on the shipped boxes: slender-body
    theory's yaw damping is twice what Clarke's (1983) regression gives a box as wide as the
    default's (L/B 2, B/T 4), and with it the default box turns at a third of its rate.
    """
    d = {} if raw is None else mapping(raw, key)
    lift = choice(d, "hull_lift", key, "none", HULL_LIFT_MODELS)
    if "hull_lift" in d and lift != "none" and model != "cummins":
        raise ScenarioError(f"{key}.hull_lift", lift, "needs hydrodynamics.radiation cummins "
                            "(the added mass whose Munk moment it completes), or none")
    return lift == "trailing_edge" and model == "cummins"


def _windage(d: Mapping[str, Any], key: str) -> Windage:
    """``windage``: the areas the wind acts on and Fossen's c_x, c_y, c_n.

    Areas absent: from the hull above its waterline (``pipeline.init``); coefficients absent:
    :data:`~boat_dynamics.physics.force_models.wind.DEFAULT_WIND_COEFFICIENTS`.
    """
    only(d, key, ("frontal_area", "lateral_area", "coefficients"))
    for k in ("frontal_area", "lateral_area"):
        describe(f"{key}.{k}", None, "number in [0, 1e+06] m^2, above the waterline",
                 default_doc="auto: from the hull above its waterline")
    areas = [number(d, k, key, math.nan, 0.0, 1e6, unit="m^2") if k in d else math.nan
             for k in ("frontal_area", "lateral_area")]
    coefficients = vector(d, "coefficients", key, 3, list(DEFAULT_WIND_COEFFICIENTS), low=0.0,
                          unit="Fossen's c_x, c_y, c_n, each at most 2")
    if np.any(coefficients > 2.0):
        raise ScenarioError(f"{key}.coefficients", d.get("coefficients"),
                            "c_x, c_y, c_n each in [0, 2] (Fossen: about 0.5-0.9, 0.7-0.95, "
                            "0.05-0.2)")
    return Windage(areas[0], areas[1], math.nan, np.full(3, math.nan), coefficients)


def _boat_name(d: Mapping[str, Any], key: str, lone: bool) -> str:
    """``name``: a ROS name, required unless the boat is alone ("" = root namespace)."""
    describe(f"{key}.name", None, f"{ROS_NAME_RULE}; unique",
             default_doc='"" (the root namespace) for a lone boat, else required')
    name = d.get("name", "" if lone else None)
    if name is None:
        raise ScenarioError(f"{key}.name", None, "every boat of a multi-boat scenario needs a name")
    if name != "" and not is_ros_name(name):
        raise ScenarioError(f"{key}.name", name, f"must be {ROS_NAME_RULE}")
    return name


#: The smallest hull extent, m: below, its mass properties lose their precision (a length
#: of 5e-324 m stopped numpy's eigenvalue solver, found by test_scenario_fuzz.py).
MIN_HULL_SIZE = 0.01


def _hull(hd: Mapping[str, Any], hk: str, base_dir: Path) -> tuple[BoxHull, HullMesh]:
    """``hull``: a box, an upright cylinder (a buoy, a spar) or a mesh file.

    Box: ``length``, ``beam``, ``height``, ``subdivisions``; cylinder: ``radius``, ``height``,
    ``subdivisions`` (bands along its axis); mesh: ``path``, ``scale``.
    """
    only(hd, hk, ("type", "length", "beam", "height", "subdivisions", "path", "scale",
                  "radius"))
    hull_type = choice(hd, "type", hk, "box", HULL_TYPES)
    for extra in {"box": ("path", "scale", "radius"), "cylinder": ("path", "scale", "length",
                                                                   "beam"),
                  "mesh": ("radius",)}[hull_type]:
        if extra in hd:
            allowed = [t for t in HULL_TYPES if extra in _HULL_TYPE_KEYS[t]]
            raise ScenarioError(f"{hk}.{extra}", hd[extra],
                                f"only for hull type {' or '.join(allowed)}")
    if hull_type == "cylinder":
        radius = number(hd, "radius", hk, 0.5, MIN_HULL_SIZE / 2, 500.0, unit="m")
        height = number(hd, "height", hk, 1.0, MIN_HULL_SIZE, 1000.0, unit="m")
        rings = integer(hd, "subdivisions", hk, 1, 1, 64, "(quads per box face edge; "
                        "a cylinder's bands along its axis)")
        mesh = cylinder_mesh(radius, height, rings=rings)
        return BoxHull(*(float(e) for e in mesh.extents)), mesh
    if hull_type == "box":
        hull = BoxHull(
            length=number(hd, "length", hk, 4.0, MIN_HULL_SIZE, 1000.0, unit="m"),
            beam=number(hd, "beam", hk, 2.0, MIN_HULL_SIZE, 1000.0, unit="m"),
            height=number(hd, "height", hk, 1.0, MIN_HULL_SIZE, 1000.0, unit="m"),
        )
        subdivisions = integer(hd, "subdivisions", hk, 1, 1, 64, "(quads per box face edge; "
                               "a cylinder's bands along its axis)")
        return hull, box_mesh(hull, subdivisions)
    for extra in ("length", "beam", "height", "subdivisions"):
        if extra in hd:
            raise ScenarioError(f"{hk}.{extra}", hd[extra],
                                "only for hull type box or cylinder (a mesh has its own size)")
    describe(f"{hk}.path", None, "an STL or OBJ file (relative: to the scenario's folder)",
             default_doc="required with type mesh")
    path = hd.get("path")
    if not isinstance(path, str) or not path:
        raise ScenarioError(f"{hk}.path", path, "must be the path of an STL or OBJ file")
    full = Path(path) if Path(path).is_absolute() else base_dir / path
    scale = number(hd, "scale", hk, 1.0, 0.0, 1e3, low_open=True)
    try:
        mesh = load_mesh(str(full), scale)
    except HullMeshError as exc:
        raise ScenarioError(f"{hk}.path", path, str(exc)) from exc
    if float(np.min(mesh.extents)) < MIN_HULL_SIZE:
        raise ScenarioError(f"{hk}.scale", scale, f"the scaled hull must be at least "
                            f"{MIN_HULL_SIZE:g} m in each direction (it is "
                            f"{np.round(mesh.extents, 6).tolist()} m)")
    return BoxHull(*(float(e) for e in mesh.extents)), mesh


#: How far the centre of mass may lie from the hull's reference point, in hull sizes (the
#: largest extent): beyond, the hull's own numbers are lost in rounding (4.5e15 m divided by
#: zero in the equilibrium search, found by
#: tests/boat_dynamics/physics/scenario/test_scenario_fuzz.py).
COM_REACH = 10.0


#: The farthest a boat may start from the world origin in each axis, m: 10,000 km, past any
#: local frame (6e307 m overflowed in the physics, found by test_scenario_fuzz.py).
MAX_POSITION = 1e7


def _mass_properties(d: Mapping[str, Any], key: str, sim: SimulationSettings, mesh: HullMesh
                     ) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """The mass properties: kg, (3,) m, (3,) kg m^2 and (3,) kg m^2.

    From ``mass`` (or ``density``), ``center_of_mass``, ``inertia`` (times ``inertia_scale``)
    and ``inertia_products``; the solid hull's where not given.
    """
    volume = mesh.volume
    if "mass" in d and "density" in d:
        raise ScenarioError(f"{key}.density", d["density"],
                            "give either mass or density, not both (the other is derived)")
    describe(f"{key}.density", None, "number in (0, inf] kg/m^3: mass = density x the hull's "
             "volume (instead of mass)", default_doc="none")
    if "density" in d:
        density = number(d, "density", key, 0.0, 0.0, math.inf, low_open=True, unit="kg/m^3")
        mass = density * volume
    else:
        mass = number(d, "mass", key, 0.5 * sim.water_density * volume, 0.0, math.inf,
                       low_open=True, unit="kg", default_doc="half the hull's displacement "
                       "(0.5 x water_density x volume: it floats at half its height)")
    com = vector(d, "center_of_mass", key, 3, [0.0, 0.0, 0.0], unit="m, body frame, from the "
                 f"hull reference point, within {COM_REACH:g} hull sizes")
    reach = COM_REACH * float(np.max(mesh.extents))
    if np.any(np.abs(com) > reach):
        raise ScenarioError(f"{key}.center_of_mass", d.get("center_of_mass"),
                            f"must lie within {COM_REACH:g} hull sizes ({reach:.4g} m) of the "
                            "hull's reference point in each axis (m)")
    describe(f"{key}.inertia", None, "3 numbers > 0, kg m^2: the principal moments about the "
             "centre of mass", default_doc="null: the solid hull's")
    describe(f"{key}.inertia_products", None, "3 numbers (Ixy, Ixz, Iyz), kg m^2",
             default_doc="the solid hull's; [0, 0, 0] when inertia is given")
    inertia_raw = d.get("inertia")
    inertia = (mesh.solid_inertia(mass) if inertia_raw is None
               else vector(d, "inertia", key, 3, [1.0, 1.0, 1.0], low=0.0))
    if np.any(inertia <= 0.0):
        raise ScenarioError(f"{key}.inertia", inertia_raw, "every moment must be > 0 (kg m^2)")
    inertia = inertia * vector(d, "inertia_scale", key, 3, [1.0, 1.0, 1.0], low=0.01)
    products_raw = d.get("inertia_products")
    products = (vector(d, "inertia_products", key, 3, [0.0, 0.0, 0.0])
                if products_raw is not None or inertia_raw is not None
                else mesh.inertia_products(mass))
    products[np.abs(products) < 1e-9 * inertia.max()] = 0.0  # rounding of symmetric hulls
    if np.linalg.eigvalsh(inertia_tensor(inertia, products)).min() <= 0.0:
        raise ScenarioError(f"{key}.inertia_products", products_raw,
                            "the inertia tensor must be positive definite (products of inertia "
                            "too large for the moments)")
    return mass, com, inertia, products


def _damping(dd: Mapping[str, Any], dk: str
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """``damping``: (6,) linear, quadratic and decay, and the critical ratios to add.

    The ratios are [heave, roll, pitch]; None adds none. Default: DEFAULT_CRITICAL_RATIO when
    ``linear`` is not given.
    """
    only(dd, dk, ("linear", "quadratic", "critical_ratio", "decay", "water_velocity"))
    linear = vector(dd, "linear", dk, 6, [0.0] * 6, low=0.0,
                    unit="N s/m (surge, sway, heave), N m s (roll, pitch, yaw)")
    decay = vector(dd, "decay", dk, 6, [0.0] * 6, low=0.0)
    quadratic = vector(dd, "quadratic", dk, 6, [0.0] * 6, low=0.0,
                       unit="N s^2/m^2, N m s^2", default_doc="derived: the hull's form drag "
                       "at its equilibrium draft")
    describe(f"{dk}.critical_ratio", None, "3 numbers >= 0: damping ratios in heave, roll, "
             "pitch added to linear", default_doc=f"{list(DEFAULT_CRITICAL_RATIO)} unless "
             f"linear is given; {list(RADIATING_CRITICAL_RATIO)} with potential-flow "
             "coefficients (the viscous share: their radiation damps the waves made)")
    ratio_default = None if "linear" in dd else list(DEFAULT_CRITICAL_RATIO)
    ratio_raw = dd.get("critical_ratio", ratio_default)
    ratio = (None if ratio_raw is None
             else vector({"critical_ratio": ratio_raw}, "critical_ratio", dk, 3, [0.0] * 3,
                          low=0.0))
    return linear, quadratic, decay, ratio


def _hydrodynamics(raw: Any, key: str, base_dir: Path, params: BoatParams, depth: float,
                   loaded: dict[Path, HydroCoefficients]
                   ) -> tuple[HydroCoefficients | None, RadiationModel | None, str | None]:
    """``hydrodynamics``: the hull's coefficient file (``coefficients``) and ``radiation``.

    ``coefficients``: a path (relative ones from the scenario's directory), or ``auto``: the
    file of this hull's key (:func:`~boat_dynamics.physics.core.model.coefficients_key`) in
    :func:`~boat_dynamics.physics.potential_flow.hydro.coefficient_directories`, or, when there is
    none, an estimate (:func:`~boat_dynamics.physics.potential_flow.hydro.estimate`, made by
    ``pipeline.init``). The
    file must have been solved about the boat's centre of mass. ``radiation``
    (:data:`~.model.RadiationModel`, default ``cummins``) only with ``coefficients``.

    Returns:
        The coefficients (None: none, or to estimate), the radiation model (None: none), and
        the hull's key when its coefficients are to be estimated.
    """
    d = mapping(raw, key)
    only(d, key, ("coefficients", "radiation", "hull_lift", "made_waves"))
    mesh = isinstance(params.buoyancy, MeshBuoyancy)
    describe(f"{key}.coefficients", None, "a .npz coefficient file (boatsim hydro; relative: "
             "to the scenario's folder), auto: the shipped or hydro/ file of this hull (or the "
             "estimate), or none", default_doc="auto for a mesh buoyancy model, none for "
             "sample points")
    path = d.get("coefficients", "auto" if mesh else "none")
    if path == "none":
        for name in ("radiation", "hull_lift"):
            if name in d:
                raise ScenarioError(f"{key}.{name}", d[name], "needs hydrodynamics."
                                    "coefficients (a coefficient file, or auto)")
        return None, None, None
    model = choice(d, "radiation", key, "cummins", RADIATION_MODELS)
    if not isinstance(path, str) or not path:
        raise ScenarioError(f"{key}.coefficients", path,
                            "must be the path of a .npz coefficient file (boatsim hydro), "
                            "auto or none")
    if path == "auto":
        hull_key = coefficients_key(params, depth)
        found = find_coefficients(hull_key, coefficient_directories(base_dir))
        if found is None:
            return None, model, hull_key
        full = found
    else:
        full = Path(path) if Path(path).is_absolute() else base_dir / path
    full = full.resolve()
    if full not in loaded:
        try:
            loaded[full] = load_coefficients(full)
        except HydroFileError as exc:
            raise ScenarioError(f"{key}.coefficients", path, str(exc)) from exc
    coefficients = loaded[full]
    com = params.center_of_mass
    if not np.allclose(coefficients.center_of_mass, com, rtol=0.0, atol=1e-6):
        raise ScenarioError(f"{key}.coefficients", path,
                            f"was solved about the centre of mass "
                            f"{coefficients.center_of_mass.tolist()}, the boat's is "
                            f"{com.tolist()} (m)")
    return coefficients, model, None


def _initial(params: BoatParams, idd: Mapping[str, Any], ik: str) -> BoatState:
    """``initial_pose``: the state at rest there (hull reference point, degrees).

    At rest: :func:`boat_dynamics.physics.core.pipeline.init` sets it afloat in the waves.
    """
    position = vector(idd, "position", ik, 3, [0.0, 0.0, 0.0],
                      unit=f"m, world frame, each within +-{MAX_POSITION:g}")
    if np.any(np.abs(position) > MAX_POSITION):
        raise ScenarioError(f"{ik}.position", idd.get("position"),
                            f"each coordinate must lie within +-{MAX_POSITION:g} m (the world "
                            "frame is local, around simulation.datum)")
    state = initial_state(
        params,
        position,
        roll=math.radians(number(idd, "roll_deg", ik, 0.0, -180.0, 180.0, unit="deg")),
        pitch=math.radians(number(idd, "pitch_deg", ik, 0.0, -90.0, 90.0, unit="deg")),
        yaw=math.radians(number(idd, "yaw_deg", ik, 0.0, -360.0, 360.0, unit="deg")),
    )
    rate = _bounded_vector(idd, "angular_velocity_deg", ik, MAX_RATE_DEG,
                           "deg/s, body frame (roll, pitch, yaw rate)")
    return replace(state, angular_velocity=np.radians(rate)) if rate.any() else state


#: Largest initial speed along a body axis, m/s (``initial_pose.velocity``).
MAX_SPEED = 50.0
#: Largest initial rate about a body axis, deg/s (``initial_pose.angular_velocity_deg``).
MAX_RATE_DEG = 360.0


def _bounded_vector(d: Mapping[str, Any], name: str, key: str, bound: float,
                    unit: str) -> np.ndarray:
    """``d[name]``: 3 finite numbers within +-``bound``, default zeros, or ScenarioError."""
    v = vector(d, name, key, 3, [0.0, 0.0, 0.0], unit=f"{unit}, each within +-{bound:g}")
    if np.any(np.abs(v) > bound):
        raise ScenarioError(f"{key}.{name}", d.get(name), f"each entry must lie within "
                                                          f"+-{bound:g}")
    return v


def _commands(raw: Any, key: str, max_rudder: float) -> CommandScript | None:
    describe(key, None, "a list of {t, thrust, rudder}, held from each t to the next; the "
             "boat then ignores its command topics", default_doc="none: the command topics")
    if raw is None:
        return None
    if not isinstance(raw, list) or not raw:
        raise ScenarioError(key, raw, "must be a non-empty list of {t, thrust, rudder}")
    times, throttles, rudders = [], [], []
    for i, entry in enumerate(raw):
        ek = f"{key}[{i}]"
        ed = mapping(entry, ek)
        only(ed, ek, ("t", "thrust", "rudder"))
        t = number(ed, "t", ek, 0.0, 0.0, unit="s")
        if times and t <= times[-1]:
            raise ScenarioError(f"{ek}.t", t,
                                f"must be later than the previous entry ({times[-1]})")
        times.append(t)
        throttles.append(number(ed, "thrust", ek, 0.0, -1.0, 1.0))
        rudders.append(number(ed, "rudder", ek, 0.0, -max_rudder, max_rudder, unit="rad",
                              range_doc="[-rudder.max_angle_deg, +rudder.max_angle_deg], rad"))
    return CommandScript(tuple(times), tuple(throttles), tuple(rudders))
