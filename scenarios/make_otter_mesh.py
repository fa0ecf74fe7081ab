#!/usr/bin/env python3
"""Write scenarios/otter.stl: an Otter-like catamaran, two V-bottomed pontoons (trimesh).

Dimensions from the Maritime Robotics Otter USV as modelled by Fossen (2021, "Handbook of
marine craft hydrodynamics and motion control", 2nd ed.; PythonVehicleSimulator, otter.py):
length 2.0 m, pontoon beam 0.25 m, pontoon centres 0.395 m either side of the centre line.
Each pontoon is a pentagon extruded 2.0 m with flat transoms: the keel line at z = -0.2 m, the
sides widening to the pontoon beam at z = 0, vertical from there to the deck at z = +0.2 m
(boatsim's choice of section). At the Otter's 80 kg in sea water it floats at z = -0.0233 m,
drawing 0.177 m (the Otter draws about 0.2 m). Usage: ``.venv/bin/python
scenarios/make_otter_mesh.py``.
"""

from pathlib import Path

import numpy as np
import trimesh

LENGTH, PONTOON_BEAM, OFFSET = 2.0, 0.25, 0.395
KEEL_Z, CHINE_Z, DECK_Z = -0.2, 0.0, 0.2


def pontoon(y0: float) -> trimesh.Trimesh:
    """One prismatic pontoon (an extruded pentagon) centred on y = ``y0`` m."""
    half = PONTOON_BEAM / 2
    section = np.array([[0.0, KEEL_Z], [half, CHINE_Z], [half, DECK_Z],
                        [-half, DECK_Z], [-half, CHINE_Z]])
    n = len(section)
    aft = np.column_stack([np.full(n, -LENGTH / 2), section[:, 0] + y0, section[:, 1]])
    fwd = np.column_stack([np.full(n, LENGTH / 2), section[:, 0] + y0, section[:, 1]])
    faces = []
    for i in range(n):  # the sides: quadrilaterals split in two
        j = (i + 1) % n
        faces += [[i, j, n + j], [i, n + j, n + i]]
    for k in range(1, n - 1):  # the transoms: fans (the pentagon is convex)
        faces += [[0, k + 1, k], [n, n + k, n + k + 1]]
    mesh = trimesh.Trimesh(np.vstack([aft, fwd]), np.array(faces), process=True)
    trimesh.repair.fix_normals(mesh)
    return mesh


def main() -> None:
    mesh = trimesh.util.concatenate([pontoon(side * OFFSET) for side in (1, -1)])
    assert mesh.is_watertight and mesh.is_volume
    mesh.export(Path(__file__).resolve().parent / "otter.stl")


if __name__ == "__main__":
    main()
