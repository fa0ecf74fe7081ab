"""The ``sensors`` list of a boat, the ``simulation.datum`` and ``magnetic_field`` blocks."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

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
from boat_dynamics.physics.sensors import (
    AisSpec,
    Datum,
    DepthSounderSpec,
    EarthField,
    GnssNoise,
    GnssSpec,
    ImuSpec,
    InertialNoise,
    LidarSpec,
    MagnetometerSpec,
    OdometryNoise,
    OdometrySpec,
    SensorSpec,
)
from boat_dynamics.physics.sensors.gnss import Multipath
from boat_dynamics.physics.sensors.imu import ACCELEROMETER, GYROSCOPE
from boat_dynamics.physics.sensors.lidar import SEA_RETURNS
from boat_dynamics.physics.sensors.radar import RadarSpec

__all__ = ["MAX_LATENCY", "MAX_MOUNT", "SENSOR_TYPES", "datum_block", "magnetic_field_block",
           "sensors_block"]

#: The ``type`` of a sensor.
SENSOR_TYPES = ("imu", "gnss", "odometry", "magnetometer", "depth_sounder", "lidar", "ais",
                "radar")
#: Hz, each type's default ``rate_hz``.
_RATES = {"imu": 100.0, "gnss": 5.0, "odometry": 50.0, "magnetometer": 20.0,
          "depth_sounder": 10.0, "lidar": 10.0, "ais": 1.0, "radar": 10.0}


def datum_block(raw: Any, key: str = "simulation.datum") -> Datum:
    """``{latitude_deg, longitude_deg, altitude}``: the world origin on WGS-84."""
    d = mapping(raw, key)
    only(d, key, ("latitude_deg", "longitude_deg", "altitude"))
    default = Datum()
    return Datum(
        latitude=math.radians(number(d, "latitude_deg", key, math.degrees(default.latitude),
                                     -89.0, 89.0, unit="deg")),
        longitude=math.radians(number(d, "longitude_deg", key,
                                      math.degrees(default.longitude), -180.0, 180.0,
                                      unit="deg")),
        altitude=number(d, "altitude", key, 0.0, -1000.0, 10000.0, unit="m"))


def magnetic_field_block(raw: Any, key: str = "simulation.magnetic_field") -> EarthField:
    """``{declination_deg, inclination_deg, intensity_nT}``: the Earth's field at the datum.

    As a world magnetic model's calculator gives it (NOAA's WMM: D, I, F); the default is
    WMM2025's at the default datum (:class:`EarthField`).
    """
    d = mapping(raw, key)
    only(d, key, ("declination_deg", "inclination_deg", "intensity_nT"))
    default = EarthField()
    return EarthField(
        declination=math.radians(number(d, "declination_deg", key,
                                        round(math.degrees(default.declination), 2),
                                        -180.0, 180.0, unit="deg, east of true north")),
        inclination=math.radians(number(d, "inclination_deg", key,
                                        round(math.degrees(default.inclination), 2),
                                        -90.0, 90.0, unit="deg, below the horizontal")),
        intensity=1e-9 * number(d, "intensity_nT", key, round(default.intensity * 1e9), 0.0,
                                1e6, unit="nT"))


#: m, the farthest a sensor may be mounted from the hull reference point, per axis (a GNSS
#: mounted 1e300 m away gave NaN fixes).
MAX_MOUNT = 1000.0


def sensors_block(raw: Any, key: str, physics_rate: float) -> tuple[SensorSpec, ...]:
    """A boat's ``sensors``: a list of ``{type, name, rate_hz, position, noise, ...}``.

    ``type``: imu, gnss, odometry (a noisy copy of ``odom``; no ``position``), magnetometer
    or depth_sounder.

    Names are unique on the boat (they name its topics and frames); rates are at most the
    physics rate (``simulation.rate_hz``), as a sensor reads the simulated motion.
    """
    if raw is None:
        return ()
    if not isinstance(raw, list):
        kinds = "|".join(SENSOR_TYPES)
        raise ScenarioError(key, raw, f"must be a list of sensors ({{type: {kinds}, ...}})")
    out: list[SensorSpec] = []
    for i, item in enumerate(raw):
        k = f"{key}[{i}]"
        d = mapping(item, k)
        only(d, k, ("type", "name", "rate_hz", "position", "noise", "dropout", "latency",
                    *_TYPE_KEYS))
        describe(f"{k}.type", None, f"one of: {', '.join(SENSOR_TYPES)}",
                 default_doc="required")
        describe(f"{k}.name", None, f"{ROS_NAME_RULE}; unique on the boat: its topics and "
                 "frame", default_doc="its type")
        kind = d.get("type")
        if kind not in SENSOR_TYPES:
            raise ScenarioError(f"{k}.type", kind, f"must be one of: {', '.join(SENSOR_TYPES)}")
        name = d.get("name", kind)
        if not is_ros_name(name):
            raise ScenarioError(f"{k}.name", name, f"must be {ROS_NAME_RULE}")
        if name in {s.name for s in out}:
            raise ScenarioError(f"{k}.name", name, "must be unique among the boat's sensors")
        out.append(_sensor(d, k, kind, name, physics_rate))
    return tuple(out)


#: s, the longest ``latency``.
MAX_LATENCY = 60.0
#: The keys of some types of sensor only: key -> those types.
_TYPE_KEYS = {"outages": ("gnss",), "drift": ("odometry",), "heading_baseline": ("gnss",),
              "field_of_view_deg": ("depth_sounder",),
              "min_range": ("depth_sounder", "lidar", "radar"),
              "max_range": ("depth_sounder", "lidar", "radar"), "samples": ("lidar",),
              "horizontal_fov_deg": ("lidar",), "rings": ("lidar",),
              "vertical_fov_deg": ("lidar",), "sea": ("lidar",),
              "clutter_probability": ("lidar",), "range": ("ais",), "rpm": ("radar",),
              "spokes": ("radar",), "beamwidth_deg": ("radar",),
              "range_resolution": ("radar",), "detection_range": ("radar",),
              "sea_clutter": ("radar",), "multipath": ("gnss",)}


def _sensor(d: Mapping[str, Any], k: str, kind: str, name: str,
            physics_rate: float) -> SensorSpec:
    """One sensor ``d`` (at ``k``) of type ``kind``, its name checked."""
    rate = number(d, "rate_hz", k, _RATES[kind], 0.0,
                  physics_rate, low_open=True, unit="Hz (at most simulation.rate_hz)",
                  default_doc=", ".join(f"{t} {r:g}" for t, r in _RATES.items()),
                  range_doc="(0, simulation.rate_hz] Hz")
    position = vector(d, "position", k, 3, [0.0, 0.0, 0.0], unit="m, body frame, from the "
                      "hull reference point (not for an odometry)", bound=MAX_MOUNT)
    describe(f"{k}.noise", None, "imu: gyroscope {...}, accelerometer {...}, "
             "orientation_sigma_deg; gnss: horizontal_sigma, vertical_sigma, bias_sigma, "
             "bias_correlation_time, velocity_sigma, heading_sigma_deg; odometry: "
             "position_sigma, orientation_sigma_deg, velocity_sigma, "
             "angular_velocity_sigma_deg; magnetometer: sigma, hard_iron, soft_iron; "
             "depth_sounder, lidar: range_sigma; ais: position_sigma; radar: none",
             default_doc="each key's default below")
    noise = mapping(d.get("noise"), f"{k}.noise")
    for only_key, only_types in _TYPE_KEYS.items():
        if kind not in only_types and only_key in d:
            raise ScenarioError(f"{k}.{only_key}", d[only_key],
                                f"only for a {' or '.join(only_types)}")
    dropout = number(d, "dropout", k, 0.0, 0.0, 1.0,
                     unit="(the probability that a reading is lost)")
    latency = number(d, "latency", k, 0.0, 0.0, MAX_LATENCY,
                     unit="s of simulation time from a reading (its stamp) to its publication")
    if kind == "imu":
        spec = _imu(name, rate, position, noise, f"{k}.noise")
    elif kind == "magnetometer":
        spec = _magnetometer(name, rate, position, noise, f"{k}.noise")
    elif kind == "depth_sounder":
        spec = _depth_sounder(name, rate, position, d, noise, k)
    elif kind == "lidar":
        spec = _lidar(name, rate, position, d, noise, k)
    elif kind == "radar":
        only(noise, f"{k}.noise", ())
        spec = _radar(name, rate, position, d, k)
    elif kind == "ais":
        only(noise, f"{k}.noise", ("position_sigma",))
        spec = AisSpec(name, rate, position,
                       number(d, "range", k, AisSpec().range, 0.0, 1e6, low_open=True,
                              unit="m (an ais receiver's: the farthest boat it hears)"),
                       number(noise, "position_sigma", f"{k}.noise", AisSpec().position_sigma,
                              0.0, 1e4, unit="m", default_doc="odometry 0.5, ais 5"))
    elif kind == "gnss":
        spec = GnssSpec(name, rate, position, _gnss_noise(noise, f"{k}.noise"),
                        _outages(d.get("outages"), f"{k}.outages"),
                        heading_baseline=_baseline(d, k),
                        multipath=_multipath(d.get("multipath"), f"{k}.multipath"))
    else:
        if "position" in d:
            raise ScenarioError(f"{k}.position", d["position"],
                                "not for an odometry (it is the hull reference point's)")
        spec = OdometrySpec(name, rate, _odometry_noise(noise, f"{k}.noise"),
                            drift=flag(d, "drift", k, False))
    return replace(spec, dropout=dropout, latency=latency)


def _depth_sounder(name: str, rate: float, position: np.ndarray, d: Mapping[str, Any],
                   noise: Mapping[str, Any], key: str) -> DepthSounderSpec:
    """A depth sounder: ``field_of_view_deg``, ``min_range``, ``max_range`` (deg, m, m).

    Its ``noise``: ``{range_sigma}`` (m).
    """
    default = DepthSounderSpec()
    only(noise, f"{key}.noise", ("range_sigma",))
    fov = number(d, "field_of_view_deg", key, round(math.degrees(default.field_of_view), 6),
                 0.0, 180.0, low_open=True, unit="deg, the beam's full cone (a depth_sounder's)")
    nearest, farthest = _ranges(d, key, default.min_range, default.max_range)
    sigma = number(noise, "range_sigma", f"{key}.noise", default.range_sigma, 0.0, 100.0,
                   unit="m")
    return DepthSounderSpec(name, rate, position, math.radians(fov), nearest, farthest, sigma)


def _ranges(d: Mapping[str, Any], key: str, nearest: float, farthest: float
            ) -> tuple[float, float]:
    """A depth sounder's, a lidar's or a radar's ``min_range`` and ``max_range`` (m)."""
    low = number(d, "min_range", key, nearest, 0.0, 1000.0,
                 unit="m (a depth_sounder reads -inf nearer; a lidar, no return; a radar, "
                 "no bin whose centre is nearer)",
                 default_doc="depth_sounder 0.5, lidar 0.3, radar 20")
    high = number(d, "max_range", key, farthest, 0.0, 12000.0, low_open=True,
                  unit="m (farther, or no echo: a depth_sounder reads +inf; a lidar, no "
                  "return; a radar, no bin whose centre is farther)",
                  default_doc="depth_sounder 200, lidar 100, radar 1852")
    if high <= low:
        raise ScenarioError(f"{key}.max_range", high, f"must be greater than min_range "
                                                      f"({low:g} m)")
    return low, high


#: The most rays a lidar casts a scan (rings x samples).
MAX_RAYS = 200_000


def _lidar(name: str, rate: float, position: np.ndarray, d: Mapping[str, Any],
           noise: Mapping[str, Any], key: str) -> LidarSpec:
    """A scanner (:class:`LidarSpec`): its rays, ranges and sea; ``noise: {range_sigma}`` (m).

    ``samples``, ``horizontal_fov_deg``, ``rings``, ``vertical_fov_deg``, ``min_range``,
    ``max_range``, ``sea``, ``clutter_probability``.
    """
    default = LidarSpec()
    only(noise, f"{key}.noise", ("range_sigma",))
    samples = integer(d, "samples", key, default.samples, 1, MAX_RAYS,
                      note="(a lidar's rays per ring)")
    rings = integer(d, "rings", key, default.rings, 1, 256,
                    note="(a lidar's: 1 a 2-D scanner, LaserScan; more a 3-D one, PointCloud2)")
    if samples * rings > MAX_RAYS:
        raise ScenarioError(f"{key}.samples", samples, f"samples x rings must be at most "
                            f"{MAX_RAYS} (rings: {rings})")
    horizontal = number(d, "horizontal_fov_deg", key, 360.0, 0.0, 360.0, low_open=True,
                        unit="deg (a lidar's, centred ahead)")
    vertical = number(d, "vertical_fov_deg", key, 30.0, 0.0, 180.0,
                      unit="deg (a lidar's rings' spread, centred on level; rings > 1)")
    nearest, farthest = _ranges(d, key, default.min_range, default.max_range)
    sea = choice(d, "sea", key, default.sea, SEA_RETURNS)
    clutter = number(d, "clutter_probability", key, default.clutter_probability, 0.0, 1.0,
                     unit="(a lidar's share of the sea's rays that return, with sea: clutter)")
    sigma = number(noise, "range_sigma", f"{key}.noise", default.range_sigma, 0.0, 100.0,
                   unit="m")
    return LidarSpec(name, rate, position, samples, math.radians(horizontal), rings,
                     math.radians(vertical) if rings > 1 else 0.0, nearest, farthest, sigma,
                     sea, clutter)


#: The most range bins a radar's spoke has (max_range / range_resolution).
MAX_BINS = 20_000


def _radar(name: str, rate: float, position: np.ndarray, d: Mapping[str, Any],
           key: str) -> RadarSpec:
    """A radar (:class:`RadarSpec`): its antenna, beam, range bins and sea clutter.

    ``rpm``, ``spokes``, ``beamwidth_deg``, ``range_resolution``, ``min_range``,
    ``max_range``, ``detection_range``, ``sea_clutter``; no ``noise``.
    """
    default = RadarSpec()
    rpm = number(d, "rpm", key, default.rpm, 0.0, 120.0, low_open=True,
                 unit="turns a minute (a radar antenna's)")
    spokes = integer(d, "spokes", key, default.spokes, 8, 16384,
                     note="(a radar's spokes a revolution)")
    width = number(d, "beamwidth_deg", key, round(math.degrees(default.beamwidth), 6), 0.0,
                   45.0, low_open=True, unit="deg (a radar's horizontal beam, -3 dB)")
    resolution = number(d, "range_resolution", key, default.range_resolution, 0.0, 1000.0,
                        low_open=True, unit="m (a radar's range bin)")
    nearest, farthest = _ranges(d, key, default.min_range, default.max_range)
    if farthest / resolution > MAX_BINS:
        raise ScenarioError(f"{key}.range_resolution", resolution, f"must be at least "
                            f"max_range / {MAX_BINS} ({farthest / MAX_BINS:g} m)")
    detection = number(d, "detection_range", key, default.detection_range, 0.0, 1e6,
                       low_open=True, unit="m (a radar's: where a target's echo falls to the "
                       "detection threshold)")
    clutter = number(d, "sea_clutter", key, default.sea_clutter, 0.0, 1000.0,
                     unit="(a radar's mean sea clutter power at 100 m in a sea of 1 m "
                     "significant height, relative to the detection threshold, for 12 m bins "
                     "and a 3.9 deg beam: it scales with the cell's area; 0: none)")
    return RadarSpec(name, rate, position, rpm, spokes, math.radians(width), resolution,
                     nearest, farthest, detection, clutter)


_TRIAD_KEYS = ("noise_density", "random_walk", "bias_instability", "bias_correlation_time")
#: A triad's turn-on errors and range (:class:`InertialNoise`), beside its noise.
_UNIT_KEYS = ("scale_factor", "misalignment_deg", "range")


def _imu(name: str, rate: float, position: np.ndarray, d: Mapping[str, Any],
         key: str) -> ImuSpec:
    """An IMU: ``noise: {gyroscope: {...}, accelerometer: {...}, orientation_sigma_deg}``."""
    only(d, key, ("gyroscope", "accelerometer", "orientation_sigma_deg"))
    sigma = number(d, "orientation_sigma_deg", key, 0.1, 0.0, 10.0, unit="deg")
    return ImuSpec(name, rate, position,
                   _triad(d.get("gyroscope"), f"{key}.gyroscope", GYROSCOPE, "rad/s"),
                   _triad(d.get("accelerometer"), f"{key}.accelerometer", ACCELEROMETER,
                          "m/s^2"),
                   math.radians(sigma))


def _triad(raw: Any, key: str, default: InertialNoise, unit: str) -> InertialNoise:
    """One triad's noise; ``unit`` is its measurement's (rad/s or m/s^2)."""
    d = mapping(raw, key)
    only(d, key, _TRIAD_KEYS + _UNIT_KEYS)
    units = (f"{unit}/sqrt(Hz)", f"{unit}/s/sqrt(Hz)", unit, "s")
    values = [number(d, k, key, getattr(default, k), 0.0,
                     1e7 if k == "bias_correlation_time" else 1e3, unit=u)
              for k, u in zip(_TRIAD_KEYS, units, strict=True)]
    if values[3] == 0.0 and values[2] > 0.0:
        raise ScenarioError(f"{key}.bias_correlation_time", 0.0,
                            "must be > 0 s when bias_instability > 0")
    scale = number(d, "scale_factor", key, default.scale_factor, 0.0, 0.5)
    misalignment = number(d, "misalignment_deg", key, math.degrees(default.misalignment), 0.0,
                          10.0, unit="deg")
    largest = number(d, "range", key, default.range, 0.0, math.inf, low_open=True, unit=unit,
                     allow_inf=True)
    return InertialNoise(*values, scale, math.radians(misalignment), largest)


#: T, the largest magnetometer noise sigma and hard-iron component (the Earth's field is
#: 25-65 uT; a hull's own field near its engine a few hundred uT).
MAX_MAGNETIC = 1e-3
#: The largest soft-iron matrix entry in magnitude.
MAX_SOFT_IRON = 10.0


def _magnetometer(name: str, rate: float, position: np.ndarray, d: Mapping[str, Any],
                  key: str) -> MagnetometerSpec:
    """A magnetometer: ``noise: {sigma, hard_iron, soft_iron}`` (T, T, a 3 x 3 matrix)."""
    only(d, key, ("sigma", "hard_iron", "soft_iron"))
    default = MagnetometerSpec()
    sigma = number(d, "sigma", key, default.sigma, 0.0, MAX_MAGNETIC, unit="T")
    hard = vector(d, "hard_iron", key, 3, [0.0, 0.0, 0.0], bound=MAX_MAGNETIC,
                  unit="T, sensor frame, added to every reading")
    soft = _soft_iron(d.get("soft_iron"), f"{key}.soft_iron")
    return MagnetometerSpec(name, rate, position, sigma, hard, soft)


def _soft_iron(raw: Any, key: str) -> np.ndarray:
    """(3, 3) a soft-iron matrix: 3 rows of 3 finite numbers, invertible (None: identity)."""
    allowed = (f"3 rows of 3 numbers within +-{MAX_SOFT_IRON:g}, invertible (a determinant "
               "of at least 1e-6 in magnitude): the field in the sensor's axes is multiplied "
               "by it")
    describe(key, None, allowed, default_doc="the identity")
    if raw is None:
        return np.eye(3)
    ok = (isinstance(raw, list) and len(raw) == 3
          and all(isinstance(row, list) and len(row) == 3 for row in raw)
          and all(isinstance(x, int | float) and not isinstance(x, bool)
                  for row in raw for x in row))
    if not ok:
        raise ScenarioError(key, raw, f"must be {allowed}")
    m = np.array(raw, dtype=float)
    if not np.all(np.isfinite(m)) or np.abs(m).max() > MAX_SOFT_IRON:
        raise ScenarioError(key, raw, f"every entry must be finite and within "
                            f"+-{MAX_SOFT_IRON:g}")
    if abs(np.linalg.det(m)) < 1e-6:
        raise ScenarioError(key, raw, "must be invertible (a determinant of at least 1e-6 "
                            "in magnitude)")
    return m


def _odometry_noise(d: Mapping[str, Any], key: str) -> OdometryNoise:
    only(d, key, ("position_sigma", "orientation_sigma_deg", "velocity_sigma",
                  "angular_velocity_sigma_deg"))
    default = OdometryNoise()
    return OdometryNoise(
        number(d, "position_sigma", key, default.position_sigma, 0.0, 1e4, unit="m",
               default_doc="odometry 0.5, ais 5"),
        math.radians(number(d, "orientation_sigma_deg", key,
                            math.degrees(default.orientation_sigma), 0.0, 90.0, unit="deg")),
        number(d, "velocity_sigma", key, default.velocity_sigma, 0.0, 100.0, unit="m/s"),
        math.radians(number(d, "angular_velocity_sigma_deg", key,
                            math.degrees(default.angular_velocity_sigma), 0.0, 1000.0,
                            unit="deg/s")))


def _outages(raw: Any, key: str) -> tuple[tuple[float, float], ...]:
    """A receiver's outages: a list of [start, end] s of simulation time, 0 <= start < end."""
    allowed = "a list of [start, end] s of simulation time, 0 <= start < end (end may be .inf)"
    describe(key, [], f"gnss: {allowed}, without a fix", default_doc="none")
    if raw is None:
        return ()
    if not isinstance(raw, list):
        raise ScenarioError(key, raw, f"must be {allowed}")
    out = []
    for i, pair in enumerate(raw):
        ok = (isinstance(pair, list) and len(pair) == 2
              and all(isinstance(x, int | float) and not isinstance(x, bool) for x in pair)
              and 0.0 <= pair[0] < pair[1] and math.isfinite(pair[0]))
        if not ok:
            raise ScenarioError(f"{key}[{i}]", pair, "must be [start, end] s with 0 <= start "
                                "< end (end may be .inf)")
        out.append((float(pair[0]), float(pair[1])))
    return tuple(out)


def _multipath(raw: Any, key: str) -> Multipath | None:
    """A receiver's multipath jumps: ``{rate_hz, sigma, duration}`` (Hz, m, s), or None."""
    describe(key, None, "gnss: {rate_hz, sigma, duration}: horizontal jumps of the fix",
             default_doc="none: no jumps")
    if raw is None:
        return None
    d = mapping(raw, key)
    only(d, key, ("rate_hz", "sigma", "duration"))
    default = Multipath()
    return Multipath(
        number(d, "rate_hz", key, default.rate_hz, 0.0, 100.0,
               unit="Hz (jumps a second while none is under way)"),
        number(d, "sigma", key, default.sigma, 0.0, 1e4,
               unit="m (a jump's east and north offsets, 1 sigma)"),
        number(d, "duration", key, default.duration, 0.0, 1e6, low_open=True,
               unit="s (a jump's mean duration, exponentially distributed)"))


def _baseline(d: Mapping[str, Any], key: str) -> np.ndarray | None:
    """A receiver's ``heading_baseline`` (m, body frame, to its second antenna), or None."""
    if d.get("heading_baseline") is None:
        return None
    b = vector(d, "heading_baseline", key, 3, [0.0, 0.0, 0.0], bound=MAX_MOUNT,
               default_doc="none: no heading", unit="m, body frame, from the antenna to a "
               "second one, at least 0.1 m horizontally (a gnss's: <name>/heading)")
    if math.hypot(b[0], b[1]) < 0.1:
        raise ScenarioError(f"{key}.heading_baseline", d["heading_baseline"],
                            "must reach at least 0.1 m horizontally (x, y) from the antenna")
    return b


def _gnss_noise(d: Mapping[str, Any], key: str) -> GnssNoise:
    fields = ("horizontal_sigma", "vertical_sigma", "bias_sigma", "bias_correlation_time",
              "velocity_sigma")
    only(d, key, (*fields, "heading_sigma_deg"))
    default = GnssNoise()
    values = {f: number(d, f, key, getattr(default, f), 0.0,
                        1e7 if f == "bias_correlation_time" else 1e4,
                        unit="s" if f == "bias_correlation_time" else
                        ("m/s" if f == "velocity_sigma" else "m"))
              for f in fields}
    if values["bias_correlation_time"] == 0.0 and values["bias_sigma"] > 0.0:
        raise ScenarioError(f"{key}.bias_correlation_time", 0.0,
                            "must be > 0 s when bias_sigma > 0")
    heading = number(d, "heading_sigma_deg", key, math.degrees(GnssNoise.heading_sigma), 0.0,
                     90.0, unit="deg (a heading_baseline's)")
    return GnssNoise(**values, heading_sigma=math.radians(heading))
