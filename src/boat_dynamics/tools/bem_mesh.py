"""The panel mesh of a hull for a boundary-element solver: pure NumPy (``boatsim hydro``).

From a closed, outward-oriented triangle mesh in boatsim's body frame (FLU, origin at the hull
reference point) floating upright at rest:

1. The mesh is translated so that the calm water is at z = 0 (``draft_offset``); coplanar
   triangle pairs are merged into quads (a box's 12 triangles give 6 rectangles); the faces
   are clipped at z = 0 (the waterline is an edge row), split at the lid level z_lid (the lid
   edge lies on a row of panel edges) and, for a hull symmetric about y = 0 and/or x = 0, cut
   to the half (quarter) used with the solver's reflection symmetries (exact: the other half
   is the mirror image). Each coarse face is then subdivided: quads into nu x nv bilinear
   grids, triangles into barycentric grids, edges at most ``panel_size`` with z lengths
   counted twice (:data:`VERTICAL_STRETCH`: rows half as tall). Default size
   (:func:`default_panel_size`): L / 40, at most the larger of B / 16 and an eighth of the
   half-girth T + B / 2, at most 2.5 |z_lid| and at most the shortest wavelength asked for
   over :data:`PANELS_PER_WAVELENGTH`.
2. The interior lid (against irregular frequencies; Lee & Newman, WAMIT manual, sec. 10;
   Babarit & Delhommeau 2015) is a grid of the same size over the hull's section at z_lid,
   clipped to the section. z_lid = 0.9 x ``lowest_lid_position(omega_max)`` (Capytaine's
   formula: the depth at which the lid's own irregular frequencies reach omega_max), or an
   existing vertex level within 15 % of it. Measured on the 4 x 2 x 1 m box: with the lid at
   0.6 x that depth and panels 3 to 7 times its depth, spurious spikes appeared at 8 to
   11 rad/s (B33 of -21,600 kg/s); lid panels must stay within about 2.5 times the lid depth.
"""

from __future__ import annotations

import logging
import math

import numpy as np

__all__ = ["LID_FRACTION", "PANELS_PER_WAVELENGTH", "PANEL_PER_LID", "REL_TOL",
           "VERTICAL_STRETCH", "default_directions", "default_omegas", "default_panel_size",
           "immersed_panels", "indexed", "mirror_symmetric"]

LOG = logging.getLogger(__name__)

#: z_lid as a fraction of lowest_lid_position(omega_max) (reference box: 0.68).
LID_FRACTION = 0.9

#: Largest panel edge as a multiple of the lid depth |z_lid|.
PANEL_PER_LID = 2.5

#: Panel edges per wavelength: Capytaine's criterion, panel radius (about edge / sqrt 2) at most
#: a wavelength / 8 (Capytaine 3.0 documentation, "Mesh resolution").
PANELS_PER_WAVELENGTH = 8.0 / math.sqrt(2.0)

#: Hull panel edges are measured with their z component times this (rows half as tall).
VERTICAL_STRETCH = 2.0

#: Geometric tolerance, relative to the hull size.
REL_TOL = 1e-9


def default_omegas(length: float, n: int = 40) -> np.ndarray:
    """(n,) rad/s, evenly spaced, Froude-scaled from 0.5..12 rad/s for a 4 m hull.

    omega ~ 1/sqrt(L): wavelengths from 0.107 L to 61.6 L (deep water), which covers the
    0.4 L .. 20 L of interest; for L = 4 m exactly the reference grid linspace(0.5, 12, 40).
    """
    scale = math.sqrt(4.0 / length)
    return np.linspace(0.5 * scale, 12.0 * scale, n)


def default_directions(symmetric: bool) -> np.ndarray:
    """Wave directions, rad: 0..180 deg step 45 for a hull symmetric about y = 0, else 0..315."""
    stop = 180.0 if symmetric else 315.0
    return np.radians(np.arange(0.0, stop + 1.0, 45.0))


def default_panel_size(extents, z_lid: float = math.nan, draft: float = math.nan,
                       shortest_wavelength: float = math.inf) -> float:
    """Panel edge length, m, for a hull of bounding-box ``extents`` (L, B, H) and lid depth.

    L / 40; at most B / 16, or an eighth of the immersed half-girth T + B / 2 where that is
    larger (a slender hull: B / 16 alone gives a 3 x 0.3 m Wigley hull, T 0.19 m, 0.019 m
    panels); at most PANEL_PER_LID x |z_lid| (coarser lid panels over a thin top row of hull
    panels give spurious spikes at high frequencies); at most ``shortest_wavelength`` (m) /
    :data:`PANELS_PER_WAVELENGTH`. With ``VERTICAL_STRETCH`` = 2 (rows half as tall): 0.1 m
    for the 4 x 2 x 1 m box, within 1.1 % of a 1.2 times finer mesh and within 1 % of the
    reference file.

    Args:
        extents: (3,) m, the hull's bounding box.
        z_lid: m, the lid's depth below the calm water (negative), nan: no lid.
        draft: T, m, the immersed depth (nan: B / 16 alone).
        shortest_wavelength: m.
    """
    length, beam = float(extents[0]), float(extents[1])
    across = beam / 16.0 if math.isnan(draft) else max(beam / 16.0, (draft + beam / 2) / 8.0)
    size = min(length / 40.0, across, shortest_wavelength / PANELS_PER_WAVELENGTH)
    return size if math.isnan(z_lid) else min(size, PANEL_PER_LID * abs(z_lid))


# --------------------------------------------------------------------------------------
# Symmetry
# --------------------------------------------------------------------------------------
def _surface_moments(vertices: np.ndarray, faces: np.ndarray):
    """Exact area moments of a triangle mesh: (int x dA, int x x^T dA, int n x^T dA)."""
    c = vertices[faces]
    cross = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])  # 2 A n
    area = 0.5 * np.linalg.norm(cross, axis=1)
    total = c.sum(axis=1)
    first = (area[:, None] * total / 3.0).sum(axis=0)
    second = (np.einsum("f,fki,fkj->ij", area, c, c)
              + np.einsum("f,fi,fj->ij", area, total, total)) / 12.0
    normal_first = np.einsum("fi,fj->ij", 0.5 * cross, total / 3.0)
    return first, second, normal_first


def _mirror_invariant(points: np.ndarray, axis: int, tol: float) -> bool:
    """Whether every mirrored point has a point within about ``tol``.

    Two staggered rounding grids, so that no match is lost at a grid-cell boundary.
    """
    mirrored = points.copy()
    mirrored[:, axis] *= -1
    found = np.zeros(len(points), dtype=bool)
    for shift in (0.0, 0.5):
        keys = {tuple(k) for k in np.floor(points / tol + shift).astype(np.int64)}
        found |= [tuple(k) in keys for k in np.floor(mirrored / tol + shift).astype(np.int64)]
    return bool(found.all())


def mirror_symmetric(vertices, faces, axis: int) -> bool:
    """Whether the closed mesh is its own mirror image about the plane ``x[axis] = 0``.

    Checks that the vertex set is mirror-invariant (to 1e-7 of the hull size) and that the odd
    area moments (first and second moments of the surface and of its normals) vanish.
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    size = float(np.ptp(v, axis=0).max())
    if not _mirror_invariant(v, axis, 1e-7 * size):
        return False
    first, second, normal_first = _surface_moments(v, f)
    others = [i for i in range(3) if i != axis]
    odd = [first[axis] / size**3, *(second[axis, others] / size**4),
           *(normal_first[axis, others] / size**3), *(normal_first[others, axis] / size**3)]
    return bool(np.all(np.abs(odd) < 1e-7))


# --------------------------------------------------------------------------------------
# Coarse polygons: merging, clipping
# --------------------------------------------------------------------------------------
def _merge_coplanar_pairs(vertices: np.ndarray, faces: np.ndarray) -> list[np.ndarray]:
    """Polygons ((k, 3) arrays) of a triangle mesh, with coplanar pairs merged.

    Two coplanar triangles sharing their longest edge become one convex quad (a box's 12
    triangles give its 6 rectangles).
    """
    corners = vertices[faces]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals = cross / np.linalg.norm(cross, axis=1, keepdims=True)
    edge_len = np.linalg.norm(corners - np.roll(corners, -1, axis=1), axis=2)  # edge i: i->i+1
    longest = edge_len.argmax(axis=1)
    owner = {}
    for f, i in enumerate(longest):
        owner[(faces[f, i], faces[f, (i + 1) % 3])] = f
    used = np.zeros(len(faces), dtype=bool)
    polygons = []
    for f, i in enumerate(longest):
        if used[f]:
            continue
        a, b, c = faces[f, i], faces[f, (i + 1) % 3], faces[f, (i + 2) % 3]
        g = owner.get((b, a))
        if g is not None and not used[g] and normals[f] @ normals[g] > 1.0 - 1e-12:
            q = faces[g, (longest[g] + 2) % 3]
            quad = vertices[[a, q, b, c]]
            if _is_convex(quad, normals[f]):
                used[[f, g]] = True
                polygons.append(quad)
                continue
        used[f] = True
        polygons.append(vertices[[a, b, c]])
    return polygons


def _is_convex(poly: np.ndarray, normal: np.ndarray) -> bool:
    """Whether the planar polygon turns strictly left (about ``normal``) at every vertex."""
    edges = np.roll(poly, -1, axis=0) - poly
    turns = np.cross(edges, np.roll(edges, -1, axis=0)) @ normal
    scale = np.linalg.norm(edges, axis=1).max() ** 2
    return bool(np.all(turns > 1e-12 * scale))


def _clip(polygons: list[np.ndarray], normal, offset: float, tol: float) -> list[np.ndarray]:
    """The parts of convex polygons where normal . x <= offset (Sutherland-Hodgman).

    Intersection points are computed from the edge's endpoints in a canonical order, so the
    two faces sharing an edge get bit-identical points (the mesh stays conforming).
    """
    normal = np.asarray(normal, dtype=float)
    out = []
    for poly in polygons:
        d = poly @ normal - offset
        d[np.abs(d) <= tol] = 0.0
        if np.all(d <= 0.0):
            out.append(poly)
            continue
        if np.all(d >= 0.0):
            continue
        kept = []
        for k in range(len(poly)):
            m = (k + 1) % len(poly)
            if d[k] <= 0.0:
                kept.append(poly[k])
            if d[k] * d[m] < 0.0:
                p, q, dp, dq = poly[k], poly[m], d[k], d[m]
                if tuple(q) < tuple(p):
                    p, q, dp, dq = q, p, dq, dp
                kept.append(p + dp / (dp - dq) * (q - p))
        kept = _simplified(np.array(kept), tol)
        if kept is not None:
            out.append(kept)
    return out


def _simplified(poly: np.ndarray, tol: float) -> np.ndarray | None:
    """``poly`` without repeated or collinear vertices, or None if degenerate."""
    for _ in range(2):
        keep = np.linalg.norm(poly - np.roll(poly, 1, axis=0), axis=1) > tol
        poly = poly[keep]
        if len(poly) < 3:
            return None
        before, after = np.roll(poly, 1, axis=0), np.roll(poly, -1, axis=0)
        bent = np.linalg.norm(np.cross(poly - before, after - poly), axis=1)
        poly = poly[bent > tol * np.linalg.norm(after - before, axis=1)]
        if len(poly) < 3:
            return None
    return poly


def _convex_pieces(poly: np.ndarray) -> list[np.ndarray]:
    """A convex polygon as quads and at most one triangle (fan of quads from vertex 0)."""
    pieces = []
    while len(poly) > 4:
        pieces.append(poly[:4])
        poly = np.concatenate([poly[:1], poly[3:]])
    pieces.append(poly)
    return pieces


# --------------------------------------------------------------------------------------
# Refinement into panels
# --------------------------------------------------------------------------------------
def _length(d: np.ndarray, stretch: float) -> float:
    """Length of the vector d with its z component scaled by ``stretch``."""
    return math.sqrt(d[0] ** 2 + d[1] ** 2 + (stretch * d[2]) ** 2)


def _refine_triangle(tri: np.ndarray, size: float, stretch: float = 1.0) -> np.ndarray:
    """(P, 4, 3) panels of a triangle, on an n x n barycentric grid.

    The grid runs along the two edges at the corner facing the longest edge: parallelogram
    quads whose sides are at most ``size`` (as a quad's), and n triangles (last corner
    repeated) along the longest edge; n = ceil(second longest edge / size).
    """
    lengths = [_length(tri[(k + 2) % 3] - tri[(k + 1) % 3], stretch) for k in range(3)]
    k = int(np.argmax(lengths))  # corner facing the longest edge
    a, b, c = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]  # same orientation
    n = max(1, math.ceil(sorted(lengths)[1] / size - 1e-9))
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    i, j = i.ravel(), j.ravel()

    def point(ii, jj):
        return a + (ii / n)[:, None] * (b - a) + (jj / n)[:, None] * (c - a)

    quad = i + j <= n - 2
    qi, qj = i[quad], j[quad]
    quads = np.stack([point(qi, qj), point(qi + 1, qj), point(qi + 1, qj + 1),
                      point(qi, qj + 1)], axis=1)
    ti = np.arange(n)
    tj = n - 1 - ti
    tris = np.stack([point(ti, tj), point(ti + 1, tj), point(ti, tj + 1),
                     point(ti, tj + 1)], axis=1)
    return np.concatenate([quads, tris])


def _refine_quad(quad: np.ndarray, size: float, stretch: float = 1.0) -> np.ndarray:
    """(P, 4, 3) panels of a quad: an nu x nv bilinear grid (counts from the longer edges)."""
    p0, p1, p2, p3 = quad
    nu = max(1, math.ceil(max(_length(p1 - p0, stretch), _length(p2 - p3, stretch)) / size
                          - 1e-9))
    nv = max(1, math.ceil(max(_length(p3 - p0, stretch), _length(p2 - p1, stretch)) / size
                          - 1e-9))
    u = np.linspace(0.0, 1.0, nu + 1)[:, None, None]
    v = np.linspace(0.0, 1.0, nv + 1)[None, :, None]
    grid = (p0 * (1 - u) * (1 - v) + p1 * u * (1 - v) + p2 * u * v + p3 * (1 - u) * v)
    return np.stack([grid[:-1, :-1], grid[1:, :-1], grid[1:, 1:], grid[:-1, 1:]],
                    axis=2).reshape(-1, 4, 3)


def _refine(polygons: list[np.ndarray], size: float, stretch: float = 1.0) -> np.ndarray:
    """(P, 4, 3) panels (triangles with their last corner repeated) of convex polygons.

    Edges are at most ``size`` long, measured with their z component times ``stretch``.
    """
    panels = [np.empty((0, 4, 3))]
    for poly in polygons:
        for piece in _convex_pieces(poly):
            refine = _refine_triangle if len(piece) == 3 else _refine_quad
            panels.append(refine(piece, size, stretch))
    return np.concatenate(panels)


# --------------------------------------------------------------------------------------
# Waterplane sections and the lid
# --------------------------------------------------------------------------------------
def _section_loops(polygons: list[np.ndarray], z: float, tol: float) -> list[np.ndarray]:
    """Closed loops (k, 2) bounding the part of the surface below ``z`` at height ``z``.

    The polygons must have been split at ``z``; the loops are the once-used edges lying on
    z, chained in the polygons' direction.
    """
    below = [p for p in polygons if np.all(p[:, 2] <= z + tol)]
    if not below:
        return []
    points = np.concatenate(below)
    ids = np.unique(np.round(points / tol).astype(np.int64), axis=0, return_inverse=True)[1]
    ids = ids.ravel()
    edges, start = [], 0
    for p in below:
        k = np.arange(len(p))
        idx = ids[start:start + len(p)]
        on = np.abs(p[:, 2] - z) <= tol
        edges += [(idx[i], idx[(i + 1) % len(p)]) for i in k if on[i] and on[(i + 1) % len(p)]]
        start += len(p)
    directed = set(edges)
    nxt = {a: b for a, b in edges if (b, a) not in directed}
    loops = []
    while nxt:
        first, chain = next(iter(nxt)), []
        node = first
        while node in nxt:
            chain.append(node)
            node = nxt.pop(node)
        if node == first and len(chain) >= 3:
            loops.append(points[[np.flatnonzero(ids == n)[0] for n in chain], :2])
        else:
            LOG.warning("open section chain of %d edges at z = %.4g m ignored (mesh not "
                        "watertight there?)", len(chain), z)
    return loops


def _lowest_lid_position(loops: list[np.ndarray], omega_max: float, g: float) -> float:
    """Capytaine's ``lowest_lid_position`` from the waterline loops (-inf: no constraint).

    Per loop, the lid's first irregular frequency (a rectangular tank of the loop's spans)
    reaches omega_max at depth arctanh(pi g p / omega^2) / (pi p), p = hypot(1/Lx, 1/Ly);
    times 0.9 as a margin.
    """
    z = -math.inf
    for loop in loops:
        span = np.ptp(loop, axis=0)
        p = math.hypot(1.0 / span[0], 1.0 / span[1])
        arg = math.pi * g * p / omega_max**2
        if arg < 1.0:
            z = max(z, -math.atanh(arg) / (math.pi * p))
    return 0.9 * z


def _lid_level(polygons: list[np.ndarray], z_low: float, draft: float) -> float:
    """Height of the lid: LID_FRACTION x z_low, at most half the draft deep.

    An existing vertex level within 15 % of |z_low| is taken instead (no thin split row).
    """
    target = max(LID_FRACTION * z_low, -0.5 * draft)
    levels = np.unique(np.round(np.concatenate(polygons)[:, 2], 12))
    near = levels[(np.abs(levels - target) <= 0.15 * abs(z_low)) & (levels >= z_low)
                  & (levels < 0.0)]
    if near.size:
        return float(near[np.argmin(np.abs(near - target))])
    return target


def _point_in_loops(points: np.ndarray, loops: list[np.ndarray]) -> np.ndarray:
    """(N,) bool, points (N, 2) inside an odd number of loops (crossing number)."""
    inside = np.zeros(len(points), dtype=bool)
    for loop in loops:
        a, b = loop, np.roll(loop, -1, axis=0)
        px, py = points[:, 0:1], points[:, 1:2]
        straddle = (a[:, 1] > py) != (b[:, 1] > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            x_cross = a[:, 0] + (py - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
        inside ^= (np.sum(straddle & (px < x_cross), axis=1) % 2).astype(bool)
    return inside


def _grid_lines(lo: float, hi: float, size: float, symmetric: bool) -> np.ndarray:
    """Grid coordinates over [lo, hi], spacing <= size, with a line at 0 if symmetric."""
    n = max(1, math.ceil((hi - lo) / size - 1e-9))
    if symmetric and n % 2:
        n += 1
    return np.linspace(lo, hi, n + 1)


def _lid_cell(cell: np.ndarray, loops: list[np.ndarray], z: float, tol: float,
              depth: int = 0) -> list[np.ndarray]:
    """Lid polygons (k, 3) of one rectangular cell (4, 2): the cell clipped to each loop.

    A non-convex piece is split into 2 x 2 sub-cells (3 levels at most, then dropped).
    """
    (x0, y0), (x1, y1) = cell.min(axis=0), cell.max(axis=0)
    pieces = []
    for loop in loops:
        poly = [np.column_stack([loop, np.full(len(loop), z)])]
        for normal, offset in (((1, 0, 0), x1), ((-1, 0, 0), -x0), ((0, 1, 0), y1),
                               ((0, -1, 0), -y0)):
            poly = _clip(poly, normal, offset, tol)  # any simple polygon: one piece
        pieces += poly
    out = []
    for piece in pieces:
        if _is_convex(piece, np.array([0.0, 0.0, 1.0])):
            out.append(piece)
        elif depth < 3:
            xm, ym = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            for a, b, c, d in ((x0, xm, y0, ym), (xm, x1, y0, ym), (x0, xm, ym, y1),
                               (xm, x1, ym, y1)):
                sub = np.array([[a, c], [b, c], [b, d], [a, d]])
                out += _lid_cell(sub, [piece[:, :2]], z, tol, depth + 1)
    return out


def _lid_polygons(loops: list[np.ndarray], z: float, size: float, sym_x: bool, sym_y: bool,
                  tol: float) -> list[np.ndarray]:
    """Coarse lid polygons over the loops' interior at height z, normals down.

    A grid of ``size`` cells aligned with the loops' bounding box (and with x = 0 / y = 0
    when symmetric), clipped to the loops; only the x <= 0 / y <= 0 part when symmetric.
    """
    pts = np.concatenate(loops)
    xs = _grid_lines(pts[:, 0].min(), pts[:, 0].max(), size, sym_x)
    ys = _grid_lines(pts[:, 1].min(), pts[:, 1].max(), size, sym_y)
    xs = xs[xs <= tol] if sym_x else xs
    ys = ys[ys <= tol] if sym_y else ys
    ccw = [lp if _signed_area(lp) > 0 else lp[::-1] for lp in loops]
    edges = np.concatenate([np.stack([lp, np.roll(lp, -1, axis=0)], axis=1) for lp in ccw])
    emin, emax = edges.min(axis=1), edges.max(axis=1)
    out = []
    for i in range(len(xs) - 1):
        for j in range(len(ys) - 1):
            cell = np.array([[xs[i], ys[j]], [xs[i + 1], ys[j]], [xs[i + 1], ys[j + 1]],
                             [xs[i], ys[j + 1]]])
            touches = np.any((emin[:, 0] <= xs[i + 1] + tol) & (emax[:, 0] >= xs[i] - tol)
                             & (emin[:, 1] <= ys[j + 1] + tol) & (emax[:, 1] >= ys[j] - tol))
            if touches:
                out += _lid_cell(cell, ccw, z, tol)
            elif _point_in_loops(cell.mean(axis=0)[None], ccw)[0]:
                out.append(np.column_stack([cell, np.full(4, z)]))
    return [p[::-1] for p in out]  # clockwise seen from above: normals down


def _signed_area(loop: np.ndarray) -> float:
    """Signed area of a 2-D loop (> 0 counter-clockwise)."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# --------------------------------------------------------------------------------------
# The panel mesh
# --------------------------------------------------------------------------------------
def immersed_panels(vertices, faces, *, draft_offset: float, omega_max: float,
                    panel_size: float | None = None, lid_panel_size: float | None = None,
                    vertical_stretch: float = VERTICAL_STRETCH, gravity: float = 9.81,
                    lid: bool = True, symmetry: bool = True,
                    shortest_wavelength: float = math.inf) -> dict:
    """Panels of the immersed hull and of its interior lid, in the calm-water frame.

    Args:
        vertices: (V, 3) m, body frame.
        faces: (F, 3) vertex indices, outward normals, closed mesh.
        draft_offset: body-frame z of the calm-water plane.
        omega_max: highest frequency solved (the lid's own irregular frequencies stay above).
        panel_size: largest hull panel edge, m; default :func:`default_panel_size`.
        lid_panel_size: largest lid panel edge, m; default ``panel_size``.
        vertical_stretch: hull edges are measured with their z component times this.
        gravity: m/s^2.
        lid: False for no lid.
        symmetry: use the y = 0 / x = 0 reflection symmetries when the mesh has them.
        shortest_wavelength: m, for the default panel size.

    Returns:
        dict: ``hull`` and ``lid`` (P, 4, 3) panels (triangles repeat their last corner) of
        the part x <= 0 and/or y <= 0 when ``sym_x`` / ``sym_y``; ``z_lid`` (calm-water
        frame, nan without lid); ``z_lowest_lid``; ``panel_size``; ``sym_x``, ``sym_y``.
    """
    v = np.asarray(vertices, dtype=float) - np.array([0.0, 0.0, draft_offset])
    f = np.asarray(faces, dtype=np.int64)
    tol = REL_TOL * float(np.ptp(v, axis=0).max())
    sym_y = symmetry and mirror_symmetric(v, f, 1)
    sym_x = symmetry and mirror_symmetric(v, f, 0)
    wet = [p for p in _clip(_merge_coplanar_pairs(v, f), (0, 0, 1), 0.0, tol)
           if np.any(p[:, 2] < -tol)]  # a face lying on the calm water is not wetted
    if not wet:
        raise ValueError("the hull is entirely above the calm water (check draft_offset)")
    draft = -float(np.concatenate(wet)[:, 2].min())
    z_low = _lowest_lid_position(_section_loops(wet, 0.0, tol), omega_max, gravity)
    z_lid = _lid_level(wet, z_low, draft) if lid and z_low > -math.inf else math.nan
    size = (default_panel_size(np.ptp(v, axis=0), z_lid, draft, shortest_wavelength)
            if panel_size is None else panel_size)
    lid_polys = []
    if not math.isnan(z_lid):
        above = _clip(wet, (0, 0, -1), -z_lid, tol)
        wet = _clip(wet, (0, 0, 1), z_lid, tol) + [  # a face on z_lid only once
            p for p in above if np.any(np.abs(p[:, 2] - z_lid) > tol)]
        lid_polys = _lid_polygons(_section_loops(wet, z_lid, tol), z_lid,
                                  lid_panel_size or size, sym_x, sym_y, tol)
    for flag, axis in ((sym_y, (0, 1, 0)), (sym_x, (1, 0, 0))):
        if flag:
            wet = _clip(wet, axis, 0.0, tol)
    return dict(hull=_refine(wet, size, vertical_stretch),
                lid=_refine(lid_polys, lid_panel_size or size), z_lid=z_lid,
                z_lowest_lid=z_low, panel_size=size, sym_x=sym_x, sym_y=sym_y)


def indexed(panels: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (V, 3), faces (P, 4)) of (P, 4, 3) panels, coincident corners merged."""
    flat = panels.reshape(-1, 3)
    _, first, inverse = np.unique(np.round(flat / tol).astype(np.int64), axis=0,
                                  return_index=True, return_inverse=True)
    return flat[first], inverse.ravel().reshape(-1, 4)
