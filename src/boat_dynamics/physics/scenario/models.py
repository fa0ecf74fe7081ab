"""The model blocks of a boat: buoyancy, hull drag, thruster, rudder, keel, control mode."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from boat_dynamics.physics.body.hull import BoxHull, HullMesh
from boat_dynamics.physics.force_models.buoyancy import (
    CURVES,
    POINT_DIRECTIONS,
    SamplePointBuoyancy,
)
from boat_dynamics.physics.force_models.control import ATTITUDES, CONTROL_MODES, ControlSettings
from boat_dynamics.physics.force_models.hull_drag import HullDrag
from boat_dynamics.physics.force_models.mesh_buoyancy import PRESSURE_MODELS, MeshBuoyancy
from boat_dynamics.physics.force_models.propulsion import MAX_THRUSTERS, Propulsion
from boat_dynamics.physics.force_models.rudder import (
    DEFAULT_LIFT_COEFFICIENT,
    RUDDER_MODELS,
    Rudder,
)
from boat_dynamics.physics.force_models.slamming import SLAMMING_MODELS, Slamming
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
from boat_dynamics.physics.scenario.specs import ScenarioError


def buoyancy_block(bd: Mapping[str, Any], bk: str, hull: BoxHull, mesh: HullMesh
              ) -> MeshBuoyancy | SamplePointBuoyancy:
    """``buoyancy``: the mesh model (with its ``drag``) or the sample points."""
    only(bd, bk, ("model", "grid", "layout", "points", "max_depth", "curve", "alpha",
                   "direction", "depth_scale", "point_damping", "force_clamp", "drag",
                   *_MESH_ONLY))
    buoyancy_model = choice(bd, "model", bk, "mesh", ("mesh", "sample_points"))
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
_MESH_ONLY = ("pressure", "panels_per_wavelength", "max_triangles", "slamming")


def _mesh_buoyancy(bd: Mapping[str, Any], bk: str, mesh: HullMesh) -> MeshBuoyancy:
    """The mesh model: its ``drag``, ``pressure`` model and, for ``froude_krylov``, panel size."""
    pressure = choice(bd, "pressure", bk, "froude_krylov", PRESSURE_MODELS)
    for extra in ("panels_per_wavelength", "max_triangles"):
        if extra in bd and pressure != "froude_krylov":
            raise ScenarioError(f"{bk}.{extra}", bd[extra], "only for pressure froude_krylov")
    max_triangles = integer(bd, "max_triangles", bk, 4096, 12, 1_000_000)
    return MeshBuoyancy(
        mesh, _hull_drag(bd.get("drag"), f"{bk}.drag"), pressure=pressure,
        panels_per_wavelength=number(bd, "panels_per_wavelength", bk, 10.0, 1.0, 100.0),
        max_triangles=max_triangles,
        slamming=_slamming(bd.get("slamming", "none"), f"{bk}.slamming"))


def _slamming(raw: Any, key: str) -> Slamming:
    """``slamming``: a model name, or ``{model, power, acceleration_max}`` (``kerner``)."""
    if isinstance(raw, str):
        raw = {"model": raw}
        key = key.rsplit(".", 1)[0]  # a bare name is read as the key itself
        model = choice({"slamming": raw["model"]}, "slamming", key, "none", SLAMMING_MODELS)
        return Slamming(model)
    d = mapping(raw, key)
    only(d, key, ("model", "power", "acceleration_max"))
    model = choice(d, "model", key, "none", SLAMMING_MODELS)
    for extra in ("power", "acceleration_max"):
        if extra in d and model != "kerner":
            raise ScenarioError(f"{key}.{extra}", d[extra], "only for model kerner")
    return Slamming(model, number(d, "power", key, 2.0, 0.0, 10.0, low_open=True),
                    number(d, "acceleration_max", key, 50.0, 0.0, 1e6, low_open=True,
                           unit="m/s^2"))


def propulsion_block(raw: Any, pk: str, hull: BoxHull
                     ) -> tuple[Propulsion | tuple[Propulsion, ...], tuple[str, ...]]:
    """``propulsion``: one thruster (a mapping), or a list of named thrusters.

    Returns:
        The thruster (a mapping) or the tuple of thrusters (a list), and their names (empty
        for a mapping: the boat then has no per-thruster topics).
    """
    if not isinstance(raw, list):
        return _thruster(mapping(raw, pk), pk, hull), ()
    if not 1 <= len(raw) <= MAX_THRUSTERS:
        raise ScenarioError(pk, raw, f"must be a mapping, or a list of 1 to {MAX_THRUSTERS} "
                                     "thrusters")
    models, names = [], []
    for i, item in enumerate(raw):
        k = f"{pk}[{i}]"
        d = mapping(item, k)
        describe(f"{k}.name", None, f"{ROS_NAME_RULE}; unique on the boat",
                 default_doc="required")
        name = d.get("name")
        if not is_ros_name(name):
            raise ScenarioError(f"{k}.name", name, f"is required: {ROS_NAME_RULE}")
        if name in names:
            raise ScenarioError(f"{k}.name", name, "must be unique among the boat's thrusters")
        names.append(name)
        rest = {key: v for key, v in d.items() if key not in ("name", "max_angle_deg")}
        model = _thruster(rest, k, hull)
        if "max_angle_deg" in d and not model.steerable:
            raise ScenarioError(f"{k}.max_angle_deg", d["max_angle_deg"],
                                "only for a steerable thruster (steerable: true)")
        max_angle = number(d, "max_angle_deg", k, 35.0, 0.0, 180.0, low_open=True, unit="deg")
        only(d, k, ("name", "max_angle_deg", "max_thrust", "position", "direction",
                    "steerable", "at_center_of_mass", "time_constant"))
        models.append(replace(model, max_angle=math.radians(max_angle)))
    return tuple(models), tuple(names)


def _thruster(pd: Mapping[str, Any], pk: str, hull: BoxHull) -> Propulsion:
    """One thruster (default at the transom, a quarter height down)."""
    only(pd, pk, ("max_thrust", "position", "direction", "steerable", "at_center_of_mass",
                   "time_constant"))
    direction = vector(pd, "direction", pk, 3, [1.0, 0.0, 0.0])
    norm = float(np.linalg.norm(direction))
    if norm < 1e-9:
        raise ScenarioError(f"{pk}.direction", pd.get("direction"), "must be a non-zero vector")
    return Propulsion(
        max_thrust=number(pd, "max_thrust", pk, 2000.0, 0.0, 1e8, low_open=True, unit="N"),
        position=vector(pd, "position", pk, 3, [-hull.length / 2, 0.0, -hull.height / 4],
                        default_doc="[-length/2, 0, -height/4]: the transom",
                        unit="m, body frame"),
        direction=direction / norm,
        steerable=flag(pd, "steerable", pk, False),
        at_center_of_mass=flag(pd, "at_center_of_mass", pk, False),
        time_constant=number(pd, "time_constant", pk, 0.0, 0.0, 600.0, unit="s"),
    )


#: The keys each rudder model needs beyond the common ones.
_RUDDER_NEEDS = {"lift": (), "torque": ("max_torque",),
                 "hybrid": ("max_torque", "base_torque", "max_speed"), "none": ()}


def rudder_block(rd: Mapping[str, Any], rk: str, hull: BoxHull) -> Rudder:
    """``rudder``: its model and the keys that model reads (default at the transom's bottom)."""
    only(rd, rk, ("model", "max_angle_deg", "area", "lift_coefficient", "position",
                   "max_torque", "base_torque", "max_speed", "skeg_area"))
    rudder_model = choice(rd, "model", rk, "lift", RUDDER_MODELS)
    if "skeg_area" in rd and rudder_model != "lift":
        raise ScenarioError(f"{rk}.skeg_area", rd["skeg_area"], "only for rudder model lift")
    for k in _RUDDER_NEEDS[rudder_model]:
        if k not in rd:
            raise ScenarioError(f"{rk}.{k}", None, f"is required by the {rudder_model} model")
    return Rudder(
        model=rudder_model,
        max_angle=math.radians(number(rd, "max_angle_deg", rk, 35.0, 0.0, 90.0, low_open=True,
                                       unit="deg")),
        area=number(rd, "area", rk, 0.25, 0.0, 1e4, low_open=True, unit="m^2"),
        lift_coefficient=number(rd, "lift_coefficient", rk, DEFAULT_LIFT_COEFFICIENT, 0.0, 10.0,
                                low_open=True, unit="1/rad"),
        position=vector(rd, "position", rk, 3, [-hull.length / 2, 0.0, -hull.height / 2],
                        default_doc="[-length/2, 0, -height/2]: the transom's bottom",
                        unit="m, body frame"),
        max_torque=number(rd, "max_torque", rk, 0.0, 0.0, 1e9, unit="N m"),
        base_torque=number(rd, "base_torque", rk, 0.0, 0.0, 1e9, unit="N m"),
        max_speed=number(rd, "max_speed", rk, 1.0, 0.0, 1e3, low_open=True, unit="m/s"),
        skeg_area=number(rd, "skeg_area", rk, 0.0, 0.0, 1e4, unit="m^2"),
    )


def keel_block(kd: Mapping[str, Any], kk: str) -> float:
    """``keel``: 1/s, the reflection rate (0 for the default ``damping`` keel)."""
    only(kd, kk, ("model", "rate"))
    keel_model = choice(kd, "model", kk, "damping", ("damping", "reflection"))
    return (number(kd, "rate", kk, 1.0, 0.0, 1e3, low_open=True, unit="1/s")
            if keel_model == "reflection" else 0.0)


def _hull_drag(raw: Any, key: str) -> HullDrag:
    d = mapping(raw, key)
    fields = ("viscous", "form_factor", "kinematic_viscosity", "pressure", "reference_speed",
              "pressure_linear", "pressure_quadratic", "suction_linear", "suction_quadratic",
              "pressure_falloff", "suction_falloff")
    only(d, key, fields)
    base = HullDrag()
    return HullDrag(
        viscous=flag(d, "viscous", key, False),
        form_factor=number(d, "form_factor", key, base.form_factor, 0.0, 10.0),
        kinematic_viscosity=number(d, "kinematic_viscosity", key, base.kinematic_viscosity,
                                    0.0, 1e-2, low_open=True, unit="m^2/s"),
        pressure=flag(d, "pressure", key, False),
        reference_speed=number(d, "reference_speed", key, 1.0, 0.0, 100.0, low_open=True,
                                unit="m/s"),
        **{name: number(d, name, key, getattr(base, name), 0.0, 1e6)
           for name in ("pressure_linear", "pressure_quadratic", "suction_linear",
                        "suction_quadratic", "pressure_falloff", "suction_falloff")},
    )


def _sample_points(bd: Mapping[str, Any], bk: str, hull: BoxHull,
                   volume: float) -> SamplePointBuoyancy:
    if "drag" in bd:
        raise ScenarioError(f"{bk}.drag", bd["drag"], "only for model mesh (drag acts on the "
                            "hull triangles)")
    layout = choice(bd, "layout", bk, "grid", ("grid", "boat", "custom"))
    if layout != "grid" and "grid" in bd:
        raise ScenarioError(f"{bk}.grid", bd["grid"], "only for layout grid")
    describe(f"{bk}.grid", [5, 3], "[nx, ny], integers in [1, 100]: points under the hull's "
             "bottom (layout grid)")
    describe(f"{bk}.points", None, "a list of [x, y, z] body points, m (layout custom)",
             default_doc="required with layout custom")
    describe(f"{bk}.force_clamp", None, "number in (0, 100]: a point's force at most this "
             "many times its share of the weight", default_doc="none")
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
        clamp = number(bd, "force_clamp", bk, 1.0, 0.0, 100.0, low_open=True)
    curve = choice(bd, "curve", bk, "linear", CURVES)
    depth = hull.height
    if curve == "sphere":  # default: spheres that together have the hull's volume
        depth = (6.0 * volume / (math.pi * points.shape[0])) ** (1.0 / 3.0)
    max_depth = number(bd, "max_depth", bk, depth, 0.0, 1000.0, low_open=True, unit="m",
                       default_doc="the hull's height (curve sphere: the diameter of spheres "
                       "that together have the hull's volume)")
    if curve == "sphere":
        volume = points.shape[0] * math.pi * max_depth**3 / 6.0
    return SamplePointBuoyancy(
        points=points, volume=volume, max_depth=max_depth, curve=curve,
        alpha=number(bd, "alpha", bk, 3.0, 0.0, 100.0, low_open=True),
        direction=choice(bd, "direction", bk, "up", POINT_DIRECTIONS),
        depth_scale=flag(bd, "depth_scale", bk, False),
        point_damping=number(bd, "point_damping", bk, 0.0, 0.0, 1000.0, unit="1/s"),
        force_clamp=clamp,
    )


def control_block(d: Mapping[str, Any], key: str) -> ControlSettings:
    """``control_mode`` and the ``control:`` block."""
    mode = choice(d, "control_mode", key, "dynamic", CONTROL_MODES)
    ck = f"{key}.control"
    cd = mapping(d.get("control"), ck)
    only(cd, ck, ("smoothing", "attitude", "pd_frequency", "pd_damping", "blend",
                   "depth_band", "max_angular_velocity", "rescue_depth", "transition"))
    return ControlSettings(
        mode=mode,
        smoothing=number(cd, "smoothing", ck, 0.3, 0.0, 60.0, low_open=True, unit="s"),
        attitude=choice(cd, "attitude", ck, "smooth", ATTITUDES),
        pd_frequency=number(cd, "pd_frequency", ck, 1.0, 0.0, 50.0, low_open=True, unit="Hz"),
        pd_damping=number(cd, "pd_damping", ck, 1.0, 0.0, 10.0, low_open=True),
        blend=number(cd, "blend", ck, 0.7, 0.0, 1.0),
        depth_band=number(cd, "depth_band", ck, 1.0, 0.0, 100.0, low_open=True, unit="m"),
        max_angular_velocity=number(cd, "max_angular_velocity", ck, 3.0, 0.0, 100.0,
                                     low_open=True, unit="rad/s"),
        rescue_depth=number(cd, "rescue_depth", ck, 3.0, 0.0, 1000.0, low_open=True, unit="m"),
        transition=number(cd, "transition", ck, 1.0, 0.0, 60.0, unit="s"),
    )
