"""Local Capytaine re-solves on the coefficient file's own mesh (boatsim's bem code).

The panels are planned exactly as `boatsim hydro` planned the file: the scenario's hull at its
equilibrium, panel size 0.05 m, the lid placed for the file's omega_max (16.9706 rad/s; the lid
depth depends on the highest frequency, so a window solve must not plan for its own top).
Each window is then solved at the requested frequencies with bem._coefficients.

Run with the Capytaine venv:
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONDONTWRITEBYTECODE=1 \
  PYTHONPATH=/work/main/src:/tmp/otter2/overlay /tmp/wigley/venv/bin/python \
  /tmp/otter2/solve_mesh.py TAG wmin wmax step [TAG wmin wmax step ...]
  -> /tmp/otter2/solves/TAG.npz   (a TAG 'check' re-solves given grid omegas: TAG w1,w2,... - -)
"""
import sys
import time
from pathlib import Path

import numpy as np

from boat_dynamics.physics.model import hull_mesh
from boat_dynamics.physics.rigid_body import mass_matrix
from boat_dynamics.physics.scenario import load_scenario
from boat_dynamics.physics.tuning import equilibrium_height
from boat_dynamics.tools import bem

SCENARIO = "/tmp/otter2/otter_v.yaml"
FILE = "/tmp/otter2/hydro/hull_2x1.04x0.4_d0.177_e884bec0fcfc08bc.npz"
OUT = Path("/tmp/otter2/solves")


def main(args):
    OUT.mkdir(exist_ok=True)
    sc = load_scenario(SCENARIO)
    p = sc.boats[0].params
    z_eq = equilibrium_height(p)
    mesh = hull_mesh(p)
    ref = np.load(FILE)
    wmax = float(ref["omega"][-1])
    M = mass_matrix(p.mass, p.inertia, p.inertia_products)
    plan, panels, _, directions = bem.plan_hull(mesh.vertices, mesh.faces, draft_offset=-z_eq,
                                                gravity=p.gravity, omegas=np.array([1.0, wmax]),
                                                lid=True, panel_size=float(ref["panel_size"]))
    assert np.allclose(directions, ref["directions"])
    print("panels", plan.panels, plan.lid_panels, "z_lid", panels["z_lid"], "file lid_z",
          float(ref["lid_z"]), "file waterline", float(ref["waterline_z"]), "z_eq", z_eq,
          flush=True)
    assert plan.panels == int(ref["panels"]) and plan.lid_panels == int(ref["lid_panels"])
    assert abs(panels["z_lid"] - z_eq - float(ref["lid_z"])) < 1e-9
    cog = p.center_of_mass + np.array([0.0, 0.0, z_eq])
    env = dict(rho=p.water_density, g=p.gravity, water_depth=sc.sea.depth)
    for i in range(0, len(args), 4):
        tag, a, b, c = args[i:i + 4]
        if b == "-":
            omegas = np.array([float(x) for x in a.split(",")])
        else:
            wmin, wmax_, step = float(a), float(b), float(c)
            omegas = np.linspace(wmin, wmax_, int(round((wmax_ - wmin) / step)) + 1)
        t0, c0 = time.time(), time.process_time()
        out = bem._coefficients(panels, cog, p.mass, M, omegas, directions, env)
        out["center_of_mass"] = p.center_of_mass
        out["cpu_seconds"] = np.array(time.process_time() - c0)
        np.savez_compressed(OUT / f"{tag}.npz", **{k: np.asarray(v) for k, v in out.items()})
        print(tag, len(omegas), "points", f"wall {time.time() - t0:.1f} s",
              f"cpu {time.process_time() - c0:.1f} s", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
