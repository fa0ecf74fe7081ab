"""Print the solved file's headline numbers: A_inf diagonals, narrow peaks, lid, panels."""
import sys
import numpy as np
from boat_dynamics.physics.hydro import load_coefficients, narrow_peaks

path = sys.argv[1]
h = load_coefficients(path)
d = np.load(path)
print("hull", d["hull"], "panels", d["panels"], "lid", d["lid_panels"], "lid_z", d["lid_z"],
      "waterline_z", d["waterline_z"], "panel_size", d["panel_size"], "solve_s", d["solve_seconds"])
print("omega", h.omega[0], h.omega[-1], len(h.omega), "dirs", np.degrees(h.directions))
print("m", h.inertia_matrix[0, 0], "A_inf diag", np.round(np.diag(h.added_mass_inf), 3))
print("A_zero diag", np.round(np.diag(d["added_mass_zero"]), 3))
print("m + A11 =", h.inertia_matrix[0, 0] + h.added_mass_inf[0, 0], " A22 =", h.added_mass_inf[1, 1])
print("C diag", np.round(np.diag(h.hydrostatic_stiffness), 2))
for p in narrow_peaks(h):
    print(f"  peak {p.omega:.4f} {p.dof:6s} {p.quantity:10s} ratio {p.ratio:.2f}")
print("max B diag", np.round(np.abs(np.diagonal(h.radiation_damping, axis1=1, axis2=2)).max(0), 1))
print("argmax", h.omega[np.abs(np.diagonal(h.radiation_damping, axis1=1, axis2=2)).argmax(0)].round(3))
