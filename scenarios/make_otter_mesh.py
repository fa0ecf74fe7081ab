#!/usr/bin/env python3
"""Write scenarios/otter.stl: an Otter-like catamaran, two box pontoons (trimesh).

Dimensions from the Maritime Robotics Otter USV as modelled by Fossen (2021, "Handbook of
marine craft hydrodynamics and motion control", 2nd ed.; PythonVehicleSimulator, otter.py):
length 2.0 m, overall beam 1.08 m, pontoon beam 0.25 m, pontoon centres 0.395 m either side of
the centre line. The pontoon height, 0.4 m, is boatsim's choice. Box pontoons have a block
coefficient of 1 where the Otter's are 0.4, so at the Otter's 80 kg they draw 0.08 m, not
0.2 m. Usage: ``.venv/bin/python scenarios/make_otter_mesh.py``.
"""

from pathlib import Path

import trimesh

LENGTH, PONTOON_BEAM, HEIGHT, OFFSET = 2.0, 0.25, 0.4, 0.395


def main() -> None:
    pontoons = [trimesh.creation.box(extents=[LENGTH, PONTOON_BEAM, HEIGHT])
                .apply_translation([0.0, side * OFFSET, 0.0]) for side in (1, -1)]
    mesh = trimesh.util.concatenate(pontoons)
    assert mesh.is_watertight and mesh.is_volume
    mesh.export(Path(__file__).resolve().parent / "otter.stl")


if __name__ == "__main__":
    main()
