"""The clip of hull triangles at the water surface, compiled (:func:`clip_f64`).

The same table and the same arithmetic as :func:`boat_dynamics.physics.body.clip.clip_parts`
(its tests' oracle: equal to the last bit), in one pass over the triangles instead of twenty
numpy calls over all of them: each triangle's wet corners (a code 0-7) select its submerged
parts, none, the triangle, its wet corner's triangle or a quadrilateral as two; a waterline
point is x_j + t (x_{j+1} - x_j), t = d_j / (d_j - d_{j+1}), with depth and head 0. The parts'
vector areas (e1 x e2) / 2 are computed with them. Kerner, "Water interaction model for boats
in video games" (Game Developer, 2015), part 1.
"""

from __future__ import annotations

import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["clip_f64", "warm", "wet_centroids_f64"]

#: As ``clip._PARTS_BY_CODE``: up to two parts by wet-corner code, indices into
#: (V0, V1, V2, E01, E12, E20); -1 = no part.
_PARTS = np.array([
    [-1, -1, -1, -1, -1, -1],
    [0, 3, 5, -1, -1, -1],
    [1, 4, 3, -1, -1, -1],
    [0, 1, 4, 0, 4, 5],
    [2, 5, 4, -1, -1, -1],
    [2, 0, 3, 2, 3, 4],
    [1, 2, 5, 1, 5, 3],
    [0, 1, 2, -1, -1, -1],
], dtype=np.int64)
#: Parts per code.
_COUNT = np.array([0, 1, 1, 2, 1, 2, 2, 1], dtype=np.int64)


@kernel
def _code(faces, depths, f):  # pragma: no cover  (compiled)
    """Triangle f's wet-corner code, w0 + 2 w1 + 4 w2."""
    return ((depths[faces[f, 0]] > 0.0) + 2 * (depths[faces[f, 1]] > 0.0)
            + 4 * (depths[faces[f, 2]] > 0.0))


@kernel
def _points(faces, vertices, depths, heads, f, pts, pd, ph):  # pragma: no cover  (compiled)
    """Triangle f's six points (corners, then waterline points on edges 01, 12, 20)."""
    for j in range(3):
        v = faces[f, j]
        pts[j, 0], pts[j, 1], pts[j, 2] = vertices[v, 0], vertices[v, 1], vertices[v, 2]
        pd[j], ph[j] = depths[v], heads[v]
    for j in range(3):
        nxt = (j + 1) % 3
        drop = pd[j] - pd[nxt]
        t = pd[j] / (drop if drop != 0.0 else 1.0)
        for k in range(3):
            pts[3 + j, k] = pts[j, k] + t * (pts[nxt, k] - pts[j, k])
        pd[3 + j], ph[3 + j] = 0.0, 0.0


@kernel
def clip_f64(faces, vertices, depths, heads):  # pragma: no cover  (compiled)
    """The submerged parts of hull triangles, their depths, heads and vector areas.

    Args:
        faces: (F, 3) int, vertex indices of each triangle, wound counter-clockwise seen from
            outside.
        vertices: (V, 3) m, world frame.
        depths: (V,) m, surface height minus vertex height (> 0 = submerged).
        heads: (V,) m, pressure head p / (rho g) at each vertex (the depths for hydrostatic
            pressure).

    Returns:
        (3, 3, T) m corners (coordinate k of corner j of part t at [k, j, t]), (3, T) m depths,
        (3, T) m heads, (T,) int the triangle of each part, (3, T) m^2 vector areas
        (area times outward normal), as :func:`boat_dynamics.physics.body.clip.clip_hulls`.
    """
    count = 0
    for f in range(faces.shape[0]):
        count += _COUNT[_code(faces, depths, f)]
    xyz, d, h = np.empty((3, 3, count)), np.empty((3, count)), np.empty((3, count))
    source, va = np.empty(count, dtype=np.int64), np.empty((3, count))
    pts, pd, ph = np.empty((6, 3)), np.empty(6), np.empty(6)
    t = 0
    for f in range(faces.shape[0]):
        code = _code(faces, depths, f)
        if code == 0:
            continue
        _points(faces, vertices, depths, heads, f, pts, pd, ph)
        for part in range(_COUNT[code]):
            for j in range(3):
                p = _PARTS[code, 3 * part + j]
                xyz[0, j, t], xyz[1, j, t], xyz[2, j, t] = pts[p, 0], pts[p, 1], pts[p, 2]
                d[j, t], h[j, t] = pd[p], ph[p]
            a0, a1, a2 = (xyz[0, 1, t] - xyz[0, 0, t], xyz[1, 1, t] - xyz[1, 0, t],
                          xyz[2, 1, t] - xyz[2, 0, t])
            b0, b1, b2 = (xyz[0, 2, t] - xyz[0, 0, t], xyz[1, 2, t] - xyz[1, 0, t],
                          xyz[2, 2, t] - xyz[2, 0, t])
            va[0, t] = 0.5 * (a1 * b2 - a2 * b1)
            va[1, t] = 0.5 * (a2 * b0 - a0 * b2)
            va[2, t] = 0.5 * (a0 * b1 - a1 * b0)
            source[t] = f
            t += 1
    return xyz, d, h, source, va


@kernel
def wet_centroids_f64(xyz, depths, vector_areas):  # pragma: no cover  (compiled)
    """The parts' centroids, the surface height over them and their areas.

    Args:
        xyz: (3, 3, T) m, the parts' corners (``clip_f64``'s layout), world frame.
        depths: (3, T) m, the corners' depths below the surface.
        vector_areas: (3, T) m^2.

    Returns:
        (T, 3) m centroids; (T,) m the surface height above them, the mean of the corners'
        z + depth (linear over the part); (T,) m^2 areas. As ``SubmergedTriangles.centroids``
        and ``.areas`` and ``(xyz[2] + depths).mean(axis=0)``, their oracles.
    """
    count = depths.shape[1]
    centroids, eta, areas = np.empty((count, 3)), np.empty(count), np.empty(count)
    for t in range(count):
        for k in range(3):
            centroids[t, k] = (xyz[k, 0, t] + xyz[k, 1, t] + xyz[k, 2, t]) / 3.0
        eta[t] = ((xyz[2, 0, t] + depths[0, t]) + (xyz[2, 1, t] + depths[1, t])
                  + (xyz[2, 2, t] + depths[2, t])) / 3.0
        areas[t] = np.sqrt(vector_areas[0, t] * vector_areas[0, t]
                           + vector_areas[1, t] * vector_areas[1, t]
                           + vector_areas[2, t] * vector_areas[2, t])
    return centroids, eta, areas


def warm() -> float:
    """Compile (or load from the cache) this module's kernel; returns the s it took."""
    start = time.perf_counter()
    faces = np.array([[0, 1, 2]], dtype=np.int64)
    xyz, d, _, _, va = clip_f64(faces, np.eye(3), np.array([1.0, -1.0, 0.5]),
                                np.array([1.0, -1.0, 0.5]))
    wet_centroids_f64(xyz, d, va)
    return time.perf_counter() - start
