"""Potential flow alone at every data point (cheap): the file's mass properties, k_yy 0.25 L
instead of 0.26 L, and (at speed) without the simulation's U L radiation terms."""
import math

import numpy as np

from boat_dynamics.physics.hydro import load_coefficients
from boat_dynamics.physics.seakeeping import encounter_frequency, potential_flow_rao
from run_points import LENGTH, G, NPZ, measured

z = np.load(NPZ)
hydro = load_coefficients(str(NPZ))
M = np.array(z["inertia_matrix"], float)
mass = float(z["mass"])
M25 = M.copy()
M25[4, 4] = mass * (0.25 * LENGTH) ** 2
print(f"mass {mass:.2f} kg, Iyy {M[4, 4]:.2f} (k_yy {math.sqrt(M[4, 4] / mass):.4f} m); "
      f"0.25 L: {M25[4, 4]:.2f}")
print("| Fn | lambda/L | omega_e | meas heave | PF | PF kyy .25L | PF no U-terms |"
      " meas pitch | PF pitch | PF pitch kyy .25L |")
print("|---|---|---|---|---|---|---|---|---|---|")
for fn, lam, heave, pitch in measured():
    k = 2 * math.pi / (lam * LENGTH)
    w = math.sqrt(G * k)
    U = fn * math.sqrt(G * LENGTH)
    we = encounter_frequency(w, k, U, math.pi)
    held = (0, 1, 5) if U else ()
    a = potential_flow_rao(hydro, M, w, math.pi, encounter=we, speed=U, held=held)
    b = potential_flow_rao(hydro, M25, w, math.pi, encounter=we, speed=U, held=held)
    c = potential_flow_rao(hydro, M, w, math.pi, encounter=we, speed=0.0, held=held)
    ps = f"{pitch:.3f}" if pitch is not None else "-"
    print(f"| {fn:.2f} | {lam:.3f} | {we:.2f} | {heave:.3f} | {abs(a[2]):.3f} | {abs(b[2]):.3f} | "
          f"{abs(c[2]):.3f} | {ps} | {abs(a[4]) / k:.3f} | {abs(b[4]) / k:.3f} |")
