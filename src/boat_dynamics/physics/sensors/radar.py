"""A marine radar: a rotating X-band fan beam, its echoes binned in range, and sea clutter.

The antenna at ``position`` (body frame) turns clockwise seen from above at ``rpm``, with the
boat's heading; a revolution is ``spokes`` spokes, spoke s at -2 pi (s mod spokes) / spokes
rad from the bow (counter-clockwise positive, FLU). Its fan beam (a small radome's: 3.9 deg
horizontal, about 25 deg vertical, e.g. Furuno 1815 / DRS4D-NXT, Simrad Halo20) is treated
as level whatever the roll and pitch: that vertical spread keeps the horizon in the beam for
rolls within about +-12 deg, so this model neither blanks nor tilts it (a beam that loses
the horizon in heavier roll is not modelled). The horizontal beam is cast as one level ray
per spoke azimuth at :data:`BEAM_HEIGHT` above the mean sea level (the fan reaches from the
antenna down to the water beyond a few metres, so anything that stands out of the water is
in it) into the obstacles and the other hulls (:func:`~boat_dynamics.physics.world.rays.
cast`); the sea does not stop it.

Echoes (power relative to the detection threshold, linear): a ray that hits at range R is a
scatterer of echo (R_d / R)^4 (the radar equation for a fixed radar cross-section; Skolnik,
"Introduction to Radar Systems", 3rd ed. 2001, eq. 1.7), ``detection_range`` R_d being where
a nominal target's echo falls to the threshold. A spoke sees the scatterers within
+-``beamwidth`` / 2 of its azimuth, weighted by the two-way Gaussian beam pattern
exp(-8 ln 2 (theta / beamwidth)^2) (so a target is drawn about one beamwidth wide, as on a
display), each in its range bin floor(R / ``range_resolution``): a bin holds its strongest.

Sea clutter: each bin of each spoke adds an exponentially distributed power (Rayleigh
amplitude, the classical model; Ward, Tough and Watts, "Sea Clutter", 2nd ed. 2013, ch. 2)
of mean c(R) = ``sea_clutter`` (H_s / 1 m) (A / A_0) (100 m / R)^3 min(1, R_c / R)^4: the
clutter cell's area A = R ``beamwidth`` ``range_resolution`` (A_0 the defaults' at 100 m: 3.9
deg, 12 m) grows as R while the echo falls as R^-4 (power as R^-3) inside the critical range
R_c = 4 pi h (H_s / 4) / lambda, and the reflectivity falls as the grazing angle^4 beyond it
(power as R^-7; Skolnik 2001, sec. 7.5; Skolnik, "Radar Handbook", 3rd ed. 2008, ch. 15),
with h the antenna's height above the mean sea, H_s the sea's significant height
(:func:`significant_height`), lambda 3.2 cm (X band); the reflectivity taken proportional to
H_s (about 5 dB a sea state at X band and low grazing, Radar Handbook ch. 15). A bin is a
detection when its power (echo plus clutter) reaches 1: clutter gives false detections near
the boat, with probability exp(-1 / c(R)) a bin, and fewer far off. The draws are addressed by
revolution and spoke (:mod:`.noise`): the same seed gives the same clutter whatever the
publication rate. Costs: docs/autonomy.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import World
from boat_dynamics.physics.world.rays import cast

__all__ = ["BEAM_HEIGHT", "WAVELENGTH", "RadarScan", "RadarSpec", "clutter_mean",
           "measure_radar", "radar_points", "significant_height", "spoke_azimuths",
           "spokes_due"]

#: m above the mean sea level, the height the beam's rays are cast at.
BEAM_HEIGHT = 0.1
#: m, an X-band radar's wavelength (9.4 GHz).
WAVELENGTH = 0.032
#: m, the range and significant height the clutter level ``sea_clutter`` is given at.
CLUTTER_RANGE = 100.0
CLUTTER_HEIGHT = 1.0
#: m, rad: the range bin and beamwidth (the clutter cell) ``sea_clutter`` is given for.
CLUTTER_BIN = 12.0
CLUTTER_BEAM = math.radians(3.9)


@dataclass(frozen=True)
class RadarSpec:
    """A radar on a boat.

    Attributes:
        name: its name (topic ``<ns>/<name>/points``, frame ``<ns>/<name>_link``).
        rate_hz: messages a second, each the spokes swept since the last.
        position: (3,) m, body frame, the antenna's from the hull reference point.
        rpm: the antenna's turns a minute.
        spokes: spokes a revolution.
        beamwidth: rad, the horizontal beam's -3 dB (one-way) width.
        range_resolution: m, a range bin's length.
        min_range: m: bins whose centre is nearer are not reported.
        max_range: m: bins whose centre is farther are not reported.
        detection_range: m, where a target's echo falls to the detection threshold.
        sea_clutter: the mean clutter power at 100 m in a sea of 1 m significant height,
            relative to the threshold, for a 12 m bin and a 3.9 deg beam (it scales with
            the cell's area; 0: none).
        dropout: the probability that a message is lost.
        latency: s from a message's spokes to its publication.
    """

    name: str = "radar"
    rate_hz: float = 10.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rpm: float = 24.0
    spokes: int = 2048
    beamwidth: float = math.radians(3.9)
    range_resolution: float = 12.0
    min_range: float = 20.0
    max_range: float = 1852.0
    detection_range: float = 3704.0
    sea_clutter: float = 0.3
    dropout: float = 0.0
    latency: float = 0.0

    @property
    def bins(self) -> int:
        """Range bins a spoke (the last one's centre within ``max_range``)."""
        return max(1, math.floor(self.max_range / self.range_resolution + 0.5))

    @property
    def spoke_rate(self) -> float:
        """Spokes a second."""
        return self.spokes * self.rpm / 60.0


@dataclass(frozen=True)
class RadarScan:
    """The detections of some spokes: P points.

    Attributes:
        azimuth: (P,) rad from the bow, counter-clockwise, level.
        range: (P,) m, their bins' centres.
        intensity: (P,) their power relative to the detection threshold (>= 1).
    """

    azimuth: np.ndarray
    range: np.ndarray
    intensity: np.ndarray


def significant_height(amplitudes: np.ndarray) -> float:
    """H_s = 4 sqrt(m0) m of Gerstner components of ``amplitudes`` (m): m0 = sum a^2 / 2."""
    return 4.0 * math.sqrt(0.5 * float(np.sum(np.square(amplitudes))))


def spokes_due(spec: RadarSpec, next_spoke: int, t: float) -> tuple[int, int]:
    """(first, count): the spokes swept by time ``t`` (s) from spoke ``next_spoke`` on."""
    end = math.floor(t * spec.spoke_rate + 1e-6) + 1  # spoke s is swept at s / spoke_rate s
    return next_spoke, max(0, end - next_spoke)


def spoke_azimuths(spec: RadarSpec, spokes: np.ndarray) -> np.ndarray:
    """(n,) rad from the bow, counter-clockwise, in [-pi, pi), of global spoke ``spokes``."""
    a = -2.0 * math.pi * np.remainder(spokes, spec.spokes) / spec.spokes
    return np.remainder(a + math.pi, 2.0 * math.pi) - math.pi


def clutter_mean(spec: RadarSpec, ranges: np.ndarray, height: float,
                 antenna_height: float) -> np.ndarray:
    """(n,) the mean clutter power at ``ranges`` (m), relative to the threshold.

    Args:
        spec: the radar (``sea_clutter``, its cell: ``range_resolution``, ``beamwidth``).
        ranges: (n,) m, > 0.
        height: m, the sea's significant height.
        antenna_height: m above the mean sea (at least 0.1 m is used).
    """
    if spec.sea_clutter <= 0.0 or height <= 0.0:
        return np.zeros(len(ranges))
    critical = 4.0 * math.pi * max(antenna_height, 0.1) * 0.25 * height / WAVELENGTH
    cell = spec.range_resolution / CLUTTER_BIN * spec.beamwidth / CLUTTER_BEAM
    return (spec.sea_clutter * height / CLUTTER_HEIGHT * cell * (CLUTTER_RANGE / ranges) ** 3
            * np.minimum(1.0, critical / ranges) ** 4)


def measure_radar(spec: RadarSpec, key: np.ndarray, first: int, count: int,
                  rotation: np.ndarray, reference: np.ndarray, world: World,
                  hulls: tuple[Footprints, np.ndarray, np.ndarray] | None, height: float,
                  own: int = -1) -> RadarScan:
    """The detections of ``count`` spokes from global spoke ``first`` (0: the bow at t = 0).

    Args:
        spec: the radar.
        key: its noise stream (:func:`.noise.stream_key`).
        first: the first spoke's index (spoke s is swept at s / ``spec.spoke_rate`` s).
        count: spokes.
        rotation: (3, 3) its boat's body-to-world rotation (its heading turns the spokes).
        reference: (3,) m, its boat's reference point, world frame.
        world: the obstacles.
        hulls: the boats (footprints, (B, 3, 3) rotations, (B, 3) reference points).
        height: m, the sea's significant height (0: flat, no clutter).
        own: the radar's boat among ``hulls`` (not seen), or -1.
    """
    if count <= 0:
        return RadarScan(np.zeros(0), np.zeros(0), np.zeros(0))
    spokes = first + np.arange(count)
    antenna = reference + rotation @ spec.position
    power = _echoes(spec, spokes, rotation, antenna, world, hulls, own)
    centres = (np.arange(spec.bins) + 0.5) * spec.range_resolution
    mean = clutter_mean(spec, centres, height, float(antenna[2]))
    if np.any(mean > 0.0):
        power = power - mean[None] * np.log1p(-_uniforms(spec, key, spokes))  # exponential
    seen = (power >= 1.0) & (centres >= spec.min_range)[None]
    s, b = np.nonzero(seen)
    return RadarScan(spoke_azimuths(spec, spokes)[s], centres[b], power[s, b])


def _echoes(spec: RadarSpec, spokes: np.ndarray, rotation: np.ndarray, antenna: np.ndarray,
            world: World, hulls: tuple[Footprints, np.ndarray, np.ndarray] | None,
            own: int) -> np.ndarray:
    """(n, bins) the targets' echo power in each spoke's bins, relative to the threshold."""
    step = 2.0 * math.pi / spec.spokes
    m = math.floor(0.5 * spec.beamwidth / step)  # rays either side within the beam
    rays = np.arange(spokes[0] - m, spokes[0] + len(spokes) + m)
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    a = yaw + spoke_azimuths(spec, rays)
    d = np.column_stack([np.cos(a), np.sin(a), np.zeros(len(a))])
    o = np.broadcast_to([antenna[0], antenna[1], BEAM_HEIGHT], d.shape)
    r = cast(world, o, d, spec.max_range, hulls, own)
    offsets = np.arange(-m, m + 1)
    gain = np.exp(-8.0 * math.log(2.0) * (offsets * step / spec.beamwidth) ** 2)
    rows = np.broadcast_to(np.arange(len(spokes))[:, None], (len(spokes), 2 * m + 1))
    rr = r[rows + m + offsets[None]]
    cells = np.floor(rr / spec.range_resolution)
    ok = np.isfinite(rr) & (cells < spec.bins)
    out = np.zeros((len(spokes), spec.bins))
    np.maximum.at(out, (rows[ok], cells[ok].astype(int)),
                  (gain[None] * (spec.detection_range / np.where(ok, rr, 1.0)) ** 4)[ok])
    return out


def _uniforms(spec: RadarSpec, key: np.ndarray, spokes: np.ndarray) -> np.ndarray:
    """(n, bins) uniform [0, 1) draws of consecutive spokes, addressed by spoke.

    Spoke s of revolution q = s // spokes: Philox counter ((s mod spokes) w / 4, q, 0, 0), w
    the bins rounded up to a multiple of 4 (a counter gives 4 draws): consecutive spokes of a
    revolution are one stream, drawn at once.
    """
    width = 4 * math.ceil(spec.bins / 4)
    out = np.empty((len(spokes), width))
    k = 0
    while k < len(spokes):
        q, s = divmod(int(spokes[k]), spec.spokes)
        n = min(len(spokes) - k, spec.spokes - s)  # to the revolution's end
        counter = np.array([s * width // 4, q, 0, 0], dtype=np.uint64)
        g = np.random.Generator(np.random.Philox(key=key, counter=counter))
        out[k:k + n] = g.random(n * width).reshape(n, width)
        k += n
    return out[:, :spec.bins]


def radar_points(scan: RadarScan, rotation: np.ndarray) -> np.ndarray:
    """(P, 3) m, the detections in the sensor's frame (the body's axes, FLU).

    Level in the world at the boat's heading, turned into the body's axes (R^T R_yaw): the
    frame's transform on /tf puts them back level.

    Args:
        scan: the detections.
        rotation: (3, 3) the boat's body-to-world rotation.
    """
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    a = yaw + scan.azimuth
    world = np.column_stack([np.cos(a), np.sin(a), np.zeros(len(a))]) * scan.range[:, None]
    return world @ rotation  # rows: R^T p
