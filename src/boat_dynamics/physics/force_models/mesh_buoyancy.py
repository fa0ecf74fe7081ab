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

from dataclasses import dataclass, field, replace
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.clip import SubmergedTriangles, clip_hulls
from boat_dynamics.physics.body.hull import HullMesh, refine
from boat_dynamics.physics.body.wrench import Wrench, cross, sum_by_owner
from boat_dynamics.physics.force_models.hull_drag import HullDrag
from boat_dynamics.physics.force_models.slamming import Slamming

__all__ = [
    "PRESSURE_MODELS",
    "Hydrostatics",
    "MeshBuoyancy",
    "PressureModel",
    "hydrostatics",
    "hydrostatics_of",
    "mesh_buoyancy",
    "panelled",
    "pressure_wrenches",
    "submerged_triangles",
]


#: The pressure on the wetted hull: ``hydrostatic``, rho g (eta - z) (the seed notes' surfacic
#: method: the full surface elevation at every depth); ``froude_krylov``, hydrostatic plus
#: the incident waves' pressure with the depth decay of linear theory
#: (:func:`ocean_sim.physics.waves.pressure_head`), on the hull up to the instantaneous
#: surface; or ``linear``, linear seakeeping: rho g (-z) on the hull up to the calm-water plane
#: (exact hydrostatics of the hull's own motion) plus the Froude-Krylov force of the incident
#: waves from the hull's potential-flow coefficients
#: (:func:`boat_dynamics.physics.potential_flow.diffraction.excitation_wrench`; Newman 1977, sec.
#: 6.17; WEC-Sim's linear hydrostatics and excitation).
PressureModel = Literal["hydrostatic", "froude_krylov", "linear"]
PRESSURE_MODELS: tuple[PressureModel, ...] = get_args(PressureModel)


@dataclass(frozen=True)
class MeshBuoyancy:
    """Parameters of the mesh model.

    Attributes:
        mesh: the closed hull mesh (body frame, origin at the hull reference point).
        drag: friction and pressure drag options on the wetted triangles.
        pressure: the pressure model.
        panels_per_wavelength: ``froude_krylov``: :func:`boat_dynamics.physics.core.pipeline.init`
            subdivides the mesh until no edge is longer than the shortest wave acting on the
            boat over this (the pressure is interpolated linearly over each triangle) ...
        max_triangles: ... unless that would take the hull past this many triangles (the cost
            bound: the surface is queried at every vertex every step).
        slamming: the slamming model (:mod:`boat_dynamics.physics.force_models.slamming`).
    """

    mesh: HullMesh
    drag: HullDrag = field(default_factory=HullDrag)
    pressure: PressureModel = "hydrostatic"
    panels_per_wavelength: float = 10.0
    max_triangles: int = 4096
    slamming: Slamming = field(default_factory=Slamming)


def submerged_triangles(model: MeshBuoyancy, vertices_world: np.ndarray,
                        vertex_depths: np.ndarray) -> SubmergedTriangles:
    """Clip one hull at the surface sampled at its vertices (see :func:`clip_parts`)."""
    return clip_hulls(model.mesh.faces, vertices_world, vertex_depths)


def pressure_wrenches(wet: SubmergedTriangles, owner: np.ndarray, count: int,
                      center_of_mass_world: np.ndarray, rho_g: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Pressure force and torque on each hull, world frame.

    The pressure is rho g h, the head h linear over each part (:attr:`SubmergedTriangles.heads`:
    the depth for hydrostatic pressure).

    Args:
        wet: the submerged triangles of ``count`` hulls.
        owner: (T,) int, the hull of each triangle.
        count: number of hulls, B.
        center_of_mass_world: (B, 3) m, the torque reference of each hull.
        rho_g: (B,) N/m^3, water density times gravity for each hull.

    Returns:
        (B, 3) N forces and (B, 3) N m torques about the centres of mass, world frame.
    """
    from boat_dynamics.physics.force_models.pressure_kernel import pressure_wrenches_f64

    return pressure_wrenches_f64(wet.xyz, wet.heads, wet.vector_areas, owner, count,
                                 np.ascontiguousarray(center_of_mass_world, dtype=float),
                                 np.ascontiguousarray(rho_g, dtype=float))


def _pressure_wrenches_numpy(wet: SubmergedTriangles, owner: np.ndarray, count: int,
                             center_of_mass_world: np.ndarray, rho_g: np.ndarray
                             ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`pressure_wrenches` in numpy: the compiled kernel's oracle."""
    p, d, vector_area = wet.xyz, wet.heads, wet.vector_areas
    dsum = d[0] + d[1] + d[2]
    com = center_of_mass_world.T.take(owner, axis=1)  # (3, T)
    # integral(r d dA) = A / 12 sum_j r_j (sum_k d_k + d_j), r about the centre of mass
    moment = ((p[:, 0] - com) * (dsum + d[0]) + (p[:, 1] - com) * (dsum + d[1])
              + (p[:, 2] - com) * (dsum + d[2]))
    rho_g_t = rho_g.take(owner)
    per_triangle = np.empty((6, d.shape[1]))
    # force -rho g integral(d dA) n = -rho g (sum d / 3) A n, at the centre of pressure
    per_triangle[:3] = (rho_g_t * dsum * (-1.0 / 3.0)) * vector_area
    per_triangle[3:] = (rho_g_t * (-1.0 / 12.0)) * cross(moment, vector_area, axis=0)
    sums = sum_by_owner(per_triangle.T, owner, count)
    return sums[:, :3], sums[:, 3:]


def panelled(model: MeshBuoyancy, shortest_wavelength: float) -> MeshBuoyancy:
    """``model`` with a mesh fine enough for its pressure in waves of ``shortest_wavelength`` m.

    For ``froude_krylov`` pressure the mesh is subdivided
    (:func:`boat_dynamics.physics.body.hull.refine`) until its longest edge is at most
    shortest_wavelength / panels_per_wavelength, within ``max_triangles``. The model itself
    for hydrostatic pressure, a still sea (``inf``) or a mesh already fine enough.
    """
    if model.pressure != "froude_krylov" or not np.isfinite(shortest_wavelength):
        return model
    mesh = refine(model.mesh, shortest_wavelength / model.panels_per_wavelength,
                  model.max_triangles)
    return model if mesh is model.mesh else replace(model, mesh=mesh)


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
        wet = submerged_triangles(model, vertices_world, vertex_depths)
    force, torque = pressure_wrenches(wet, np.zeros(wet.faces.shape[0], dtype=np.intp), 1,
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
    wet = submerged_triangles(model, vertices_world, vertex_depths)
    return hydrostatics_of(wet, np.zeros(wet.faces.shape[0], dtype=np.intp), 1,
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
    p, d = wet.xyz, wet.depths  # (3, 3, T), (3, T): corners along the first or second axis
    nz_area = wet.vector_areas[2]  # n_z dA

    def integral(f, g=None):
        """Integral over each triangle of f (linear) or f*g (both linear), per unit area."""
        if g is None:
            return f.sum(axis=0) / 3.0
        return (f.sum(axis=0) * g.sum(axis=0) + (f * g).sum(axis=0)) / 12.0

    # waterplane moments, in coordinates across each body x axis (transverse)
    axis = rotation[:, :, 0].copy()
    axis[:, 2] = 0.0
    axis /= np.maximum(np.linalg.norm(axis, axis=1), 1e-12)[:, None]
    across = np.stack([-axis[:, 1], axis[:, 0], np.zeros(count)], axis=1).T.take(owner, axis=1)
    s = p[0] * across[0] + p[1] * across[1]  # (3, T) transverse coordinate of each corner
    x, y, z = p[0], p[1], p[2]
    columns = np.stack([integral(d), integral(x, d), integral(y, d),
                        integral(z, d) + 0.5 * integral(d, d), np.ones_like(nz_area),
                        integral(s), integral(s, s)], axis=1)
    sums = sum_by_owner(-columns * nz_area[:, None], owner, count)
    volume, a_wp, s_first, s_second = sums[:, 0], sums[:, 4], sums[:, 5], sums[:, 6]
    floating = volume > 0.0
    cb = np.where(floating[:, None], sums[:, 1:4] / np.where(floating, volume, 1.0)[:, None],
                  center_of_mass_world)
    s_mean = s_first / np.where(a_wp > 0.0, a_wp, np.inf)
    i_wp = s_second - a_wp * s_mean**2
    gm = cb[:, 2] + i_wp / np.where(floating, volume, np.inf) - center_of_mass_world[:, 2]
    rows = zip(floating.tolist(), volume.tolist(), cb, a_wp.tolist(), gm.tolist(),
               np.asarray(draft, dtype=float).tolist(), strict=True)
    return [Hydrostatics(v, c, a, m, d) if f else Hydrostatics(0.0, c, 0.0, 0.0, 0.0)
            for f, v, c, a, m, d in rows]
