"""A scanning range sensor: a 2-D laser scanner (one ring) or a 3-D lidar (several rings).

Its rays leave the sensor's origin (``position``, body frame) in its own frame (the body's
axes, FLU), at ``rings`` elevations evenly over ``vertical_fov`` (one ring: level) and
``samples`` azimuths evenly over ``horizontal_fov`` centred on its x axis, counter-clockwise
(as sensor_msgs/LaserScan's angle_min .. angle_max): they turn with the boat's roll, pitch
and heading. Each reads the range to the nearest obstacle or other hull
(:func:`boat_dynamics.physics.world.rays.cast`) or the sea surface
(:func:`~boat_dynamics.physics.world.rays.water_range`), with white Gaussian noise of
``range_sigma``; beyond ``max_range`` or nearer than ``min_range``, nothing (inf). The sea:
``sea: none`` stops a ray without a return (the water absorbs it: nothing behind it is
seen); ``sea: clutter`` returns it with probability ``clutter_probability`` per ray (spray
and wave crests, drawn from the seed; 0.05 by default). Costs: docs/DESIGN.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from boat_dynamics.physics.sensors.noise import standard_normal
from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import World
from boat_dynamics.physics.world.rays import cast, water_range

__all__ = ["CLUTTER_SAMPLES", "SEA_RETURNS", "LidarSpec", "SeaReturn", "lidar_directions",
           "measure_lidar"]

#: Where a scanner's clutter draws start (counter CLUTTER_SAMPLES + scan): apart from its
#: range noise and its dropouts (:mod:`.noise`).
CLUTTER_SAMPLES = 2**60

#: What a ray that reaches the sea returns.
SeaReturn = Literal["none", "clutter"]
SEA_RETURNS: tuple[SeaReturn, ...] = ("none", "clutter")


@dataclass(frozen=True)
class LidarSpec:
    """A scanner on a boat.

    Attributes:
        name: its name (topic ``<ns>/<name>/scan`` or ``/points``, frame ``<ns>/<name>_link``).
        rate_hz: scans a second.
        position: (3,) m, body frame, from the hull reference point.
        samples: azimuths per ring.
        horizontal_fov: rad, centred on the sensor's x axis.
        rings: elevations (1: a 2-D scanner, level).
        vertical_fov: rad, the rings' spread, centred on level.
        min_range: m.
        max_range: m.
        range_sigma: m, white noise on each range.
        sea: what the sea returns.
        clutter_probability: the share of the sea's rays that return (``sea: clutter``).
        dropout: the probability that a scan is lost.
        latency: s from a scan to its publication.
    """

    name: str = "lidar"
    rate_hz: float = 10.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    samples: int = 360
    horizontal_fov: float = 2.0 * math.pi
    rings: int = 1
    vertical_fov: float = 0.0
    min_range: float = 0.3
    max_range: float = 100.0
    range_sigma: float = 0.02
    sea: SeaReturn = "none"
    clutter_probability: float = 0.05
    dropout: float = 0.0
    latency: float = 0.0

    @property
    def azimuths(self) -> np.ndarray:
        """(samples,) rad, counter-clockwise from the sensor's x axis (a full circle: no repeat)."""
        full = math.isclose(self.horizontal_fov, 2.0 * math.pi)
        step = self.horizontal_fov / (self.samples if full else max(self.samples - 1, 1))
        return -0.5 * self.horizontal_fov + step * np.arange(self.samples)

    @property
    def elevations(self) -> np.ndarray:
        """(rings,) rad, up from level."""
        if self.rings == 1:
            return np.zeros(1)
        return np.linspace(-0.5 * self.vertical_fov, 0.5 * self.vertical_fov, self.rings)


def lidar_directions(spec: LidarSpec) -> np.ndarray:
    """(rings * samples, 3) unit ray directions in the sensor's frame, ring after ring."""
    el, az = np.meshgrid(spec.elevations, spec.azimuths, indexing="ij")
    return np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)],
                    axis=-1).reshape(-1, 3)


def measure_lidar(spec: LidarSpec, key: np.ndarray, sample: int, rotation: np.ndarray,
                  reference: np.ndarray, world: World,
                  hulls: tuple[Footprints, np.ndarray, np.ndarray] | None,
                  heights: Callable[[np.ndarray], np.ndarray], own: int = -1) -> np.ndarray:
    """Scan number ``sample``: (rings * samples,) m ranges, ring after ring (inf: none).

    Args:
        spec: the scanner.
        key: its noise stream.
        sample: the scan's index (its draws).
        rotation: (3, 3) its boat's body-to-world rotation.
        reference: (3,) m, its boat's reference point, world frame.
        world: the obstacles.
        hulls: the boats (footprints, (B, 3, 3) rotations, (B, 3) reference points).
        heights: (N, 2) m world x, y -> (N,) m, the sea surface's height there.
        own: the scanner's boat among ``hulls`` (not seen), or -1.
    """
    d = lidar_directions(spec) @ rotation.T
    o = np.broadcast_to(reference + rotation @ spec.position, d.shape)
    solid = cast(world, o, d, spec.max_range, hulls, own)
    water = water_range(o, d, heights)
    ranges = solid.copy()
    sea = water < solid
    ranges[sea] = np.inf
    if spec.sea == "clutter":
        counter = np.array([0, CLUTTER_SAMPLES + sample, 0, 0], dtype=np.uint64)
        draws = np.random.Generator(np.random.Philox(key=key, counter=counter)).random(
            d.shape[0])
        back = draws < spec.clutter_probability
        ranges[sea & back] = water[sea & back]
    ranges = ranges + spec.range_sigma * standard_normal(key, sample, d.shape[0])
    return np.where((ranges >= spec.min_range) & (ranges <= spec.max_range), ranges, np.inf)
