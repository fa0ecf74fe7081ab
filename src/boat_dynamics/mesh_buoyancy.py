"""Mesh buoyancy, the surfacic method: hydrostatic pressure on the submerged hull triangles.

Each hull triangle is clipped against the water surface sampled at its vertices (the depth
d = surface height - z is taken linear along each edge, so the waterline cuts an edge where
d = 0). On each submerged triangle the pressure p = rho g d acts along the inward normal::

    F_i = -rho g (integral of d dA) n_i = -rho g A_i (d_1 + d_2 + d_3) / 3 n_i

applied at its true centre of pressure (not the centroid: deeper points push harder),
integral(r d dA) / integral(d dA), with, for d linear on a triangle,
integral(r d dA) = A / 12 [ (sum r_j)(sum d_j) + sum r_j d_j ]. On a closed hull in flat water
the forces sum to rho g V_submerged straight up (Archimedes, by the divergence theorem) and the
torques to the exact righting moment, for any shape and heel.

Sources: Kerner, "Water interaction model for boats in video games" (Game Developer, 2015),
parts 1-2; the seed notes ("Volume Displacement (Mesh-Based Archimedes)", "surfacic"
variant, "true center of pressure").
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.hull import HullMesh
from boat_dynamics.hull_drag import HullDrag
from boat_dynamics.wrench import Wrench, cross, sum_by_owner

__all__ = [
    "Hydrostatics",
    "MeshBuoyancy",
    "SubmergedTriangles",
    "clip_hulls",
    "clip_submerged",
    "clip_submerged_indexed",
    "hydrostatics",
    "hydrostatics_of",
    "mesh_buoyancy",
    "pressure_wrenches",
    "submerged_triangles",
]


@dataclass(frozen=True)
class MeshBuoyancy:
    """Parameters of the mesh model.

    Attributes:
        mesh: the closed hull mesh (body frame, origin at the hull reference point).
        drag: friction and pressure drag options on the wetted triangles.
    """

    mesh: HullMesh
    drag: HullDrag = field(default_factory=HullDrag)


def clip_submerged(corners: np.ndarray, depths: np.ndarray, normals: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The submerged parts of triangles, as triangles.

    Args:
        corners: (F, 3, 3) m, triangle vertices, world frame.
        depths: (F, 3) m, depth below the surface at each vertex (> 0 = submerged).
        normals: (F, 3) unit outward normals.

    Returns:
        (T, 3, 3) corners, (T, 3) depths (0 on the waterline), (T, 3) normals of the submerged
        triangles; winding is preserved. A triangle with one vertex under water gives one
        triangle, with two a quadrilateral split in two.
    """
    return clip_submerged_indexed(corners, depths, normals)[:3]


def clip_submerged_indexed(corners: np.ndarray, depths: np.ndarray, normals: np.ndarray
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`clip_submerged`, plus (T,) the index of the input triangle each part comes from."""
    wet = depths > 0.0
    count = wet.sum(axis=1)
    rows = np.arange(corners.shape[0])
    full = rows[count == 3]
    out_p, out_d, out_n, out_s = [corners[full]], [depths[full]], [normals[full]], [full]

    def edge_point(p_from, d_from, p_to, d_to):
        t = d_from / (d_from - d_to)
        return p_from + t[:, None] * (p_to - p_from)

    one = rows[count == 1]
    if one.size:
        a = np.argmax(wet[one], axis=1)  # the submerged vertex; b, c keep the winding
        b, c = (a + 1) % 3, (a + 2) % 3
        pa, pb, pc = corners[one, a], corners[one, b], corners[one, c]
        da, db, dc = depths[one, a], depths[one, b], depths[one, c]
        ab, ac = edge_point(pa, da, pb, db), edge_point(pa, da, pc, dc)
        zero = np.zeros_like(da)
        out_p.append(np.stack([pa, ab, ac], axis=1))
        out_d.append(np.stack([da, zero, zero], axis=1))
        out_n.append(normals[one])
        out_s.append(one)
    two = rows[count == 2]
    if two.size:
        c = np.argmin(wet[two], axis=1)  # the dry vertex; a, b keep the winding
        a, b = (c + 1) % 3, (c + 2) % 3
        pa, pb, pc = corners[two, a], corners[two, b], corners[two, c]
        da, db, dc = depths[two, a], depths[two, b], depths[two, c]
        bc, ca = edge_point(pb, db, pc, dc), edge_point(pa, da, pc, dc)
        zero = np.zeros_like(da)
        out_p += [np.stack([pa, pb, bc], axis=1), np.stack([pa, bc, ca], axis=1)]
        out_d += [np.stack([da, db, zero], axis=1), np.stack([da, zero, zero], axis=1)]
        out_n += [normals[two], normals[two]]
        out_s += [two, two]
    if len(out_p) == 1:
        return out_p[0], out_d[0], out_n[0], out_s[0]
    return (np.concatenate(out_p), np.concatenate(out_d), np.concatenate(out_n),
            np.concatenate(out_s))


@dataclass(frozen=True)
class SubmergedTriangles:
    """The wetted part of one or several hulls, world frame.

    Attributes:
        corners: (T, 3, 3) m.
        depths: (T, 3) m below the surface at each corner.
        normals: (T, 3) outward unit normals.
        areas: (T,) m^2.
        faces: (T,) int, the hull face each part comes from.
    """

    corners: np.ndarray
    depths: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    faces: np.ndarray

    def __iter__(self):
        return iter((self.corners, self.depths, self.normals, self.areas))


def clip_hulls(faces: np.ndarray, normals_world: np.ndarray, vertices_world: np.ndarray,
               vertex_depths: np.ndarray) -> SubmergedTriangles:
    """Clip hulls at the surface sampled at their vertices (see :func:`clip_submerged`).

    Args:
        faces: (F, 3) int, vertex indices of each triangle (several hulls may be concatenated).
        normals_world: (F, 3) outward unit normals, world frame.
        vertices_world: (V, 3) m.
        vertex_depths: (V,) m, surface height minus vertex height.
    """
    p, d, n, source = clip_submerged_indexed(vertices_world[faces], vertex_depths[faces],
                                             normals_world)
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    c = cross(e1, e2)
    area = 0.5 * np.sqrt(np.einsum("ij,ij->i", c, c))
    return SubmergedTriangles(p, d, n, area, source)


def submerged_triangles(model: MeshBuoyancy, vertices_world: np.ndarray,
                        vertex_depths: np.ndarray, rotation: np.ndarray) -> SubmergedTriangles:
    """Clip one hull at the surface sampled at its vertices (see :func:`clip_submerged`)."""
    return clip_hulls(model.mesh.faces, model.mesh.face_normals @ rotation.T, vertices_world,
                      vertex_depths)


def pressure_wrenches(wet: SubmergedTriangles, owner: np.ndarray, count: int,
                      center_of_mass_world: np.ndarray, rho_g: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Hydrostatic pressure force and torque on each hull, world frame.

    Args:
        wet: the submerged triangles of ``count`` hulls.
        owner: (T,) int, the hull of each triangle.
        count: number of hulls, B.
        center_of_mass_world: (B, 3) m, the torque reference of each hull.
        rho_g: (B,) N/m^3, water density times gravity for each hull.

    Returns:
        (B, 3) N forces and (B, 3) N m torques about the centres of mass, world frame.
    """
    p, d, n, area = wet
    dsum = d.sum(axis=1)
    integral_d = area * dsum / 3.0  # integral of d dA, m^3
    rel = p - center_of_mass_world[owner][:, None, :]
    moment = (area / 12.0)[:, None] * (rel.sum(axis=1) * dsum[:, None]
                                        + np.einsum("tj,tjk->tk", d, rel))
    pressure_n = -rho_g[owner][:, None] * n
    per_triangle = np.concatenate([integral_d[:, None] * pressure_n,
                                   cross(moment, pressure_n)], axis=1)
    sums = sum_by_owner(per_triangle, owner, count)
    return sums[:, :3], sums[:, 3:]


def mesh_buoyancy(
    model: MeshBuoyancy,
    vertices_world: np.ndarray,
    vertex_depths: np.ndarray,
    rotation: np.ndarray,
    center_of_mass_world: np.ndarray,
    water_density: float,
    gravity: float,
    wet: SubmergedTriangles | None = None,
) -> Wrench:
    """Hydrostatic pressure wrench on one submerged hull (see :func:`pressure_wrenches`).

    Args:
        model: the mesh model.
        vertices_world: (V, 3) m, hull vertices in the world frame.
        vertex_depths: (V,) m, surface height minus vertex height.
        rotation: (3, 3) body-to-world rotation.
        center_of_mass_world: (3,) m.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.
        wet: the submerged triangles, if already clipped.

    Returns:
        The wrench about the centre of mass, body frame.
    """
    if wet is None:
        wet = submerged_triangles(model, vertices_world, vertex_depths, rotation)
    force, torque = pressure_wrenches(wet, np.zeros(wet.areas.shape[0], dtype=np.intp), 1,
                                      np.asarray(center_of_mass_world)[None, :],
                                      np.array([water_density * gravity]))
    return Wrench(rotation.T @ force[0], rotation.T @ torque[0])


@dataclass(frozen=True)
class Hydrostatics:
    """Hydrostatic properties of the floating hull, world frame (exact in flat water).

    Attributes:
        submerged_volume: m^3.
        center_of_buoyancy: (3,) m, centroid of the submerged volume.
        waterplane_area: m^2, area of the hull's section by the surface.
        metacentric_height: GM_T = KB + BM - KG, m (transverse, about the body x axis).
        draft: m, depth of the lowest submerged vertex below its surface.
    """

    submerged_volume: float
    center_of_buoyancy: np.ndarray
    waterplane_area: float
    metacentric_height: float
    draft: float


def hydrostatics(model: MeshBuoyancy, vertices_world: np.ndarray, vertex_depths: np.ndarray,
                 rotation: np.ndarray, center_of_mass_world: np.ndarray) -> Hydrostatics:
    """Submerged volume, centre of buoyancy, waterplane area and GM of one hull.

    See :func:`hydrostatics_of` for the method.
    """
    wet = submerged_triangles(model, vertices_world, vertex_depths, rotation)
    return hydrostatics_of(wet, np.zeros(wet.areas.shape[0], dtype=np.intp), 1,
                           rotation[None], np.asarray(center_of_mass_world)[None],
                           np.array([vertex_depths.max()]))[0]


def hydrostatics_of(wet: SubmergedTriangles, owner: np.ndarray, count: int,
                    rotation: np.ndarray, center_of_mass_world: np.ndarray,
                    draft: np.ndarray) -> list[Hydrostatics]:
    """Submerged volume, centre of buoyancy, waterplane area and GM of ``count`` hulls.

    Volume integrals become integrals over the submerged surface by the divergence theorem
    with fields that vanish on the waterplane (d = 0 there): V = -integral(d n_z dA),
    integral(x dV) = -integral(x d n_z dA), integral(z dV) = -integral((z d + d^2/2) n_z dA);
    waterplane moments are integral(f dA_wp) = -integral(f n_z dA) over the submerged surface.
    BM = I_wp / V with I_wp the waterplane's second moment about its centroid line along the
    body x axis. Source: Biran & Lopez-Pulido, "Ship Hydrostatics and Stability" (2014),
    ch. 2-3.

    Args:
        wet: the submerged triangles of the hulls.
        owner: (T,) int, the hull of each triangle.
        count: number of hulls, B.
        rotation: (B, 3, 3) body-to-world rotations.
        center_of_mass_world: (B, 3) m.
        draft: (B,) m, depth of each hull's lowest vertex below its surface.
    """
    p, d, n, area = wet
    nz = n[:, 2]

    def integral(f, g=None):
        """Integral over each triangle of f (linear) or f*g (both linear), (T,)."""
        if g is None:
            return area * f.sum(axis=1) / 3.0
        return area / 12.0 * (f.sum(axis=1) * g.sum(axis=1) + (f * g).sum(axis=1))

    # waterplane moments, in coordinates across each body x axis (transverse)
    axis = rotation[:, :, 0].copy()
    axis[:, 2] = 0.0
    axis /= np.maximum(np.linalg.norm(axis, axis=1), 1e-12)[:, None]
    across = np.stack([-axis[:, 1], axis[:, 0], np.zeros(count)], axis=1)
    s = np.einsum("tjk,tk->tj", p, across[owner])  # transverse coordinate of each corner
    x, y, z = p[:, :, 0], p[:, :, 1], p[:, :, 2]
    columns = np.stack([integral(d), integral(x, d), integral(y, d),
                        integral(z, d) + 0.5 * integral(d, d), area, integral(s),
                        integral(s, s)], axis=1)
    sums = sum_by_owner(-columns * nz[:, None], owner, count)
    out = []
    for b in range(count):
        volume, mx, my, mz, a_wp, s_first, s_second = sums[b].tolist()
        com = center_of_mass_world[b]
        if volume <= 0.0:
            out.append(Hydrostatics(0.0, com.copy(), 0.0, 0.0, 0.0))
            continue
        cb = np.array([mx, my, mz]) / volume
        s_mean = s_first / a_wp if a_wp > 0.0 else 0.0
        i_wp = s_second - a_wp * s_mean**2
        gm = (cb[2] + i_wp / volume) - com[2]
        out.append(Hydrostatics(volume, cb, a_wp, gm, float(draft[b])))
    return out
