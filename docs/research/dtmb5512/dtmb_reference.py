#!/usr/bin/env python3
"""Potential-flow coefficients of the DTMB 5512 model (IIHR, 1:46.6, Lpp 3.048 m), with
boatsim's own Capytaine wrapper (boat_dynamics.tools.bem), as
tests/data/hydro/journee_wigley_reference.py does for Journee's Wigley hulls.

Hull: dtmb5512.stl (make_mesh.py: FRyDoM's DTMB5512_IIHR_full.obj cut at a flat deck 0.08 m
above the calm water and capped). boatsim's body frame: FLU, origin at the bounding-box centre,
the calm water at body z = WATERLINE.

Mass properties: mass = rho V of the mesh (fresh water), centre of mass at the centre of
buoyancy's x (trim-free), 0.030 m above the calm water (FRyDoM: COG z = 0.03 m in the mesh frame;
VCG 0.162 m above the keel at T 0.132 m), radii of gyration from FRyDoM's bench_DTMB5512.cpp
(mass 86.0 kg; Ixx 1.98, Iyy 53.88, Izz 49.99 kg m^2: k_xx 0.152 m, k_yy 0.792 m = 0.260 L,
k_zz 0.762 m = 0.250 L), scaled to this mass.

Fresh water 1000 kg/m^3, g 9.81, deep. 32 frequencies 1.5-16 rad/s; directions 0-180 deg by
45; hull panels of 0.08 m (the mesh's own triangles are finer: ~4,100 hull panels) and the
default interior lid.

Usage:
    OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 PYTHONPATH=/work/main/src:/tmp/dtmb/overlay \
        /tmp/wigley/venv/bin/python dtmb_reference.py
"""

import logging
import resource
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
STL = HERE / "dtmb5512.stl"
OUT = HERE / "dtmb5512.npz"
RHO, G = 1000.0, 9.81
LPP = 3.048
VCG_ABOVE_WL = 0.030
FRYDOM_MASS, FRYDOM_I = 86.0, (1.98, 53.88, 49.99)
PANEL = 0.08
OMEGAS = np.linspace(1.5, 16.0, 32)


def model():
    """(vertices, faces, waterline, mass, com, (6, 6) inertia) in boatsim's body frame."""
    import capytaine as cpt

    from boat_dynamics.physics.hull import load_mesh

    hm = load_mesh(str(STL))
    v, f = np.asarray(hm.vertices), np.asarray(hm.faces)
    # load_mesh centres the bounding box: the calm water (OBJ z = 0) is at body z =
    # -(the OBJ bounding-box centre's z)
    import trimesh
    raw = trimesh.load(str(STL), force="mesh", process=False)
    waterline = -0.5 * float(raw.bounds[0, 2] + raw.bounds[1, 2])
    immersed = cpt.Mesh(v - [0.0, 0.0, waterline], f).immersed_part()
    mass = RHO * float(immersed.volume)
    cob = np.asarray(immersed.center_of_buoyancy, dtype=float)
    com = np.array([cob[0], 0.0, waterline + VCG_ABOVE_WL])
    radii2 = np.array(FRYDOM_I) / FRYDOM_MASS
    inertia = np.diag([mass] * 3 + list(mass * radii2))
    return v, f, waterline, mass, com, inertia


def main() -> None:
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s")
    from boat_dynamics.tools import bem

    v, f, waterline, mass, com, inertia = model()
    print("waterline body z", waterline, "mass", mass, "com", com, "inertia diag",
          np.diag(inertia), flush=True)
    plan, *_ = bem.plan_hull(v, f, draft_offset=waterline, omegas=OMEGAS,
                             directions=np.radians([0.0, 45.0, 90.0, 135.0, 180.0]),
                             panel_size=PANEL)
    print(plan.describe(), flush=True)
    if "--plan" in sys.argv:
        return
    t0 = time.process_time()
    out = bem.solve_hull(v, f, draft_offset=waterline, mass=mass, center_of_mass=com,
                         inertia_matrix=inertia, water_density=RHO, gravity=G,
                         omegas=OMEGAS, directions=np.radians([0.0, 45.0, 90.0, 135.0, 180.0]),
                         panel_size=PANEL,
                         description="DTMB 5512 (IIHR 1:46.6 model, FRyDoM's "
                                     "DTMB5512_IIHR_full.obj, deck at +0.08 m)")
    bem.write(OUT, out)
    cpu = time.process_time() - t0
    print("panels", int(out["panels"]), "lid", int(out["lid_panels"]), "lid_z",
          float(out["lid_z"]), "omega_resolved", float(out["omega_resolved"]),
          "wall s", float(out["solve_seconds"]), "cpu s", cpu,
          "max RSS MB", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, flush=True)


if __name__ == "__main__":
    main()
