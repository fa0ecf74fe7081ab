"""DTMB 5512 hull for boatsim: FRyDoM's DTMB5512_IIHR_full.obj (open at the sheer line) cut
at a flat deck z = DECK above the calm waterline and capped (ear clipping): a closed,
watertight, outward-oriented STL.

OBJ frame: x forward (origin near midships), y to port, z up, calm waterline at z = 0.
"""
import numpy as np
import trimesh

DECK = 0.08  # m above the calm water (the open sheer line lies at z >= 0.085)
SRC = "/tmp/pitchdata/frydom/DTMB5512_IIHR_full.obj"
OUT = "/tmp/dtmb/dtmb5512.stl"


def boundary_loops(mesh):
    e = mesh.edges  # directed, per face
    key = np.sort(e, axis=1)
    u, inv, c = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    b = e[c[inv.ravel()] == 1]
    nxt = {int(a): int(bb) for a, bb in b}
    loops, seen = [], set()
    for s in nxt:
        if s in seen:
            continue
        loop, v = [], s
        while v not in seen:
            seen.add(v); loop.append(v); v = nxt[v]
        loops.append(loop)
    return loops


def ear_clip(pts2):
    """Triangles (index triples into pts2) of a simple CCW polygon."""
    idx = list(range(len(pts2)))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(idx) > 3 and guard < 100000:
        guard += 1
        n = len(idx)
        best = None
        for k in range(n):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % n]
            a, b, c = pts2[i0], pts2[i1], pts2[i2]
            if cross(a, b, c) <= 1e-14:
                continue
            inside = False
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                p = pts2[j]
                if cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0:
                    inside = True
                    break
            if not inside:
                # prefer the ear with the best-shaped triangle
                ab, bc, ca = np.linalg.norm(b - a), np.linalg.norm(c - b), np.linalg.norm(a - c)
                q = cross(a, b, c) / max(ab * ab + bc * bc + ca * ca, 1e-30)
                if best is None or q > best[0]:
                    best = (q, k)
        if best is None:
            raise RuntimeError("ear clipping failed")
        k = best[1]
        tris.append((idx[k - 1], idx[k], idx[(k + 1) % n]))
        del idx[k]
    tris.append(tuple(idx))
    return tris


def clip_below(v, f, zc):
    """The part of the triangle mesh with z <= zc; edge crossings computed once per edge."""
    verts = [p for p in v]
    cross_id = {}

    def crossing(a, b):
        key = (min(a, b), max(a, b))
        if key not in cross_id:
            p, q = v[key[0]], v[key[1]]
            t = (zc - p[2]) / (q[2] - p[2])
            r = p + t * (q - p)
            r[2] = zc
            verts.append(r)
            cross_id[key] = len(verts) - 1
        return cross_id[key]

    faces = []
    for tri in f:
        below = [v[i][2] <= zc for i in tri]
        if all(below):
            faces.append(list(tri)); continue
        if not any(below):
            continue
        poly = []
        for k in range(3):
            a, b = int(tri[k]), int(tri[(k + 1) % 3])
            if v[a][2] <= zc:
                poly.append(a)
            if (v[a][2] <= zc) != (v[b][2] <= zc):
                poly.append(crossing(a, b))
        for k in range(1, len(poly) - 1):
            faces.append([poly[0], poly[k], poly[k + 1]])
    return trimesh.Trimesh(np.array(verts), np.array(faces), process=False)


def main():
    m = trimesh.load(SRC, force="mesh", process=False)
    m.merge_vertices()
    cut = clip_below(np.asarray(m.vertices), np.asarray(m.faces), DECK)
    cut.merge_vertices(digits_vertex=9)
    cut.update_faces(cut.nondegenerate_faces(height=1e-10))
    cut.remove_unreferenced_vertices()
    loops = boundary_loops(cut)
    print("boundary loops", [len(l) for l in loops])
    assert len(loops) == 1
    loop = np.array(loops[0])
    v = np.asarray(cut.vertices)
    assert np.allclose(v[loop, 2], DECK, atol=1e-9)
    pts = v[loop, :2]
    # the deck's normal must point up: the boundary as seen by the hull faces runs one way;
    # triangulate CCW (seen from above) and keep that order.
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    order = loop if area > 0 else loop[::-1]
    tris = ear_clip(v[order, :2])
    deck = np.array([[order[a], order[b], order[c]] for a, b, c in tris])
    closed = trimesh.Trimesh(v, np.vstack([cut.faces, deck]), process=False)
    if not closed.is_winding_consistent:
        closed = trimesh.Trimesh(v, np.vstack([cut.faces, deck[:, ::-1]]), process=False)
    print("triangles", len(closed.faces), "watertight", closed.is_watertight,
          "winding", closed.is_winding_consistent, "volume", closed.volume)
    print("bounds", closed.bounds.round(4).tolist())
    closed.export(OUT)


if __name__ == "__main__":
    main()
