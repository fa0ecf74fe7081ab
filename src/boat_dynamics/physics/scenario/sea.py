"""The ``simulation`` and ``ocean`` sections (explicit components and generated spectra)."""

from __future__ import annotations

import math
from typing import Any

from boat_dynamics.physics.scenario.read import (
    choice,
    describe,
    flag,
    integer,
    mapping,
    number,
    only,
)
from boat_dynamics.physics.scenario.sensors import datum_block, magnetic_field_block
from boat_dynamics.physics.scenario.specs import (
    TF_FRAMES,
    WRENCH_TOPICS,
    ScenarioError,
    SimulationSettings,
)
from ocean_sim.physics.constants import GRAVITY, WATER_DENSITY
from ocean_sim.physics.environment import (
    GUST_MODELS,
    MAX_CURRENT_SPEED,
    MAX_GUST_COMPONENTS,
    MAX_WIND_SPEED,
    Environment,
    Wind,
)
from ocean_sim.physics.fft import FFT_SPECTRA, MAX_RESOLUTION, OCEAN_MODELS, TileSpec, tile_sea
from ocean_sim.physics.spectra import SPECTRUM_TYPES, SpectrumSpec, beaufort_sea, generate_sea
from ocean_sim.physics.waves import (
    DEFAULT_PRECISION,
    PRECISIONS,
    InvalidSeaStateError,
    WaveComponent,
    WaveField,
)


def simulation_block(raw: Any) -> SimulationSettings:
    """The ``simulation:`` block."""
    key = "simulation"
    d = mapping(raw, key)
    only(d, key, ("rate_hz", "publish_rate_hz", "diagnostics_rate_hz", "realtime", "duration",
                   "seed", "gravity", "water_density", "cmd_timeout", "substeps",
                   "wave_precision", "datum", "magnetic_field", "publish_tf", "frames",
                   "wrench_topics", "fleet_state"))
    rate = number(d, "rate_hz", key, 100.0, 1.0, 10000.0, unit="Hz")
    pub = number(d, "publish_rate_hz", key, 50.0, 0.0, rate, low_open=True, unit="Hz",
                 range_doc="(0, rate_hz] Hz")
    diag = number(d, "diagnostics_rate_hz", key, 10.0, 0.0, rate, low_open=True, unit="Hz",
                  range_doc="(0, rate_hz] Hz")
    realtime = flag(d, "realtime", key, True)
    describe(f"{key}.duration", None, "number in (0, inf] s, or null: until stopped")
    duration = d.get("duration")
    if duration is not None:
        duration = number(d, "duration", key, 0.0, 0.0, math.inf, low_open=True, unit="s")
    substeps = integer(d, "substeps", key, 1, 1, 100)
    seed = integer(d, "seed", key, 0, 0)
    return SimulationSettings(
        rate_hz=rate,
        publish_rate_hz=pub,
        diagnostics_rate_hz=diag,
        realtime=realtime,
        duration=duration,
        seed=seed,
        gravity=number(d, "gravity", key, GRAVITY, 0.0, 100.0, low_open=True, unit="m/s^2"),
        water_density=number(d, "water_density", key, WATER_DENSITY, 0.0, 1e5, low_open=True,
                              unit="kg/m^3"),
        cmd_timeout=number(d, "cmd_timeout", key, 1.0, 0.0, 3600.0, low_open=True, unit="s"),
        substeps=substeps,
        wave_precision=choice(d, "wave_precision", key, DEFAULT_PRECISION, PRECISIONS),
        datum=datum_block(d.get("datum")),
        magnetic_field=magnetic_field_block(d.get("magnetic_field")),
        publish_tf=flag(d, "publish_tf", key, True),
        frames=choice(d, "frames", key, "world", TF_FRAMES),
        wrench_topics=choice(d, "wrench_topics", key, "auto", WRENCH_TOPICS),
        fleet_state=flag(d, "fleet_state", key, False),
    )


def environment_block(raw: Any, seed: int) -> Environment:
    """The ``environment:`` block: the current and the wind.

    ``current: {speed, direction_deg}``, ``wind: {speed, direction_deg, gusts, components}``;
    directions are where they go toward; the gusts' phases come from ``seed``.
    """
    key = "environment"
    d = mapping(raw, key)
    only(d, key, ("current", "wind"))
    ck, wk = f"{key}.current", f"{key}.wind"
    c, w = mapping(d.get("current"), ck), mapping(d.get("wind"), wk)
    only(c, ck, ("speed", "direction_deg"))
    only(w, wk, ("speed", "direction_deg", "gusts", "components"))
    components = integer(w, "components", wk, 50, 1, MAX_GUST_COMPONENTS)
    wind = Wind.make(number(w, "speed", wk, 0.0, 0.0, MAX_WIND_SPEED, unit="m/s"),
                     math.radians(number(w, "direction_deg", wk, 0.0, -360.0, 360.0,
                                         unit="deg")),
                     choice(w, "gusts", wk, "none", GUST_MODELS), components, seed)
    return Environment(number(c, "speed", ck, 0.0, 0.0, MAX_CURRENT_SPEED, unit="m/s"),
                       math.radians(number(c, "direction_deg", ck, 0.0, -360.0, 360.0,
                                           unit="deg")), wind)


def ocean_block(raw: Any, sim: SimulationSettings) -> WaveField:
    """The ``ocean:`` block: explicit components and/or a generated spectrum, or an FFT tile.

    ``model: gerstner`` (the default) sums ``components`` and ``spectrum``; ``model: fft`` is
    the tile of ``fft:`` (ocean_sim/physics/fft.py), as its Gerstner components.
    """
    key = "ocean"
    d = mapping(raw, key)
    only(d, key, ("model", "depth", "components", "spectrum", "fft"))
    model = choice(d, "model", key, "gerstner", OCEAN_MODELS)
    depth = number(d, "depth", key, math.inf, 0.0, math.inf, low_open=True, unit="m",
                    allow_inf=True)
    if model == "fft":
        for other in ("components", "spectrum"):
            if other in d:
                raise ScenarioError(f"{key}.{other}", d[other],
                                    "not with ocean.model fft: the sea is the tile of ocean.fft")
        return _fft(d.get("fft"), sim, depth)
    if "fft" in d:
        raise ScenarioError(f"{key}.fft", d["fft"], "only with ocean.model: fft")
    generated = _spectrum(d.get("spectrum"), sim, depth)
    describe(f"{key}.components", None, "a list of {amplitude, wavelength, direction_deg, "
             "steepness, phase}", default_doc="none")
    comps_raw = d.get("components") or []
    if not isinstance(comps_raw, list):
        raise ScenarioError(f"{key}.components", comps_raw, "must be a list of components")
    comps = []
    for i, c in enumerate(comps_raw):
        ck = f"{key}.components[{i}]"
        cd = mapping(c, ck)
        only(cd, ck, ("amplitude", "wavelength", "direction_deg", "steepness", "phase"))
        comps.append(WaveComponent(
            amplitude=number(cd, "amplitude", ck, 0.0, 0.0, unit="m"),
            wavelength=number(cd, "wavelength", ck, 10.0, 0.0, low_open=True, unit="m"),
            direction=math.radians(number(cd, "direction_deg", ck, 0.0, unit="deg")),
            steepness=number(cd, "steepness", ck, 0.0, 0.0, 1.0),
            phase=number(cd, "phase", ck, 0.0, unit="rad"),
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
    d = mapping(raw, key)
    only(d, key, _SPECTRUM_KEYS)
    kind = choice(d, "type", key, "jonswap", SPECTRUM_TYPES)
    describe(f"{key}.spreading", 10.0, "number in [0, 1000] (s of cos-2s: larger is "
             "narrower), or null: every component in direction_deg")
    spreading = d.get("spreading", 10.0)
    if spreading is not None:
        spreading = number(d, "spreading", key, 10.0, 0.0, 1000.0)
    n = integer(d, "components", key, 16, 1, 1000)
    describe(f"{key}.beaufort", None, "integer in [0, 12]: a fully developed "
             "pierson_moskowitz sea of that force (instead of significant_height and "
             "peak_period)", default_doc="none")
    direction = math.radians(number(d, "direction_deg", key, 0.0, -360.0, 360.0, unit="deg"))
    steepness = number(d, "steepness", key, 0.5, 0.0, 1.0)
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
                significant_height=number(d, "significant_height", key, 1.0, 0.0, 30.0,
                                           unit="m"),
                peak_period=number(d, "peak_period", key, 6.0, 0.5, 40.0, unit="s"),
                direction=direction, spreading=spreading, components=n,
                gamma=number(d, "gamma", key, 3.3, 1.0, 7.0), steepness=steepness,
            )
            sea = generate_sea(spec, seed=sim.seed, gravity=sim.gravity, depth=depth)
    except InvalidSeaStateError as exc:
        raise ScenarioError(f"ocean.{exc.key}", exc.value, exc.allowed) from exc
    return sea.components


#: ``ocean.fft`` keys that only one spectrum reads.
_FFT_ONLY = {"wind_speed": "phillips", "phillips_constant": "phillips",
             "significant_height": "jonswap", "peak_period": "jonswap", "gamma": "jonswap",
             "spreading": "jonswap"}


def _fft(raw: Any, sim: SimulationSettings, depth: float) -> WaveField:
    """The sea of ``ocean.fft``: Tessendorf's tile as Gerstner components."""
    key = "ocean.fft"
    d = mapping(raw, key)
    only(d, key, ("size", "resolution", "seed", "spectrum", "direction_deg", "choppiness",
                  "suppression_length", *_FFT_ONLY))
    spectrum = choice(d, "spectrum", key, "phillips", FFT_SPECTRA)
    for name, owner in _FFT_ONLY.items():
        if name in d and owner != spectrum:
            raise ScenarioError(f"{key}.{name}", d[name], f"only with spectrum: {owner}")
    resolution = integer(d, "resolution", key, 32, 4, MAX_RESOLUTION,
                         note="and even (N x N points, (N - 1)^2 waves)")
    if resolution % 2:
        raise ScenarioError(f"{key}.resolution", resolution,
                            f"must be an even integer in [4, {MAX_RESOLUTION}]")
    describe(f"{key}.seed", None, "integer >= 0", default_doc="simulation.seed")
    seed = d.get("seed", sim.seed)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ScenarioError(f"{key}.seed", seed, "must be an integer >= 0")
    values = dict(
        size=number(d, "size", key, 200.0, 0.0, 1e6, low_open=True, unit="m"),
        resolution=resolution, seed=seed, spectrum=spectrum,
        wind_speed=number(d, "wind_speed", key, 8.0, 0.0, 100.0, unit="m/s"),
        phillips_constant=number(d, "phillips_constant", key, TileSpec.phillips_constant,
                                 0.0, 1.0, default_doc="0.00175: Pierson-Moskowitz's "
                                 "H_s = 0.21 U^2 / g"),
        significant_height=number(d, "significant_height", key, 1.0, 0.0, 30.0, unit="m"),
        peak_period=number(d, "peak_period", key, 6.0, 0.5, 40.0, unit="s"),
        gamma=number(d, "gamma", key, 3.3, 1.0, 7.0),
        spreading=number(d, "spreading", key, 10.0, 0.0, 1000.0),
        direction=math.radians(number(d, "direction_deg", key, 0.0, -360.0, 360.0,
                                      unit="deg")),
        choppiness=number(d, "choppiness", key, 0.5, 0.0, 1.0),
        suppression_length=number(
            d, "suppression_length", key, 0.0, 0.0, 1e6, unit="m",
            default_doc="0: none", range_doc="[0, ocean.fft.size] m (Tessendorf's small-wave "
            "suppression P(k) exp(-k^2 l^2): waves shorter than l removed)"),
        gravity=sim.gravity, depth=depth)
    try:
        return tile_sea(TileSpec(**values))
    except InvalidSeaStateError as exc:
        raise ScenarioError(f"ocean.{exc.key}", exc.value, exc.allowed) from exc
