"""Hull geometry: the box hull and its sample-point layouts.

Body frame FLU (x forward, y left, z up) with the origin at the hull reference point, the
centre of the hull's bounding box (DESIGN.md, "Conventions").
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = [
    "CYLINDER_SEGMENTS",
    "MAX_MESH_FILE_BYTES",
    "MAX_TRIANGLES",
    "BoxHull",
    "HullMesh",
    "HullMeshError",
    "box_mesh",
    "check_mesh",
    "cylinder_mesh",
    "load_mesh",
    "longest_edge",
    "refine",
    "subdivide",
]


@dataclass(frozen=True)
class BoxHull:
    """A rectangular box hull.

    Attributes:
        length: along x, m, > 0.
        beam: along y, m, > 0.
        height: along z, m, > 0.
    """

    length: float
    beam: float
    height: float

    @property
    def volume(self) -> float:
        """Enclosed volume, m^3."""
        return self.length * self.beam * self.height

    @property
    def waterplane_area(self) -> float:
        """Area of the horizontal section when floating upright, m^2."""
        return self.length * self.beam

    def solid_inertia(self, mass: float) -> np.ndarray:
        """Principal moments of a solid box of ``mass`` kg about its centre, (3,) kg m^2.

        I_xx = m (B^2 + H^2) / 12, I_yy = m (L^2 + H^2) / 12, I_zz = m (L^2 + B^2) / 12.
        """
        lsq, bsq, hsq = self.length**2, self.beam**2, self.height**2
        return mass / 12.0 * np.array([bsq + hsq, lsq + hsq, lsq + bsq])

    def bottom_grid(self, nx: int, ny: int) -> np.ndarray:
        """Cell centres of an nx x ny grid on the hull bottom, (nx * ny, 3) m, body frame.

        Each point stands for an equal share of the bottom area, so columns of water above
        the points add up to the displaced volume of the box exactly in flat water.
        """
        xs = (np.arange(nx) + 0.5) / nx * self.length - self.length / 2
        ys = (np.arange(ny) + 0.5) / ny * self.beam - self.beam / 2
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        return np.stack([gx.ravel(), gy.ravel(), np.full(nx * ny, -self.height / 2)], axis=1)

    def boat_layout(self) -> np.ndarray:
        """The seed notes' 7-point boat layout on the hull bottom, (7, 3) m, body frame.

        Bow, port and starboard forward, centre, port and starboard aft, stern: spread wide
        for roll and far fore and aft for pitch, symmetric about the centre line, with their
        centroid at the hull centre (no trim).
        """
        length, beam = self.length, self.beam
        xy = [(0.42, 0.0), (0.2, 0.35), (0.2, -0.35), (0.0, 0.0), (-0.2, 0.35),
              (-0.2, -0.35), (-0.42, 0.0)]
        return np.array([[x * length, y * beam, -self.height / 2] for x, y in xy])


class HullMeshError(ValueError):
    """A hull mesh that cannot be used (not watertight, degenerate, inside out, wrong units)."""


@dataclass(frozen=True)
class HullMesh:
    """A closed, outward-oriented triangle mesh of a hull.

    Attributes:
        vertices: (V, 3) m, body frame, origin at the hull reference point (bounding-box centre).
        faces: (F, 3) vertex indices, counter-clockwise seen from outside.
    """

    vertices: np.ndarray
    faces: np.ndarray

    @cached_property
    def face_normals(self) -> np.ndarray:
        """(F, 3) outward unit normals, body frame (computed once)."""
        c = self.corners
        n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        return n / np.linalg.norm(n, axis=1, keepdims=True)

    @property
    def corners(self) -> np.ndarray:
        """(F, 3, 3) m, the triangles' vertex positions."""
        return self.vertices[self.faces]

    @property
    def areas(self) -> np.ndarray:
        """(F,) m^2 triangle areas."""
        c = self.corners
        return 0.5 * np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1)

    @cached_property
    def volume(self) -> float:
        """Enclosed volume, m^3 (divergence theorem; > 0 for outward faces; computed once)."""
        c = self.corners
        return float(np.einsum("ij,ij->i", c[:, 0], np.cross(c[:, 1], c[:, 2])).sum() / 6.0)

    @property
    def extents(self) -> np.ndarray:
        """(3,) m, size of the bounding box along x, y, z."""
        return self.vertices.max(axis=0) - self.vertices.min(axis=0)

    def solid_inertia(self, mass: float) -> np.ndarray:
        """Moments of inertia (3,) kg m^2 [Ixx, Iyy, Izz] of a uniform solid about its centroid.

        The diagonal of :meth:`inertia_tensor` (body axes).
        """
        return np.diag(self.inertia_tensor(mass)).copy()

    def inertia_products(self, mass: float) -> np.ndarray:
        """Products of inertia (3,) kg m^2 [Ixy, Ixz, Iyz] of a uniform solid about its centroid.

        Ixy = integral(x y dm), ...; the tensor holds them negated (Fossen 2011, eq. 3.28).
        """
        tensor = self.inertia_tensor(mass)
        return -np.array([tensor[0, 1], tensor[0, 2], tensor[1, 2]])

    def inertia_tensor(self, mass: float) -> np.ndarray:
        """Inertia tensor (3, 3) kg m^2 of a uniform solid of ``mass`` about its centroid.

        Each face and the origin make a signed tetrahedron; for a tetrahedron (0, a, b, d) of
        signed volume V = det / 6, integral(x_i x_j dV) = det / 120 (sum_k v_ki v_kj +
        (sum_k v_ki)(sum_k v_kj)). Source: Eberly, "Polyhedral Mass Properties" (2002);
        Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor" (2004).
        """
        c = self.corners
        a, b, d = c[:, 0], c[:, 1], c[:, 2]
        det = np.einsum("ij,ij->i", a, np.cross(b, d))  # 6 x signed tetrahedron volume
        vol = det.sum() / 6.0
        total = a + b + d
        centroid = (det[:, None] * total).sum(axis=0) / (24.0 * vol)
        second = (np.einsum("t,ti,tj->ij", det, a, a) + np.einsum("t,ti,tj->ij", det, b, b)
                  + np.einsum("t,ti,tj->ij", det, d, d)
                  + np.einsum("t,ti,tj->ij", det, total, total)) / 120.0  # integral x_i x_j dV
        second = second / vol * mass - mass * np.outer(centroid, centroid)  # about the centroid
        return np.trace(second) * np.eye(3) - second


def _box_face_grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit-square grid (n x n quads, 2 triangles each): (V, 2) coordinates and (F, 3) faces."""
    ticks = np.linspace(0.0, 1.0, n + 1)
    u, v = np.meshgrid(ticks, ticks, indexing="ij")
    uv = np.stack([u.ravel(), v.ravel()], axis=1)
    idx = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                            np.stack([a, c, d], -1).reshape(-1, 3)])
    return uv, faces


def box_mesh(hull: BoxHull, subdivisions: int = 1) -> HullMesh:
    """Watertight triangle mesh of a box hull, each face an n x n grid of quads (2 n^2 triangles).

    ``subdivisions = 1`` gives the 12-triangle box; more let the waterline follow the waves
    across a face.
    """
    half = np.array([hull.length, hull.beam, hull.height]) / 2.0
    uv, grid_faces = _box_face_grid(subdivisions)
    verts, faces = [], []
    # each face: (normal axis, sign, u axis, v axis) with u x v = outward normal
    for axis, sign in ((0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)):
        u_axis, v_axis = [(1, 2), (2, 0), (0, 1)][axis]
        if sign < 0:
            u_axis, v_axis = v_axis, u_axis
        p = np.zeros((uv.shape[0], 3))
        p[:, axis] = sign * half[axis]
        p[:, u_axis] = (uv[:, 0] * 2 - 1) * half[u_axis]
        p[:, v_axis] = (uv[:, 1] * 2 - 1) * half[v_axis]
        faces.append(grid_faces + sum(len(v) for v in verts))
        verts.append(p)
    vertices = np.concatenate(verts)
    faces = np.concatenate(faces)
    # merge the duplicated edge vertices so the mesh is watertight
    rounded = np.round(vertices / (1e-9 + half.min()) * 1e6).astype(np.int64)
    unique, inverse = np.unique(rounded, axis=0, return_inverse=True)
    merged = np.zeros((unique.shape[0], 3))
    merged[inverse.ravel()] = vertices
    return HullMesh(merged, inverse.ravel()[faces])


#: Facets round a cylinder hull by default: its volume is 1.1 % under the circle's.
CYLINDER_SEGMENTS = 24


def cylinder_mesh(radius: float, height: float, segments: int = CYLINDER_SEGMENTS,
                  rings: int = 4) -> HullMesh:
    """Watertight triangle mesh of an upright circular cylinder (a buoy, a spar).

    Its axis is the body z axis, from -height/2 to height/2 (the bounding box's centre is the
    origin, as for every hull). The side is ``segments`` facets round by ``rings`` bands
    high (2 triangles each), the ends fans of ``segments`` triangles about their centres.
    The facets' corners lie on the circle, so the prism inscribed in it has the volume
    (segments / 2 pi) sin(2 pi / segments) x pi r^2 h: 1.1 % less at 24 segments.

    Args:
        radius: m, > 0.
        height: m, > 0.
        segments: facets round, at least 3.
        rings: bands along the axis, at least 1 (more let the waterline follow the waves).
    """
    angle = 2.0 * np.pi * np.arange(segments) / segments
    z = np.linspace(-height / 2, height / 2, rings + 1)
    side = np.stack([np.tile(radius * np.cos(angle), rings + 1),
                     np.tile(radius * np.sin(angle), rings + 1),
                     np.repeat(z, segments)], axis=1)  # ring k, corner j at k * segments + j
    bottom, top = side.shape[0], side.shape[0] + 1
    vertices = np.concatenate([side, [[0.0, 0.0, -height / 2], [0.0, 0.0, height / 2]]])
    j = np.arange(segments)
    jn = (j + 1) % segments
    faces = []
    for k in range(rings):  # counter-clockwise seen from outside: a, a', b' and a, b', b
        a, an, b, bn = k * segments + j, k * segments + jn, (k + 1) * segments + j, \
            (k + 1) * segments + jn
        faces += [np.stack([a, an, bn], axis=1), np.stack([a, bn, b], axis=1)]
    faces.append(np.stack([np.full(segments, bottom), jn, j], axis=1))
    last = rings * segments
    faces.append(np.stack([np.full(segments, top), last + j, last + jn], axis=1))
    return HullMesh(vertices, np.concatenate(faces).astype(np.int64))


def subdivide(mesh: HullMesh) -> HullMesh:
    """Each triangle split in four at its edge midpoints (shared edges share their midpoint).

    The surface is unchanged (same planes), so volume, hydrostatics and watertightness are
    kept; edges halve.
    """
    faces = mesh.faces
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    unique, inverse = np.unique(np.sort(edges, axis=1), axis=0, return_inverse=True)
    mid = mesh.vertices.shape[0] + inverse.ravel().reshape(3, -1)  # (3, F): m01, m12, m20
    vertices = np.concatenate([mesh.vertices, 0.5 * (mesh.vertices[unique[:, 0]]
                                                     + mesh.vertices[unique[:, 1]])])
    a, b, c = faces.T
    m01, m12, m20 = mid
    new = np.stack([np.stack([a, m01, m20], axis=1), np.stack([m01, b, m12], axis=1),
                    np.stack([m20, m12, c], axis=1), np.stack([m01, m12, m20], axis=1)], axis=1)
    return HullMesh(vertices, new.reshape(-1, 3))


def longest_edge(mesh: HullMesh) -> float:
    """m, the longest triangle edge of the mesh."""
    c = mesh.corners
    return float(np.sqrt(((c - np.roll(c, 1, axis=1)) ** 2).sum(axis=2)).max())


def refine(mesh: HullMesh, max_edge: float, max_triangles: int) -> HullMesh:
    """``mesh`` subdivided (:func:`subdivide`) until no edge exceeds ``max_edge`` (m).

    Stops before a subdivision would pass ``max_triangles`` (the cost bound); returns the mesh
    itself when it is fine enough already.
    """
    while longest_edge(mesh) > max_edge and 4 * mesh.faces.shape[0] <= max_triangles:
        mesh = subdivide(mesh)
    return mesh


def check_mesh(mesh: HullMesh, source: str = "mesh") -> None:
    """Refuse meshes the buoyancy model cannot use.

    Raises:
        HullMeshError: degenerate triangles, open or inconsistently oriented (not watertight)
            surface, inward-facing triangles, or a size that suggests wrong units.
    """
    if mesh.faces.size == 0:
        raise HullMeshError(f"{source}: has no triangles")
    areas = mesh.areas
    size = float(np.max(mesh.extents))
    tiny = np.flatnonzero(areas <= 1e-12 * max(size, 1e-9) ** 2)
    if tiny.size:
        raise HullMeshError(f"{source}: {tiny.size} degenerate triangle(s) of zero area "
                            f"(first: triangle {tiny[0]}); repair the mesh")
    directed = np.concatenate([mesh.faces[:, [0, 1]], mesh.faces[:, [1, 2]],
                               mesh.faces[:, [2, 0]]])
    undirected = np.sort(directed, axis=1)
    _, counts = np.unique(undirected, axis=0, return_counts=True)
    _, dcounts = np.unique(directed, axis=0, return_counts=True)
    if np.any(counts != 2) or np.any(dcounts != 1):
        open_edges = int(np.sum(counts == 1))
        raise HullMeshError(f"{source}: not watertight ({open_edges} open edge(s), "
                            f"{int(np.sum(counts > 2))} edge(s) shared by more than two "
                            "triangles, or inconsistent triangle orientation); buoyancy from "
                            "pressure needs a closed hull")
    if mesh.volume <= 0.0:
        raise HullMeshError(f"{source}: triangles face inward (volume {mesh.volume:.4g} m^3); "
                            "flip the face orientation")
    if size > 500.0 or size < 0.05:
        raise HullMeshError(f"{source}: spans {size:.4g} m; expected 0.05 to 500 m. Wrong "
                            "units? Set hull.scale (e.g. 0.001 for a mesh in millimetres)")


#: The most triangles a hull mesh may have: the pressure integration costs about 5 k
#: instructions a triangle a step (3,072 triangles: 16 M), and ``boatsim hydro`` meshes at most
#: 8,000 panels.
MAX_TRIANGLES = 100_000
#: The largest mesh file read, bytes (100,000 triangles: 5 MB of binary STL, about 25 MB of
#: ASCII STL or OBJ).
MAX_MESH_FILE_BYTES = 64 * 2**20


def _check_size(path: str) -> None:
    """Refuse a mesh file too large to read, before reading it (a binary STL by its header).

    Raises:
        HullMeshError: over :data:`MAX_MESH_FILE_BYTES`, or a binary STL declaring over
            :data:`MAX_TRIANGLES` triangles.
    """
    import os

    try:
        size = os.path.getsize(path)
        with open(path, "rb") as f:
            head = f.read(84)
    except OSError as exc:
        raise HullMeshError(f"{path}: cannot read a triangle mesh ({exc.strerror})") from exc
    if size > MAX_MESH_FILE_BYTES:
        raise HullMeshError(f"{path}: {size:,} bytes; a hull mesh file may have at most "
                            f"{MAX_MESH_FILE_BYTES:,} ({MAX_TRIANGLES:,} triangles)")
    declared = int.from_bytes(head[80:84], "little") if len(head) == 84 else 0
    if size == 84 + 50 * declared and declared > MAX_TRIANGLES:  # a binary STL's count
        raise HullMeshError(f"{path}: declares {declared:,} triangles; a hull mesh may have "
                            f"at most {MAX_TRIANGLES:,}")


def load_mesh(path: str, scale: float = 1.0) -> HullMesh:
    """Read an STL or OBJ hull with trimesh, scale it, centre its bounding box, check it.

    Args:
        path: file path.
        scale: factor to metres (0.001 for millimetres).

    Raises:
        HullMeshError: unreadable file or a mesh that :func:`check_mesh` refuses.
    """
    import trimesh  # imported here: only mesh files need it

    _check_size(path)
    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for bad files
        raise HullMeshError(f"{path}: cannot read a triangle mesh ({exc})") from exc
    vertices = np.asarray(loaded.vertices, dtype=float) * scale
    faces = np.asarray(loaded.faces, dtype=np.int64)
    if vertices.size == 0:
        raise HullMeshError(f"{path}: has no triangles")
    if len(faces) > MAX_TRIANGLES:
        raise HullMeshError(f"{path}: {len(faces):,} triangles; a hull mesh may have at most "
                            f"{MAX_TRIANGLES:,}")
    # merge coincident vertices (STL stores each triangle's corners separately)
    rounded = np.round(vertices / max(float(np.ptp(vertices)), 1e-9) * 1e9).astype(np.int64)
    _, first, inverse = np.unique(rounded, axis=0, return_index=True, return_inverse=True)
    vertices = vertices[first]
    faces = inverse.ravel()[faces]
    centre = (vertices.max(axis=0) + vertices.min(axis=0)) / 2.0
    mesh = HullMesh(vertices - centre, faces)
    check_mesh(mesh, path)
    return mesh
