"""Exploratory: potential flow at speed with Salvesen-Tuck-Faltinsen's radiation terms
completed (pitch-from-heave A53 + U B33/w^2, B53 - U A33, and the U^2 pitch terms
A55 + U^2 A33/w^2, B55 + U^2 B33/w^2; no transom terms, no speed term in the diffraction),
next to the heave-from-pitch terms alone (2 dof; potential_flow_rao also has pitch-pitch
terms from its U L product) and no speed terms at all.
Heave and pitch only (surge, sway, roll, yaw held: head seas)."""
import math

import numpy as np

from boat_dynamics.physics.hydro import load_coefficients
from boat_dynamics.physics.seakeeping import encounter_frequency
from run_points import LENGTH, G, NPZ, measured

z = np.load(NPZ)
hydro = load_coefficients(str(NPZ))
M = np.array(z["inertia_matrix"], float)
idx = [2, 4]
print("| Fn | lambda/L | meas heave | no U | heave-from-pitch only (2 dof) | STF radiation |")
print("|---|---|---|---|---|---|")
for fn, lam, heave, _ in measured():
    if fn == 0.0:
        continue
    k = 2 * math.pi / (lam * LENGTH)
    w = math.sqrt(G * k)
    U = fn * math.sqrt(G * LENGTH)
    we = encounter_frequency(w, k, U, math.pi)
    F = (hydro.froude_krylov_at(np.array([w]), np.array([math.pi]))[0]
         + hydro.diffraction_at(np.array([we]), np.array([math.pi]))[0])[idx]
    A, B = hydro.added_mass_at(we)[np.ix_(idx, idx)], hydro.damping_at(we)[np.ix_(idx, idx)]
    C = hydro.hydrostatic_stiffness[np.ix_(idx, idx)]
    Mm = M[np.ix_(idx, idx)]
    out = []
    for variant in ("none", "half", "stf"):
        Ae, Be = A.copy(), B.copy()
        if variant in ("half", "stf"):
            Ae[0, 1] -= U * B[0, 0] / we**2
            Be[0, 1] += U * A[0, 0]
        if variant == "stf":
            Ae[1, 0] += U * B[0, 0] / we**2
            Be[1, 0] -= U * A[0, 0]
            Ae[1, 1] += U**2 * A[0, 0] / we**2
            Be[1, 1] += U**2 * B[0, 0] / we**2
        H = -we**2 * (Mm + Ae) - 1j * we * Be + C
        out.append(abs(np.linalg.solve(H, F)[0]))
    print(f"| {fn:.2f} | {lam:.3f} | {heave:.3f} | {out[0]:.3f} | {out[1]:.3f} | {out[2]:.3f} |")
