"""Hydrostatic checks of /tmp/dtmb/dtmb5512.stl (OBJ frame: calm water z = 0) and the plan."""
import sys
import numpy as np
import capytaine as cpt
from boat_dynamics.physics.hull import load_mesh
from boat_dynamics.tools import bem
from boat_dynamics.tools.bem_mesh import mirror_symmetric

path = sys.argv[1] if len(sys.argv) > 1 else "/tmp/dtmb/dtmb5512.stl"
hm = load_mesh(path)
import trimesh
raw = trimesh.load(path, force="mesh", process=False)
lo, hi = raw.bounds
centre = 0.5 * (lo + hi)
print("boatsim load_mesh ok:", len(hm.faces), "triangles; bbox centre in OBJ frame", centre.round(5))
wl = -centre[2]  # body z of the calm water
print("calm water at body z =", round(wl, 6))
v, f = np.asarray(hm.vertices), np.asarray(hm.faces)
print("symmetric y:", mirror_symmetric(v, f, 1), " x:", mirror_symmetric(v, f, 0))
mesh = cpt.Mesh(v - [0, 0, wl], f)
imm = mesh.immersed_part()
V = float(imm.volume)
cob = np.array(imm.center_of_buoyancy) + [0, 0, wl]
print(f"V = {V:.5f} m^3, rho V = {1000*V:.2f} kg; CoB body {cob.round(4)}; CoB OBJ {(cob+centre-[0,0,0]).round(4) if False else (cob + [centre[0], centre[1], centre[2]]).round(4)}")
print(f"wetted area {float(imm.faces_areas.sum()):.4f} m^2")
# waterplane from a thin slice of the mesh vertices at z ~ 0: use the hydrostatic stiffness
body = cpt.FloatingBody(mesh=imm, dofs=cpt.rigid_body_dofs(rotation_center=(cob[0], 0, 0)),
                        center_of_mass=(cob[0], 0, 0), mass=1000 * V)
K = body.compute_hydrostatic_stiffness(rho=1000.0, g=9.81)
Awp = float(K.sel(influenced_dof="Heave", radiating_dof="Heave")) / (1000 * 9.81)
print(f"waterplane area {Awp:.4f} m^2 (Cwp = {Awp/(3.048*0.405):.3f} of Lpp x B), "
      f"C_B = {V/(3.048*0.405*0.132):.3f}")
print("hull x span below water:", imm.vertices[:, 0].min().round(4) + centre[0], imm.vertices[:, 0].max().round(4) + centre[0],
      " z min", (imm.vertices[:, 2].min()).round(4), " half-beam at WL",
      np.abs(imm.vertices[np.abs(imm.vertices[:, 2]) < 1e-6, 1]).max().round(4))
