"""Scenario files (YAML): parsing and validation into frozen specs, nothing more.

The reader computes no physics: what a boat's own hydrostatics fix (its equilibrium, the
damping the file leaves to derive) is asked for in ``BoatParams.derive``, and the boats start
at rest at their initial poses; :func:`boat_dynamics.physics.pipeline.init` derives it and
sets them afloat, once.

The keys are the public contract of DESIGN.md ("Scenario file"). Every refusal raises
:class:`ScenarioError` naming the key (as a path such as ``boats[0].hull.length``), the value
and what is allowed. Pure Python + numpy; never imports rclpy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from boat_dynamics.physics.buoyancy import CURVES, POINT_DIRECTIONS, SamplePointBuoyancy
from boat_dynamics.physics.commands import CommandScript
from boat_dynamics.physics.control import ATTITUDES, CONTROL_MODES, ControlSettings
from boat_dynamics.physics.hull import BoxHull, HullMesh, HullMeshError, box_mesh, load_mesh
from boat_dynamics.physics.hull_drag import HullDrag
from boat_dynamics.physics.hydro import HydroCoefficients, HydroFileError, load_coefficients
from boat_dynamics.physics.mesh_buoyancy import PRESSURE_MODELS, MeshBuoyancy
from boat_dynamics.physics.model import BoatParams, BoatState, Derivation, initial_state
from boat_dynamics.physics.propulsion import Propulsion
from boat_dynamics.physics.rigid_body import inertia_tensor
from boat_dynamics.physics.rudder import RUDDER_MODELS, Rudder
from ocean_sim.physics.constants import GRAVITY, WATER_DENSITY
from ocean_sim.physics.spectra import SPECTRUM_TYPES, SpectrumSpec, beaufort_sea, generate_sea
from ocean_sim.physics.waves import (
    PRECISIONS,
    InvalidSeaStateError,
    Precision,
    WaveComponent,
    WaveField,
)

__all__ = [
    "BoatSpec",
    "Scenario",
    "ScenarioError",
    "SimulationSettings",
    "default_scenario_path",
    "load_scenario",
    "parse_scenario",
]


class ScenarioError(ValueError):
    """A scenario that cannot be run.

    Attributes:
        key: path of the offending key, e.g. ``boats[0].mass``.
        value: the value found.
        allowed: what would have been accepted.
    """

    def __init__(self, key: str, value: object, allowed: str) -> None:
        self.key = key
        self.value = value
        self.allowed = allowed
        super().__init__(f"{key}: {value!r} is not allowed: {allowed}")


@dataclass(frozen=True)
class SimulationSettings:
    """The ``simulation:`` block.

    Attributes:
        rate_hz: physics steps per simulated second.
        publish_rate_hz: odom / pose / twist messages per simulated second.
        diagnostics_rate_hz: wrench/* messages per simulated second.
        realtime: pace the simulation to the wall clock (False = as fast as possible).
        duration: s of simulated time to run, None = until stopped.
        seed: random seed (generated sea states).
        gravity: m/s^2.
        water_density: kg/m^3.
        cmd_timeout: s without a cmd_thrust message after which thrust is set to zero.
        substeps: physics substeps per step.
        wave_precision: precision of the boats' surface queries, ``float32`` (fast; heights
            within about 1e-5 m of float64) or ``float64``.
    """

    rate_hz: float = 100.0
    publish_rate_hz: float = 50.0
    diagnostics_rate_hz: float = 10.0
    realtime: bool = True
    duration: float | None = None
    seed: int = 0
    gravity: float = GRAVITY
    water_density: float = WATER_DENSITY
    cmd_timeout: float = 1.0
    substeps: int = 1
    wave_precision: Precision = "float32"


@dataclass(frozen=True)
class BoatSpec:
    """One boat of a scenario.

    Attributes:
        name: the boat's namespace; "" for a lone boat in the root namespace.
        params: its physical parameters.
        initial: its initial state.
        commands: scripted commands, or None to follow the command topics.
    """

    name: str
    params: BoatParams
    initial: BoatState
    commands: CommandScript | None


@dataclass(frozen=True)
class Scenario:
    """A whole run: settings, the sea and the boats."""

    simulation: SimulationSettings
    sea: WaveField
    boats: tuple[BoatSpec, ...]
    source: str = "<scenario>"


def default_scenario_path() -> Path:
    """Path of the shipped default scenario (scenarios/default.yaml)."""
    return Path(__file__).resolve().parents[3] / "scenarios" / "default.yaml"


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a scenario file.

    Raises:
        ScenarioError: unreadable file, bad YAML, or an invalid key or value.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ScenarioError("file", str(p), f"must be a readable file ({exc.strerror})") from exc
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "somewhere"
        raise ScenarioError("file", str(p), f"must be valid YAML (error at {where})") from exc
    return parse_scenario({} if data is None else data, source=str(p), base_dir=p.parent)


# --------------------------------------------------------------------------- readers


def _mapping(value: Any, key: str) -> Mapping[str, Any]:
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise ScenarioError(key, value, "must be a mapping (key: value)")
    return value


def _only(d: Mapping[str, Any], key: str, allowed: tuple[str, ...]) -> None:
    for k in d:
        if k not in allowed:
            raise ScenarioError(f"{key}.{k}" if key else str(k), d[k],
                                f"unknown key; allowed keys here: {', '.join(allowed)}")


def _number(
    d: Mapping[str, Any],
    name: str,
    key: str,
    default: float,
    low: float = -math.inf,
    high: float = math.inf,
    low_open: bool = False,
    unit: str = "",
    allow_inf: bool = False,
) -> float:
    path = f"{key}.{name}" if key else name
    v = d.get(name, default)
    bounds = ("(" if low_open else "[") + f"{low:g}, {high:g}]" + (f" {unit}" if unit else "")
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ScenarioError(path, v, f"must be a number in {bounds}")
    v = float(v)
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise ScenarioError(path, v, f"must be a finite number in {bounds}")
    if v < low or v > high or (low_open and v == low):
        raise ScenarioError(path, v, f"must be in {bounds}")
    return v


def _vector(d: Mapping[str, Any], name: str, key: str, n: int, default: list[float],
            low: float = -math.inf) -> np.ndarray:
    path = f"{key}.{name}"
    v = d.get(name, default)
    if (not isinstance(v, (list, tuple)) or len(v) != n
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)):
        raise ScenarioError(path, v, f"must be a list of {n} numbers")
    arr = np.array(v, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ScenarioError(path, v, f"must be a list of {n} finite numbers")
    if np.any(arr < low):
        raise ScenarioError(path, v, f"every entry must be >= {low:g}")
    return arr


def _flag(d: Mapping[str, Any], name: str, key: str, default: bool) -> bool:
    v = d.get(name, default)
    if not isinstance(v, bool):
        raise ScenarioError(f"{key}.{name}", v, "must be true or false")
    return v


def _choice(d: Mapping[str, Any], name: str, key: str, default: str,
            allowed: tuple[str, ...]) -> str:
    path = f"{key}.{name}"
    v = d.get(name, default)
    if v not in allowed:
        raise ScenarioError(path, v, f"must be one of: {', '.join(allowed)}")
    return str(v)


# --------------------------------------------------------------------------- sections


def _simulation(raw: Any) -> SimulationSettings:
    key = "simulation"
    d = _mapping(raw, key)
    _only(d, key, ("rate_hz", "publish_rate_hz", "diagnostics_rate_hz", "realtime", "duration",
                   "seed", "gravity", "water_density", "cmd_timeout", "substeps",
                   "wave_precision"))
    rate = _number(d, "rate_hz", key, 100.0, 1.0, 10000.0, unit="Hz")
    pub = _number(d, "publish_rate_hz", key, 50.0, 0.0, rate, low_open=True, unit="Hz")
    diag = _number(d, "diagnostics_rate_hz", key, 10.0, 0.0, rate, low_open=True, unit="Hz")
    realtime = d.get("realtime", True)
    if not isinstance(realtime, bool):
        raise ScenarioError(f"{key}.realtime", realtime, "must be true or false")
    duration = d.get("duration")
    if duration is not None:
        duration = _number(d, "duration", key, 0.0, 0.0, math.inf, low_open=True, unit="s")
    substeps = d.get("substeps", 1)
    if isinstance(substeps, bool) or not isinstance(substeps, int) or not 1 <= substeps <= 100:
        raise ScenarioError(f"{key}.substeps", substeps, "must be an integer in [1, 100]")
    seed = d.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ScenarioError(f"{key}.seed", seed, "must be an integer >= 0")
    return SimulationSettings(
        rate_hz=rate,
        publish_rate_hz=pub,
        diagnostics_rate_hz=diag,
        realtime=realtime,
        duration=duration,
        seed=seed,
        gravity=_number(d, "gravity", key, GRAVITY, 0.0, 100.0, low_open=True, unit="m/s^2"),
        water_density=_number(d, "water_density", key, WATER_DENSITY, 0.0, 1e5, low_open=True,
                              unit="kg/m^3"),
        cmd_timeout=_number(d, "cmd_timeout", key, 1.0, 0.0, 3600.0, low_open=True, unit="s"),
        substeps=substeps,
        wave_precision=_choice(d, "wave_precision", key, "float32", PRECISIONS),
    )


def _ocean(raw: Any, sim: SimulationSettings) -> WaveField:
    key = "ocean"
    d = _mapping(raw, key)
    _only(d, key, ("depth", "components", "spectrum"))
    depth = _number(d, "depth", key, math.inf, 0.0, math.inf, low_open=True, unit="m",
                    allow_inf=True)
    generated = _spectrum(d.get("spectrum"), sim, depth)
    comps_raw = d.get("components") or []
    if not isinstance(comps_raw, list):
        raise ScenarioError(f"{key}.components", comps_raw, "must be a list of components")
    comps = []
    for i, c in enumerate(comps_raw):
        ck = f"{key}.components[{i}]"
        cd = _mapping(c, ck)
        _only(cd, ck, ("amplitude", "wavelength", "direction_deg", "steepness", "phase"))
        comps.append(WaveComponent(
            amplitude=_number(cd, "amplitude", ck, 0.0, 0.0, unit="m"),
            wavelength=_number(cd, "wavelength", ck, 10.0, 0.0, low_open=True, unit="m"),
            direction=math.radians(_number(cd, "direction_deg", ck, 0.0, unit="deg")),
            steepness=_number(cd, "steepness", ck, 0.0, 0.0, 1.0),
            phase=_number(cd, "phase", ck, 0.0, unit="rad"),
        ))
    try:
        return WaveField(tuple(comps) + generated, gravity=sim.gravity, depth=depth)
    except InvalidSeaStateError as exc:
        if generated and exc.key == "components":
            raise ScenarioError(key, exc.value, "components and spectrum together: "
                                + exc.allowed) from exc
        raise ScenarioError(f"{key}.{exc.key}", exc.value, exc.allowed) from exc


_SPECTRUM_KEYS = ("type", "significant_height", "peak_period", "beaufort", "direction_deg",
                  "spreading", "components", "gamma", "steepness")


def _spectrum(raw: Any, sim: SimulationSettings, depth: float) -> tuple[WaveComponent, ...]:
    """Components generated from ``ocean.spectrum`` (empty if absent)."""
    if raw is None:
        return ()
    key = "ocean.spectrum"
    d = _mapping(raw, key)
    _only(d, key, _SPECTRUM_KEYS)
    kind = _choice(d, "type", key, "jonswap", SPECTRUM_TYPES)
    spreading = d.get("spreading", 10.0)
    if spreading is not None:
        spreading = _number(d, "spreading", key, 10.0, 0.0, 1000.0)
    n = d.get("components", 16)
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 1000:
        raise ScenarioError(f"{key}.components", n, "must be an integer in [1, 1000]")
    direction = math.radians(_number(d, "direction_deg", key, 0.0, -360.0, 360.0, unit="deg"))
    steepness = _number(d, "steepness", key, 0.5, 0.0, 1.0)
    try:
        if "beaufort" in d:
            for other in ("significant_height", "peak_period", "gamma"):
                if other in d:
                    raise ScenarioError(f"{key}.{other}", d[other],
                                        "give either beaufort or significant_height/peak_period")
            if kind != "pierson_moskowitz" and "type" in d:
                raise ScenarioError(f"{key}.type", kind,
                                    "a beaufort sea is pierson_moskowitz (fully developed)")
            sea = beaufort_sea(d["beaufort"], direction, spreading, n, steepness, sim.seed,
                               sim.gravity, depth)
        else:
            spec = SpectrumSpec(
                type=kind,
                significant_height=_number(d, "significant_height", key, 1.0, 0.0, 30.0,
                                           unit="m"),
                peak_period=_number(d, "peak_period", key, 6.0, 0.5, 40.0, unit="s"),
                direction=direction, spreading=spreading, components=n,
                gamma=_number(d, "gamma", key, 3.3, 1.0, 7.0), steepness=steepness,
            )
            sea = generate_sea(spec, seed=sim.seed, gravity=sim.gravity, depth=depth)
    except InvalidSeaStateError as exc:
        raise ScenarioError(f"ocean.{exc.key}", exc.value, exc.allowed) from exc
    return sea.components


_BOAT_KEYS = ("name", "hull", "mass", "density", "center_of_mass", "inertia", "buoyancy",
              "damping", "added_mass", "propulsion", "rudder", "control_mode", "initial_pose",
              "commands", "min_wavelength", "keel", "stokes_drift", "control",
              "inertia_scale", "inertia_products", "hydrodynamics")


def _boat(raw: Any, key: str, sim: SimulationSettings, lone: bool,
          base_dir: Path) -> BoatSpec:
    """One boat of ``boats``: each block read and checked in turn, in the order of the keys."""
    d = _mapping(raw, key)
    _only(d, key, _BOAT_KEYS)
    name = _boat_name(d, key, lone)
    hull, mesh = _hull(_mapping(d.get("hull"), f"{key}.hull"), f"{key}.hull", base_dir)
    mass, com, inertia, products = _mass_properties(d, key, sim, mesh)
    buoyancy = _buoyancy(_mapping(d.get("buoyancy"), f"{key}.buoyancy"), f"{key}.buoyancy",
                         hull, mesh)
    dk = f"{key}.damping"
    dd = _mapping(d.get("damping"), dk)
    linear, quadratic, decay, ratio = _damping(dd, dk)
    added = _vector(d, "added_mass", key, 6, [0.0] * 6, low=0.0)
    propulsion = _propulsion(_mapping(d.get("propulsion"), f"{key}.propulsion"),
                             f"{key}.propulsion", hull)
    rudder = _rudder(_mapping(d.get("rudder"), f"{key}.rudder"), f"{key}.rudder", hull)
    keel_rate = _keel_rate(_mapping(d.get("keel"), f"{key}.keel"), f"{key}.keel")
    control = _control(d, key)
    coefficients = _hydrodynamics(d.get("hydrodynamics"), f"{key}.hydrodynamics", base_dir, com)
    radiation = (coefficients is not None and "linear" not in dd
                 and "critical_ratio" not in dd)
    if radiation:
        ratio = None  # the radiation damping replaces the default critical ratio
    ik = f"{key}.initial_pose"
    idd = _mapping(d.get("initial_pose"), ik)
    _only(idd, ik, ("position", "roll_deg", "pitch_deg", "yaw_deg"))
    params = BoatParams(
        hull=hull, mass=mass, center_of_mass=com, inertia=inertia, inertia_products=products,
        buoyancy=buoyancy,
        damping_linear=linear, damping_quadratic=quadratic, damping_decay=decay,
        added_mass=added, propulsion=propulsion, rudder=rudder,
        water_density=sim.water_density, gravity=sim.gravity,
        min_wavelength=_number(d, "min_wavelength", key, 0.0, 0.0, 1e4, unit="m"),
        wave_precision=sim.wave_precision,
        keel_rate=keel_rate,
        stokes_drift=_flag(d, "stokes_drift", key, False),
        control=control,
        derive=Derivation(critical_ratio=ratio, quadratic="quadratic" not in dd,
                          coefficients=coefficients,
                          added_mass=coefficients is not None and "added_mass" not in d,
                          radiation_damping=radiation),
    )
    return BoatSpec(name=name, params=params, initial=_initial(params, idd, ik),
                    commands=_commands(d.get("commands"), f"{key}.commands", rudder.max_angle))


def _boat_name(d: Mapping[str, Any], key: str, lone: bool) -> str:
    """``name``: a ROS name, required unless the boat is alone ("" = root namespace)."""
    name = d.get("name", "" if lone else None)
    if name is None:
        raise ScenarioError(f"{key}.name", None, "every boat of a multi-boat scenario needs a name")
    if not isinstance(name, str) or (name and not name.replace("_", "a").isalnum()) \
            or (name and name[0].isdigit()):
        raise ScenarioError(f"{key}.name", name,
                            "must be a ROS name: letters, digits and _, not starting with a digit")
    return name


def _hull(hd: Mapping[str, Any], hk: str, base_dir: Path) -> tuple[BoxHull, HullMesh]:
    """``hull``: a box (``length``, ``beam``, ``height``, ``subdivisions``) or a mesh file."""
    _only(hd, hk, ("type", "length", "beam", "height", "subdivisions", "path", "scale"))
    hull_type = _choice(hd, "type", hk, "box", ("box", "mesh"))
    if hull_type == "box":
        for extra in ("path", "scale"):
            if extra in hd:
                raise ScenarioError(f"{hk}.{extra}", hd[extra], "only for hull type mesh")
        hull = BoxHull(
            length=_number(hd, "length", hk, 4.0, 0.0, 1000.0, low_open=True, unit="m"),
            beam=_number(hd, "beam", hk, 2.0, 0.0, 1000.0, low_open=True, unit="m"),
            height=_number(hd, "height", hk, 1.0, 0.0, 1000.0, low_open=True, unit="m"),
        )
        subdivisions = hd.get("subdivisions", 1)
        if (isinstance(subdivisions, bool) or not isinstance(subdivisions, int)
                or not 1 <= subdivisions <= 64):
            raise ScenarioError(f"{hk}.subdivisions", subdivisions,
                                "must be an integer in [1, 64] (quads per box face edge)")
        return hull, box_mesh(hull, subdivisions)
    for extra in ("length", "beam", "height", "subdivisions"):
        if extra in hd:
            raise ScenarioError(f"{hk}.{extra}", hd[extra],
                                "only for hull type box (a mesh has its own size)")
    path = hd.get("path")
    if not isinstance(path, str) or not path:
        raise ScenarioError(f"{hk}.path", path, "must be the path of an STL or OBJ file")
    full = Path(path) if Path(path).is_absolute() else base_dir / path
    scale = _number(hd, "scale", hk, 1.0, 0.0, 1e3, low_open=True)
    try:
        mesh = load_mesh(str(full), scale)
    except HullMeshError as exc:
        raise ScenarioError(f"{hk}.path", path, str(exc)) from exc
    return BoxHull(*(float(e) for e in mesh.extents)), mesh


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
    if "density" in d:
        density = _number(d, "density", key, 0.0, 0.0, math.inf, low_open=True, unit="kg/m^3")
        mass = density * volume
    else:
        mass = _number(d, "mass", key, 0.5 * sim.water_density * volume, 0.0, math.inf,
                       low_open=True, unit="kg")
    com = _vector(d, "center_of_mass", key, 3, [0.0, 0.0, 0.0])
    inertia_raw = d.get("inertia")
    inertia = (mesh.solid_inertia(mass) if inertia_raw is None
               else _vector(d, "inertia", key, 3, [1.0, 1.0, 1.0], low=0.0))
    if np.any(inertia <= 0.0):
        raise ScenarioError(f"{key}.inertia", inertia_raw, "every moment must be > 0 (kg m^2)")
    inertia = inertia * _vector(d, "inertia_scale", key, 3, [1.0, 1.0, 1.0], low=0.01)
    products_raw = d.get("inertia_products")
    products = (_vector(d, "inertia_products", key, 3, [0.0, 0.0, 0.0])
                if products_raw is not None or inertia_raw is not None
                else mesh.inertia_products(mass))
    products[np.abs(products) < 1e-9 * inertia.max()] = 0.0  # rounding of symmetric hulls
    if np.linalg.eigvalsh(inertia_tensor(inertia, products)).min() <= 0.0:
        raise ScenarioError(f"{key}.inertia_products", products_raw,
                            "the inertia tensor must be positive definite (products of inertia "
                            "too large for the moments)")
    return mass, com, inertia, products


def _buoyancy(bd: Mapping[str, Any], bk: str, hull: BoxHull, mesh: HullMesh
              ) -> MeshBuoyancy | SamplePointBuoyancy:
    """``buoyancy``: the mesh model (with its ``drag``) or the sample points."""
    _only(bd, bk, ("model", "grid", "layout", "points", "max_depth", "curve", "alpha",
                   "direction", "depth_scale", "point_damping", "force_clamp", "drag",
                   *_MESH_ONLY))
    buoyancy_model = _choice(bd, "model", bk, "mesh", ("mesh", "sample_points"))
    if buoyancy_model == "mesh":
        for extra in bd:
            if extra not in ("model", "drag", *_MESH_ONLY):
                raise ScenarioError(f"{bk}.{extra}", bd[extra], "only for model sample_points")
        return _mesh_buoyancy(bd, bk, mesh)
    for extra in _MESH_ONLY:
        if extra in bd:
            raise ScenarioError(f"{bk}.{extra}", bd[extra], "only for model mesh")
    return _sample_points(bd, bk, hull, mesh.volume)


#: The mesh model's keys besides ``drag``.
_MESH_ONLY = ("pressure", "panels_per_wavelength", "max_triangles")


def _mesh_buoyancy(bd: Mapping[str, Any], bk: str, mesh: HullMesh) -> MeshBuoyancy:
    """The mesh model: its ``drag``, ``pressure`` model and, for ``froude_krylov``, panel size."""
    pressure = _choice(bd, "pressure", bk, "hydrostatic", PRESSURE_MODELS)
    for extra in ("panels_per_wavelength", "max_triangles"):
        if extra in bd and pressure != "froude_krylov":
            raise ScenarioError(f"{bk}.{extra}", bd[extra], "only for pressure froude_krylov")
    max_triangles = bd.get("max_triangles", 4096)
    if (isinstance(max_triangles, bool) or not isinstance(max_triangles, int)
            or not 12 <= max_triangles <= 1_000_000):
        raise ScenarioError(f"{bk}.max_triangles", max_triangles,
                            "must be an integer in [12, 1000000]")
    return MeshBuoyancy(
        mesh, _hull_drag(bd.get("drag"), f"{bk}.drag"), pressure=pressure,
        panels_per_wavelength=_number(bd, "panels_per_wavelength", bk, 10.0, 1.0, 100.0),
        max_triangles=max_triangles)


def _damping(dd: Mapping[str, Any], dk: str
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """``damping``: (6,) linear, quadratic and decay, and the critical ratios to add.

    The ratios are [heave, roll, pitch]; None adds none. Default: DEFAULT_CRITICAL_RATIO when
    ``linear`` is not given.
    """
    _only(dd, dk, ("linear", "quadratic", "critical_ratio", "decay"))
    linear = _vector(dd, "linear", dk, 6, [0.0] * 6, low=0.0)
    decay = _vector(dd, "decay", dk, 6, [0.0] * 6, low=0.0)
    quadratic = _vector(dd, "quadratic", dk, 6, [0.0] * 6, low=0.0)
    ratio_default = None if "linear" in dd else list(DEFAULT_CRITICAL_RATIO)
    ratio_raw = dd.get("critical_ratio", ratio_default)
    ratio = (None if ratio_raw is None
             else _vector({"critical_ratio": ratio_raw}, "critical_ratio", dk, 3, [0.0] * 3,
                          low=0.0))
    return linear, quadratic, decay, ratio


def _propulsion(pd: Mapping[str, Any], pk: str, hull: BoxHull) -> Propulsion:
    """``propulsion``: the thruster (default at the transom, a quarter height down)."""
    _only(pd, pk, ("max_thrust", "position", "direction", "steerable", "at_center_of_mass",
                   "time_constant"))
    direction = _vector(pd, "direction", pk, 3, [1.0, 0.0, 0.0])
    norm = float(np.linalg.norm(direction))
    if norm < 1e-9:
        raise ScenarioError(f"{pk}.direction", pd.get("direction"), "must be a non-zero vector")
    return Propulsion(
        max_thrust=_number(pd, "max_thrust", pk, 2000.0, 0.0, 1e8, low_open=True, unit="N"),
        position=_vector(pd, "position", pk, 3, [-hull.length / 2, 0.0, -hull.height / 4]),
        direction=direction / norm,
        steerable=_flag(pd, "steerable", pk, False),
        at_center_of_mass=_flag(pd, "at_center_of_mass", pk, False),
        time_constant=_number(pd, "time_constant", pk, 0.0, 0.0, 600.0, unit="s"),
    )


#: The keys each rudder model needs beyond the common ones.
_RUDDER_NEEDS = {"lift": (), "torque": ("max_torque",),
                 "hybrid": ("max_torque", "base_torque", "max_speed"), "none": ()}


def _rudder(rd: Mapping[str, Any], rk: str, hull: BoxHull) -> Rudder:
    """``rudder``: its model and the keys that model reads (default at the transom's bottom)."""
    _only(rd, rk, ("model", "max_angle_deg", "area", "lift_coefficient", "position",
                   "max_torque", "base_torque", "max_speed"))
    rudder_model = _choice(rd, "model", rk, "lift", RUDDER_MODELS)
    for k in _RUDDER_NEEDS[rudder_model]:
        if k not in rd:
            raise ScenarioError(f"{rk}.{k}", None, f"is required by the {rudder_model} model")
    return Rudder(
        model=rudder_model,
        max_angle=math.radians(_number(rd, "max_angle_deg", rk, 35.0, 0.0, 90.0, low_open=True,
                                       unit="deg")),
        area=_number(rd, "area", rk, 0.25, 0.0, 1e4, low_open=True, unit="m^2"),
        lift_coefficient=_number(rd, "lift_coefficient", rk, 1.0, 0.0, 10.0, low_open=True),
        position=_vector(rd, "position", rk, 3, [-hull.length / 2, 0.0, -hull.height / 2]),
        max_torque=_number(rd, "max_torque", rk, 0.0, 0.0, 1e9, unit="N m"),
        base_torque=_number(rd, "base_torque", rk, 0.0, 0.0, 1e9, unit="N m"),
        max_speed=_number(rd, "max_speed", rk, 1.0, 0.0, 1e3, low_open=True, unit="m/s"),
    )


def _keel_rate(kd: Mapping[str, Any], kk: str) -> float:
    """``keel``: 1/s, the reflection rate (0 for the default ``damping`` keel)."""
    _only(kd, kk, ("model", "rate"))
    keel_model = _choice(kd, "model", kk, "damping", ("damping", "reflection"))
    return (_number(kd, "rate", kk, 1.0, 0.0, 1e3, low_open=True, unit="1/s")
            if keel_model == "reflection" else 0.0)


def _hydrodynamics(raw: Any, key: str, base_dir: Path, com: np.ndarray
                   ) -> HydroCoefficients | None:
    """``hydrodynamics``: the hull's potential-flow coefficient file (``coefficients``), or None.

    A relative path is taken from the scenario's directory. The file must have been solved
    about the boat's centre of mass.
    """
    d = _mapping(raw, key)
    _only(d, key, ("coefficients",))
    if "coefficients" not in d:
        return None
    path = d["coefficients"]
    if not isinstance(path, str) or not path:
        raise ScenarioError(f"{key}.coefficients", path,
                            "must be the path of a .npz coefficient file (boatsim hydro)")
    full = Path(path) if Path(path).is_absolute() else base_dir / path
    try:
        coefficients = load_coefficients(full)
    except HydroFileError as exc:
        raise ScenarioError(f"{key}.coefficients", path, str(exc)) from exc
    if not np.allclose(coefficients.center_of_mass, com, rtol=0.0, atol=1e-6):
        raise ScenarioError(f"{key}.coefficients", path,
                            f"was solved about the centre of mass "
                            f"{coefficients.center_of_mass.tolist()}, the boat's is "
                            f"{com.tolist()} (m)")
    return coefficients


def _initial(params: BoatParams, idd: Mapping[str, Any], ik: str) -> BoatState:
    """``initial_pose``: the state at rest there (hull reference point, degrees).

    At rest: :func:`boat_dynamics.physics.pipeline.init` sets it afloat in the waves.
    """
    return initial_state(
        params,
        _vector(idd, "position", ik, 3, [0.0, 0.0, 0.0]),
        roll=math.radians(_number(idd, "roll_deg", ik, 0.0, -180.0, 180.0, unit="deg")),
        pitch=math.radians(_number(idd, "pitch_deg", ik, 0.0, -90.0, 90.0, unit="deg")),
        yaw=math.radians(_number(idd, "yaw_deg", ik, 0.0, -360.0, 360.0, unit="deg")),
    )


#: Damping ratios [heave, roll, pitch] of the default linear damping (critical-damping helper).
DEFAULT_CRITICAL_RATIO = (0.2, 0.1, 0.2)
def _hull_drag(raw: Any, key: str) -> HullDrag:
    d = _mapping(raw, key)
    fields = ("viscous", "form_factor", "kinematic_viscosity", "pressure", "reference_speed",
              "pressure_linear", "pressure_quadratic", "suction_linear", "suction_quadratic",
              "pressure_falloff", "suction_falloff")
    _only(d, key, fields)
    base = HullDrag()
    return HullDrag(
        viscous=_flag(d, "viscous", key, False),
        form_factor=_number(d, "form_factor", key, base.form_factor, 0.0, 10.0),
        kinematic_viscosity=_number(d, "kinematic_viscosity", key, base.kinematic_viscosity,
                                    0.0, 1e-2, low_open=True, unit="m^2/s"),
        pressure=_flag(d, "pressure", key, False),
        reference_speed=_number(d, "reference_speed", key, 1.0, 0.0, 100.0, low_open=True,
                                unit="m/s"),
        **{name: _number(d, name, key, getattr(base, name), 0.0, 1e6)
           for name in ("pressure_linear", "pressure_quadratic", "suction_linear",
                        "suction_quadratic", "pressure_falloff", "suction_falloff")},
    )


def _sample_points(bd: Mapping[str, Any], bk: str, hull: BoxHull,
                   volume: float) -> SamplePointBuoyancy:
    if "drag" in bd:
        raise ScenarioError(f"{bk}.drag", bd["drag"], "only for model mesh (drag acts on the "
                            "hull triangles)")
    layout = _choice(bd, "layout", bk, "grid", ("grid", "boat", "custom"))
    if layout != "grid" and "grid" in bd:
        raise ScenarioError(f"{bk}.grid", bd["grid"], "only for layout grid")
    if layout == "grid":
        grid = bd.get("grid", [5, 3])
        if (not isinstance(grid, list) or len(grid) != 2
                or not all(isinstance(g, int) and not isinstance(g, bool) and 1 <= g <= 100
                           for g in grid)):
            raise ScenarioError(f"{bk}.grid", grid, "must be [nx, ny], integers in [1, 100]")
        points = hull.bottom_grid(*grid)
    elif layout == "boat":
        points = hull.boat_layout()
    else:
        raw = bd.get("points")
        if (not isinstance(raw, list) or not raw or not all(
                isinstance(p, list) and len(p) == 3
                and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                        and math.isfinite(x) for x in p) for p in raw)):
            raise ScenarioError(f"{bk}.points", raw,
                                "layout custom needs a list of [x, y, z] body points (m)")
        points = np.array(raw, dtype=float)
    if "points" in bd and layout != "custom":
        raise ScenarioError(f"{bk}.points", bd["points"], "only for layout custom")
    clamp = bd.get("force_clamp")
    if clamp is not None:
        clamp = _number(bd, "force_clamp", bk, 1.0, 0.0, 100.0, low_open=True)
    return SamplePointBuoyancy(
        points=points, volume=volume,
        max_depth=_number(bd, "max_depth", bk, hull.height, 0.0, 1000.0, low_open=True,
                          unit="m"),
        curve=_choice(bd, "curve", bk, "linear", CURVES),
        alpha=_number(bd, "alpha", bk, 3.0, 0.0, 100.0, low_open=True),
        direction=_choice(bd, "direction", bk, "up", POINT_DIRECTIONS),
        depth_scale=_flag(bd, "depth_scale", bk, False),
        point_damping=_number(bd, "point_damping", bk, 0.0, 0.0, 1000.0, unit="1/s"),
        force_clamp=clamp,
    )


def _control(d: Mapping[str, Any], key: str) -> ControlSettings:
    mode = _choice(d, "control_mode", key, "dynamic", CONTROL_MODES)
    ck = f"{key}.control"
    cd = _mapping(d.get("control"), ck)
    _only(cd, ck, ("smoothing", "attitude", "pd_frequency", "pd_damping", "blend",
                   "depth_band", "max_angular_velocity", "rescue_depth", "transition"))
    return ControlSettings(
        mode=mode,
        smoothing=_number(cd, "smoothing", ck, 0.3, 0.0, 60.0, low_open=True, unit="s"),
        attitude=_choice(cd, "attitude", ck, "smooth", ATTITUDES),
        pd_frequency=_number(cd, "pd_frequency", ck, 1.0, 0.0, 50.0, low_open=True, unit="Hz"),
        pd_damping=_number(cd, "pd_damping", ck, 1.0, 0.0, 10.0, low_open=True),
        blend=_number(cd, "blend", ck, 0.7, 0.0, 1.0),
        depth_band=_number(cd, "depth_band", ck, 1.0, 0.0, 100.0, low_open=True, unit="m"),
        max_angular_velocity=_number(cd, "max_angular_velocity", ck, 3.0, 0.0, 100.0,
                                     low_open=True, unit="rad/s"),
        rescue_depth=_number(cd, "rescue_depth", ck, 3.0, 0.0, 1000.0, low_open=True, unit="m"),
        transition=_number(cd, "transition", ck, 1.0, 0.0, 60.0, unit="s"),
    )


def _commands(raw: Any, key: str, max_rudder: float) -> CommandScript | None:
    if raw is None:
        return None
    if not isinstance(raw, list) or not raw:
        raise ScenarioError(key, raw, "must be a non-empty list of {t, thrust, rudder}")
    times, throttles, rudders = [], [], []
    for i, entry in enumerate(raw):
        ek = f"{key}[{i}]"
        ed = _mapping(entry, ek)
        _only(ed, ek, ("t", "thrust", "rudder"))
        t = _number(ed, "t", ek, 0.0, 0.0, unit="s")
        if times and t <= times[-1]:
            raise ScenarioError(f"{ek}.t", t,
                                f"must be later than the previous entry ({times[-1]})")
        times.append(t)
        throttles.append(_number(ed, "thrust", ek, 0.0, -1.0, 1.0))
        rudders.append(_number(ed, "rudder", ek, 0.0, -max_rudder, max_rudder, unit="rad"))
    return CommandScript(tuple(times), tuple(throttles), tuple(rudders))


def parse_scenario(data: Any, source: str = "<scenario>", base_dir: Path | None = None
                   ) -> Scenario:
    """Validate a scenario given as parsed YAML (nested dicts and lists).

    Relative mesh paths are resolved against ``base_dir`` (the scenario file's directory;
    default: the current directory).

    Raises:
        ScenarioError: an invalid key or value, named by its path.
    """
    d = _mapping(data, "")
    _only(d, "", ("simulation", "ocean", "boats"))
    sim = _simulation(d.get("simulation"))
    sea = _ocean(d.get("ocean"), sim)
    boats_raw = d.get("boats")
    if boats_raw is None:
        boats_raw = [{}]
    if not isinstance(boats_raw, list) or not boats_raw:
        raise ScenarioError("boats", boats_raw, "must be a non-empty list of boats")
    lone = len(boats_raw) == 1
    base = Path.cwd() if base_dir is None else base_dir
    boats = tuple(_boat(b, f"boats[{i}]", sim, lone, base) for i, b in enumerate(boats_raw))
    names = [b.name for b in boats]
    for i, n in enumerate(names):
        if names.index(n) != i:
            raise ScenarioError(f"boats[{i}].name", n, "must be unique among the boats")
    return Scenario(simulation=sim, sea=sea, boats=boats, source=source)
