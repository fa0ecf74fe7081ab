#!/usr/bin/env python3
"""Potential-flow coefficients of Journee's Wigley I and III models, with Capytaine.

Hull (J.M.J. Journee, "Experiments and calculations on four Wigley hullforms", Delft University
of Technology, Ship Hydromechanics Laboratory report 909, 1992, sec. 2, as quoted by
risingtideresearch/michell, crates/michell-seakeeping/examples/journee_wigley.rs, commit
14db901ddaedda992cb99dc71ee68fbe44a13785)::

    eta = (1 - zeta^2)(1 - xi^2)(1 + 0.2 xi^2) + alpha zeta^2 (1 - zeta^8)(1 - xi^2)^4
    xi = 2x/L, eta = 2y/B, zeta = z/d (z up from the waterline, -d <= z <= 0)

L 3 m, B 0.3 m, d 0.1875 m; alpha 1 (Wigley I) or 0 (III); k_yy 0.75 m; fresh water. Above the
waterline the sides go up vertically to a flat deck 0.1 m above it (not from the report: it
closes the mesh). The centre of mass at the height of the centre of buoyancy (KG is not in the
sources found; raising it 0.08 m changes the Fn 0.3 heave peak by 3 %); k_xx 0.35 B and
k_zz 0.25 L assumed (they do not enter head-sea heave and pitch). Body frame FLU, origin at
the bounding-box centre: the calm water at z = +0.04375 m.

The coefficients: 76 stations x 10 rows (3,798 triangles), panels of 0.045 m (Wigley I: 3,940
hull + 584 lid panels, 322 s of CPU; III: 3,376 + 612, 224 s), 40 frequencies 1.5-15 rad/s,
directions 0-180 deg by 45; a 2,292 + 772 panel mesh agrees within 0.7 %. The
simulation's hull: 24 x 4 (622 triangles), within 0.3 % of 32 x 6 in the towed RAOs.

Usage (the bem extra: `make bem`):

    .venv/bin/python tests/data/hydro/journee_wigley_reference.py
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
LENGTH, BEAM, DRAFT, FREEBOARD = 3.0, 0.3, 0.1875, 0.1
RHO, G, KYY = 1000.0, 9.81, 0.75
ALPHA = {"I": 1.0, "III": 0.0}


def half_breadth(x, z, alpha):
    """Journee's half-breadth y(x, z), m; vertical sides above the waterline (z > 0)."""
    xi, zeta = 2.0 * x / LENGTH, np.minimum(z, 0.0) / DRAFT
    eta = ((1 - zeta**2) * (1 - xi**2) * (1 + 0.2 * xi**2)
           + alpha * zeta**2 * (1 - zeta**8) * (1 - xi**2) ** 4)
    return 0.5 * BEAM * np.maximum(eta, 0.0)


def wigley(alpha, nx, nz, nz_dry=2):
    """(V, 3) vertices, (F, 3) outward triangles, and the calm water's body z."""
    xs = np.linspace(-LENGTH / 2, LENGTH / 2, nx + 1)
    zs = np.concatenate([np.linspace(-DRAFT, 0.0, nz + 1),
                         np.linspace(0.0, FREEBOARD, nz_dry + 1)[1:]])
    x, z = np.meshgrid(xs, zs, indexing="ij")
    y = half_breadth(x, z, alpha)
    top = len(zs) - 1
    verts, index, faces = [], {}, []

    def vid(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(verts)
            verts.append(p)
        return index[key]

    def quad(a, b, c, d, i, flip):
        # diagonals mirrored about x = 0: the mesh is fore-aft symmetric
        tris = ([a, b, c], [a, c, d]) if i < nx // 2 else ([a, b, d], [b, c, d])
        faces.extend(t[::-1] if flip else t for t in tris if len(set(t)) == 3)

    for side in (1, -1):
        p = np.stack([x, side * y, z], axis=-1)
        for i in range(nx):
            for k in range(top):
                quad(vid(p[i, k]), vid(p[i + 1, k]), vid(p[i + 1, k + 1]), vid(p[i, k + 1]),
                     i, side > 0)
    for i in range(nx):  # the deck, normal up
        quad(*(vid(np.array([x[j, top], s * y[j, top], z[j, top]]))
               for j, s in ((i, -1), (i + 1, -1), (i + 1, 1), (i, 1))), i, False)
    v = np.array(verts)
    centre = 0.5 * (v.max(axis=0) + v.min(axis=0))
    return v - centre, np.array(faces), -float(centre[2])


def main() -> None:
    import capytaine as cpt
    import trimesh

    from boat_dynamics.tools import bem

    for model, alpha in ALPHA.items():
        v, f, waterline = wigley(alpha, 76, 10)
        immersed = cpt.Mesh(v - [0.0, 0.0, waterline], f).immersed_part()
        mass = RHO * float(immersed.volume)
        com = np.array([0.0, 0.0, waterline + float(immersed.center_of_buoyancy[2])])
        inertia = np.diag([mass] * 3 + [mass * (0.35 * BEAM) ** 2, mass * KYY**2,
                                        mass * (0.25 * LENGTH) ** 2])
        out = bem.solve_hull(v, f, draft_offset=waterline, mass=mass, center_of_mass=com,
                             inertia_matrix=inertia, water_density=RHO, gravity=G,
                             omegas=np.linspace(1.5, 15.0, 40),
                             directions=np.radians([0.0, 45.0, 90.0, 135.0, 180.0]),
                             panel_size=0.045,
                             description=f"Journee (1992) Wigley {model}, 76 x 10")
        bem.write(HERE / f"journee_wigley_{model}.npz", out)
        coarse = wigley(alpha, 24, 4)
        trimesh.Trimesh(coarse[0], coarse[1], process=False).export(
            HERE / f"journee_wigley_{model}_24x4.stl")
        print(model, mass, com, float(out["solve_seconds"]))


if __name__ == "__main__":
    main()
