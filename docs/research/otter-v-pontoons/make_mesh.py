#!/usr/bin/env python3
"""Write /tmp/otter2/otter_v.stl: an Otter-like catamaran with V-bottomed prismatic pontoons.

Each pontoon: length 2.0 m, cross-section a pentagon: keel line at z = -0.2 m (width 0),
sides widening linearly to the pontoon beam 0.25 m at z = 0.0, vertical sides from z = 0.0 up
to the deck at z = +0.2 m; flat transoms at x = +-1.0 m; centre lines at y = +-0.395 m
(Fossen's Otter: L 2.0 m, pontoon beam 0.25 m, pontoon centres 0.395 m off the centre line).
At 80 kg in sea water (1025 kg/m^3) it floats at z = -0.0233 (draft 0.177 m).
Usage: OPENBLAS_NUM_THREADS=1 /work/main/.venv/bin/python /tmp/otter2/make_mesh.py
"""

from pathlib import Path

import numpy as np
import trimesh

LENGTH, PONTOON_BEAM, OFFSET = 2.0, 0.25, 0.395
KEEL_Z, CHINE_Z, DECK_Z = -0.2, 0.0, 0.2
MASS, RHO = 80.0, 1025.0


def pontoon(y0: float) -> trimesh.Trimesh:
    """One prismatic pontoon (extruded pentagon) centred on y = y0."""
    half = PONTOON_BEAM / 2
    # Section (y, z), counter-clockwise seen from +x (bow looking aft... orientation fixed below).
    section = np.array([[0.0, KEEL_Z], [half, CHINE_Z], [half, DECK_Z],
                        [-half, DECK_Z], [-half, CHINE_Z]])
    n = len(section)
    aft = np.column_stack([np.full(n, -LENGTH / 2), section[:, 0] + y0, section[:, 1]])
    fwd = np.column_stack([np.full(n, LENGTH / 2), section[:, 0] + y0, section[:, 1]])
    vertices = np.vstack([aft, fwd])
    faces = []
    for i in range(n):  # sides: quads split in two
        j = (i + 1) % n
        faces += [[i, j, n + j], [i, n + j, n + i]]
    for k in range(1, n - 1):  # end caps: fans (the pentagon is convex)
        faces.append([0, k + 1, k])              # aft
        faces.append([n, n + k, n + k + 1])      # forward
    mesh = trimesh.Trimesh(vertices, np.array(faces), process=True)
    trimesh.repair.fix_normals(mesh)
    return mesh


def main() -> None:
    mesh = trimesh.util.concatenate([pontoon(s * OFFSET) for s in (1, -1)])
    assert mesh.is_watertight and mesh.is_volume and mesh.volume > 0
    out = Path(__file__).resolve().parent / "otter_v.stl"
    mesh.export(out)
    # Displaced volume below z = KEEL_Z + h (h <= 0.2): 2 pontoons x L x (1/2) (1.25 h) h.
    h = np.sqrt(MASS / RHO / (2 * LENGTH * 0.5 * (PONTOON_BEAM / (CHINE_Z - KEEL_Z))))
    z_w = KEEL_Z + h
    print(f"{out}: {len(mesh.faces)} faces, volume {mesh.volume:.5f} m^3, "
          f"bounds {mesh.bounds.tolist()}, is_volume {mesh.is_volume}")
    print(f"waterline at 80 kg (analytic): z = {z_w:.5f}, draft {h:.5f} m")


if __name__ == "__main__":
    main()
