"""Each hull as contact sees it: a convex prism in its own body frame, and points round it.

Contact (:mod:`boat_dynamics.physics.force_models.collision`) takes a hull as the convex
hull of its vertices seen from above in its body frame (Andrew's monotone chain), between
its lowest and highest vertex: a box is itself; a ship-shaped hull is filled out to its
widest waterline. What touches an obstacle or another hull are points round that prism's
sides, at most :data:`SPACING` apart, at its bottom, middle and top: a hull's own
vertices can be metres apart (a box has 8), and a piling or another bow would pass between
them. Which pairs of boats can touch is found by sorting them along x (sweep and prune),
each within its footprint's circle about its reference point.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["SPACING", "Footprints", "convex_hull", "near_pairs", "perimeter_points"]

#: m: the most the contact points round a hull are apart.
SPACING = 0.25
#: Fleets up to this size check every pair at once; larger ones sweep along x.
_BRUTE_FORCE = 48


@dataclass(frozen=True)
class Footprints:
    """The boats' hulls as convex prisms, body frames.

    Attributes:
        corners: per boat, (P, 2) m, its footprint's corners counter-clockwise, body x, y
            from the hull reference point.
        normals: per boat, (P, 2) the unit outward normals of its edges (corner k to k + 1).
        z: (B, 2) m, body z of its lowest and highest vertex.
        radius: (B,) m, its farthest corner from the reference point (plan view).
        points: (E, 3) m, every boat's contact points (:func:`perimeter_points`), body
            frames, boat after boat.
        owner: (E,) int, the boat of each point.
        starts: (B + 1,) int, boat b's points are rows starts[b] to starts[b + 1].
    """

    corners: tuple[np.ndarray, ...]
    normals: tuple[np.ndarray, ...]
    z: np.ndarray
    radius: np.ndarray
    points: np.ndarray
    owner: np.ndarray
    starts: np.ndarray

    @classmethod
    def build(cls, vertices: Sequence[np.ndarray]) -> Footprints:
        """From each hull's (V, 3) m body-frame vertices (boats sharing an array share a hull)."""
        hulls: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        for v in vertices:
            if id(v) not in hulls:
                c = convex_hull(v[:, :2])
                e = np.roll(c, -1, axis=0) - c
                hulls[id(v)] = (c, np.stack([e[:, 1], -e[:, 0]], axis=1)
                                / np.hypot(e[:, 0], e[:, 1])[:, None])
        corners = tuple(hulls[id(v)][0] for v in vertices)
        normals = tuple(hulls[id(v)][1] for v in vertices)
        z = np.array([[v[:, 2].min(), v[:, 2].max()] for v in vertices])
        points = [perimeter_points(c, lo, hi) for c, (lo, hi) in zip(corners, z, strict=True)]
        counts = np.array([p.shape[0] for p in points])
        return cls(corners, normals, z,
                   np.array([np.hypot(c[:, 0], c[:, 1]).max() for c in corners]),
                   np.concatenate(points), np.repeat(np.arange(len(points)), counts),
                   np.concatenate([[0], np.cumsum(counts)]))


def perimeter_points(corners: np.ndarray, low: float, high: float,
                     spacing: float = SPACING) -> np.ndarray:
    """(n, 3) m: points round a prism's sides at most ``spacing`` apart, at 3 heights.

    Args:
        corners: (P, 2) m, its footprint's corners.
        low: m, its bottom's z.
        high: m, its top's z.
        spacing: m, > 0.
    """
    a = corners
    e = np.roll(a, -1, axis=0) - a
    pieces = np.maximum(1, np.ceil(np.hypot(e[:, 0], e[:, 1]) / spacing).astype(int))
    ring = np.concatenate([a[k] + np.outer(np.arange(n) / n, e[k])
                           for k, n in enumerate(pieces)])
    heights = np.array([low, 0.5 * (low + high), high])
    return np.concatenate([np.column_stack([ring, np.full(ring.shape[0], h)])
                           for h in heights])


def convex_hull(points: np.ndarray) -> np.ndarray:
    """(P, 2) the convex hull of (N, 2) points, counter-clockwise, no collinear corners.

    Andrew's monotone chain (A. M. Andrew, Inf. Process. Lett. 9 (1979) 216-219).
    """
    pts = sorted(set(map(tuple, np.round(np.asarray(points, dtype=float), 12).tolist())))
    if len(pts) < 3:
        raise ValueError(f"points: {len(pts)} distinct, a hull needs 3 not on one line")

    def turn(o, a, b) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    upper: list = []
    for p in pts:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    hull = np.array(lower[:-1] + upper[:-1])
    if hull.shape[0] < 3:
        raise ValueError("points: all on one line, no hull")
    return hull


def near_pairs(xy: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """(K, 2) int, i < j: the boats whose footprints' circles overlap.

    Args:
        xy: (B, 2) m, the reference points, world frame.
        radius: (B,) m, each footprint's circle.
    """
    if xy.shape[0] <= _BRUTE_FORCE:  # every pair at once: fewer numpy calls
        d = xy[:, None, :] - xy[None, :, :]
        reach = radius[:, None] + radius[None, :]
        i, j = np.nonzero(np.triu(d[..., 0] ** 2 + d[..., 1] ** 2 <= reach * reach, k=1))
        return np.stack([i, j], axis=1)
    order = np.argsort(xy[:, 0], kind="stable")
    x = xy[order, 0]
    reach = x + radius[order] + radius.max()
    end = np.searchsorted(x, reach, side="right")  # candidates k < end along x
    count = end - np.arange(x.shape[0]) - 1
    if not np.any(count > 0):
        return np.zeros((0, 2), dtype=np.intp)
    first = np.repeat(np.arange(x.shape[0]), count)
    second = first + 1 + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))
    a, b = order[first], order[second]
    gap = np.hypot(*(xy[a] - xy[b]).T)
    keep = gap <= radius[a] + radius[b]
    return np.sort(np.stack([a[keep], b[keep]], axis=1), axis=1)
