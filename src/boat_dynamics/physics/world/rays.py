"""Rays cast into the world: the ranges a lidar or a laser scanner reads.

A ray from ``origin`` along the unit ``direction`` (world frame) stops at the first of:
an obstacle's walls or top (:mod:`.obstacles`: a prism's sides are vertical rectangles from
the sea floor to its top, its top the polygon at that height; a cylinder's side and top),
another boat's hull (its convex prism, :mod:`.footprints`, at its pose: the Cyrus-Beck
clip of a ray by a convex polyhedron's faces, Cyrus and Beck, Computers & Graphics 3 (1978)
23-28), or the sea surface (:func:`water_range`). Pure numpy over all rays at once.
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import Cylinder, Prism, World, inside_polygon

__all__ = ["cast", "hull_ranges", "obstacle_ranges", "water_range"]


def cast(world: World, origins: np.ndarray, directions: np.ndarray, max_range: float,
         hulls: tuple[Footprints, np.ndarray, np.ndarray] | None = None, skip: int = -1
         ) -> np.ndarray:
    """(R,) m: how far each ray goes before it hits an obstacle or a hull (inf: nothing).

    Args:
        world: the obstacles.
        origins: (R, 3) m, world frame.
        directions: (R, 3) unit vectors, world frame.
        max_range: m: hits beyond are not hits.
        hulls: (footprints, (B, 3, 3) body-to-world rotations, (B, 3) m reference points) of
            the boats the rays may hit, or None.
        skip: the boat of ``hulls`` the rays leave from (not hit), or -1.
    """
    best = obstacle_ranges(world, origins, directions)
    if hulls is not None:
        best = np.minimum(best, hull_ranges(*hulls, origins, directions, skip))
    return np.where(best <= max_range, best, np.inf)


def obstacle_ranges(world: World, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """(R,) m, the nearest obstacle along each ray (inf: none)."""
    best = np.full(origins.shape[0], np.inf)
    for o in world.obstacles:
        hit = (_prism(o, origins, directions) if isinstance(o, Prism)
               else _cylinder(o, origins, directions))
        best = np.minimum(best, hit)
    return best


def _prism(prism: Prism, o: np.ndarray, d: np.ndarray) -> np.ndarray:
    """(R,) m to the prism's walls (below its top) or its top face."""
    a, e, _ = prism.edges
    # o + t d = a + s e in x, y: solve [d_xy, -e] [t, s]^T = a - o_xy per ray and edge
    det = d[:, None, 0] * -e[None, :, 1] + d[:, None, 1] * e[None, :, 0]
    rel = a[None] - o[:, None, :2]  # (R, P, 2)
    with np.errstate(all="ignore"):  # parallel edges: inf and nan, masked below
        t = (rel[..., 0] * -e[None, :, 1] + rel[..., 1] * e[None, :, 0]) / det
        s = (d[:, None, 0] * rel[..., 1] - d[:, None, 1] * rel[..., 0]) / det
        z = o[:, None, 2] + t * d[:, None, 2]
    wall = np.where((t > 0.0) & (s >= 0.0) & (s <= 1.0) & (z <= prism.top) & (det != 0.0),
                    t, np.inf).min(axis=1)
    return np.minimum(wall, _top(prism.top, o, d, lambda xy: inside_polygon(prism.points, xy)))


def _cylinder(cylinder: Cylinder, o: np.ndarray, d: np.ndarray) -> np.ndarray:
    """(R,) m to the cylinder's side (below its top) or its top disc."""
    rel = o[:, :2] - cylinder.center
    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b = rel[:, 0] * d[:, 0] + rel[:, 1] * d[:, 1]
    c = rel[:, 0] ** 2 + rel[:, 1] ** 2 - cylinder.radius ** 2
    disc = b * b - a * c
    with np.errstate(all="ignore"):  # a vertical ray, a miss: masked below
        t = (-b - np.sqrt(disc)) / a  # the nearer root: entering the side
        z = o[:, 2] + t * d[:, 2]
    side = np.where((disc >= 0.0) & (a > 0.0) & (t > 0.0) & (z <= cylinder.top), t, np.inf)

    def on_disc(xy: np.ndarray) -> np.ndarray:
        return np.hypot(*(xy - cylinder.center).T) <= cylinder.radius

    return np.minimum(side, _top(cylinder.top, o, d, on_disc))


def _top(height: float, o: np.ndarray, d: np.ndarray, inside) -> np.ndarray:
    """(R,) m to the horizontal face at ``height`` where ``inside(xy)``, from above only."""
    with np.errstate(all="ignore"):  # a level ray: masked below
        t = (height - o[:, 2]) / d[:, 2]
    down = (d[:, 2] < 0.0) & (o[:, 2] > height) & np.isfinite(t)
    xy = o[:, :2] + np.where(down, t, 0.0)[:, None] * d[:, :2]
    return np.where(down & inside(xy), t, np.inf)


def hull_ranges(footprints: Footprints, rotation: np.ndarray, reference: np.ndarray,
                origins: np.ndarray, directions: np.ndarray, skip: int = -1) -> np.ndarray:
    """(R,) m to the nearest hull prism along each ray (inf: none; a ray from inside: none).

    Args:
        footprints: the boats' prisms (body frames).
        rotation: (B, 3, 3) body to world.
        reference: (B, 3) m, their reference points, world frame.
        origins: (R, 3) m, world frame.
        directions: (R, 3) unit, world frame.
        skip: a boat not hit (the rays' own), or -1.
    """
    best = np.full(origins.shape[0], np.inf)
    for b in range(rotation.shape[0]):
        if b == skip:
            continue
        o = (origins - reference[b]) @ rotation[b]  # body frame of boat b
        d = directions @ rotation[b]
        normals = np.concatenate([np.column_stack([footprints.normals[b],
                                                   np.zeros(len(footprints.normals[b]))]),
                                  [[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]])
        low, high = footprints.z[b]
        points = np.concatenate([np.column_stack([footprints.corners[b],
                                                  np.zeros(len(footprints.corners[b]))]),
                                 [[0.0, 0.0, low], [0.0, 0.0, high]]])
        best = np.minimum(best, _clip(o, d, points, normals))
    return best


def _clip(o: np.ndarray, d: np.ndarray, points: np.ndarray, normals: np.ndarray
          ) -> np.ndarray:
    """(R,) t where rays enter the convex polyhedron {x: (x - p_k) . n_k <= 0} (inf: miss)."""
    num = np.einsum("rk,fk->rf", o, normals) - np.einsum("fk,fk->f", points, normals)[None]
    den = d @ normals.T  # (R, F): < 0 entering through face f, > 0 leaving
    with np.errstate(all="ignore"):  # parallel faces: masked below
        t = -num / den
    enter = np.where(den < 0.0, t, -np.inf).max(axis=1)
    leave = np.where(den > 0.0, t, np.inf).min(axis=1)
    parallel_out = np.any((den == 0.0) & (num > 0.0), axis=1)
    hit = (enter <= leave) & (enter > 0.0) & ~parallel_out
    return np.where(hit, enter, np.inf)


def water_range(origins: np.ndarray, directions: np.ndarray, heights) -> np.ndarray:
    """(R,) m along each ray to the sea surface (inf: a ray that does not go down to it).

    The surface at the hit is found by fixed-point iteration on the calm-water plane's hit:
    t_{k+1} = (eta(x(t_k)) - o_z) / d_z, three times (a ray steeper than the waves' slopes
    converges; a grazing one is left where the third step puts it).

    Args:
        origins: (R, 3) m, world frame.
        directions: (R, 3) unit, world frame.
        heights: (N, 2) m world x, y -> (N,) m, the surface's height there.
    """
    down = directions[:, 2] < 0.0
    t = np.full(origins.shape[0], np.inf)
    if not down.any():
        return t
    o, d = origins[down], directions[down]
    tk = -o[:, 2] / d[:, 2]
    for _ in range(3):
        eta = heights(o[:, :2] + tk[:, None] * d[:, :2])
        tk = np.maximum((eta - o[:, 2]) / d[:, 2], 0.0)
    t[down] = tk
    return t
