#!/usr/bin/env python3
"""Potential-flow reference of a ship-like hull: a closed Wigley-type hull, with Capytaine.

Hull (body frame FLU, origin at the bounding-box centre): length 4 m, beam 1 m, height 1 m,
y = B/2 (1 - (2x/L)^2) (1 - ((z - H/2)/H)^2) from the keel line (z = -H/2) to a flat deck
(z = H/2); 24 x 8 quads a side, 814 triangles (`wigley_4x1x1.stl`). Floating with the calm
water at body z = 0.1 m (draft 0.6 m): mass rho V = 784.5 kg, centre of mass above the centre
of buoyancy at z = -0.1 m, moments of inertia 0.3 m, 1.2 m, 1.3 m (kg m^2 per kg). Solved
with boatsim's own solver (`boat_dynamics.tools.bem.solve_hull`, as `boatsim hydro` does),
panels of 0.1 m: 2,928 hull + 444 lid panels, 40 frequencies 0.5-12 rad/s, 5 directions;
about 3 minutes on one core.

Usage (the bem extra: `make bem`):

    .venv/bin/python tests/data/hydro/wigley_reference.py
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def wigley(length=4.0, beam=1.0, height=1.0, nx=24, nz=8):
    """(V, 3) vertices and (F, 3) outward triangles of the closed hull."""
    xs, zs = np.linspace(-length / 2, length / 2, nx + 1), np.linspace(-height / 2, height / 2,
                                                                        nz + 1)
    x, z = np.meshgrid(xs, zs, indexing="ij")
    y = beam / 2 * (1 - (2 * x / length) ** 2) * (1 - ((z - height / 2) / height) ** 2)
    verts, index, faces = [], {}, []

    def vid(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(verts)
            verts.append(p)
        return index[key]

    for side in (1, -1):
        p = np.stack([x, side * y, z], axis=-1)
        for i in range(nx):
            for k in range(nz):
                a, b, c, d = (vid(p[i, k]), vid(p[i + 1, k]), vid(p[i + 1, k + 1]),
                              vid(p[i, k + 1]))
                tris = ([a, b, c], [a, c, d]) if i < nx // 2 else ([a, b, d], [b, c, d])
                if side > 0:
                    tris = [t[::-1] for t in tris]
                faces += [t for t in tris if len(set(t)) == 3]
    for i in range(nx):  # the deck, normal up
        a = vid(np.array([x[i, nz], -y[i, nz], z[i, nz]]))
        b = vid(np.array([x[i + 1, nz], -y[i + 1, nz], z[i + 1, nz]]))
        c = vid(np.array([x[i + 1, nz], y[i + 1, nz], z[i + 1, nz]]))
        d = vid(np.array([x[i, nz], y[i, nz], z[i, nz]]))
        faces += [t for t in ([a, b, c], [a, c, d]) if len(set(t)) == 3]
    v = np.array(verts)
    return v - 0.5 * (v.max(axis=0) + v.min(axis=0)), np.array(faces)


def main() -> None:
    import capytaine as cpt
    import trimesh

    from boat_dynamics.tools import bem

    v, f = wigley()
    trimesh.Trimesh(v, f, process=False).export(HERE / "wigley_4x1x1.stl")
    waterline = 0.1
    immersed = cpt.Mesh(v - [0, 0, waterline], f).immersed_part()
    mass = 1025.0 * immersed.volume
    com = np.array([*immersed.center_of_buoyancy[:2], -0.1])
    inertia = np.diag([mass] * 3 + [0.3 * mass, 1.2 * mass, 1.3 * mass])
    out = bem.solve_hull(v, f, draft_offset=waterline, mass=mass, center_of_mass=com,
                         inertia_matrix=inertia, panel_size=0.1, description="wigley 4x1x1")
    bem.write(HERE / "wigley_4x1x1.npz", out)


if __name__ == "__main__":
    main()
