"""Markdown tables for REPORT.md: every fitted mode (kept or not), and the memory against the
file at the grid points nearest the strongest modes."""
import sys
sys.dont_write_bytecode = True

import numpy as np

from boat_dynamics.physics.gap_modes import fit_with_modes
from boat_dynamics.physics.hydro import load_coefficients

import otlib
from select_modes import POOL

KEPT = ["SR1:0", "SR1:1", "Y1:0", "Y1:1", "H1:0", "SP1:0", "H1:1", "SP1:1", "SR2:0", "Y2:0",
        "H2:0", "SP2:0", "H2:1", "SP2:1", "SR3n:0", "Y3:0", "Y3:1"]
CLS = {"SR": "sway/roll", "Y": "yaw", "H": "heave", "SP": "surge/pitch"}

rows = []
for spec in POOL:
    name, k = spec.split(":")
    f = np.load(f"/tmp/otter2/fits/{name}.npz")
    k = int(k)
    w0, z, r = float(f["omega0"][k]), float(f["zeta"][k]), f["residue"][k]
    cls = str(f["cls"])
    dofs = otlib.CLASS_DOFS[cls]
    diag = ", ".join(f"{otlib.DOF[d]} {r[d, d].real:,.0f}" for d in dofs)
    dom = max(dofs, key=lambda d: abs(r[d, d]))  # Im/Re of the dominant diagonal entry
    imre = r[dom, dom].imag / r[dom, dom].real
    sv = np.linalg.svd(r[np.ix_(dofs, dofs)], compute_uv=False)
    s21 = f"{sv[-1] / sv[0]:.4f}" if len(dofs) > 1 else "-"
    rows.append((w0, f"| {spec} | {CLS[cls]} | {w0:.4f} | {2 * z * w0:.4f} | {z:.2e} | "
                     f"{1 / (2 * z):,.0f} | {diag} | {imre:+.2f} | {s21} | "
                     f"{float(f['resid_k']):.1e} / {float(f['resid_x']):.1e} | "
                     f"{f['lo']:g}-{f['hi']:g}, {f['solves']} | {'yes' if spec in KEPT else 'no'} |"))
print("| fit | dofs | ω0 rad/s | FWHM rad/s | ζ | Q | Re ρ diagonal | Im/Re (dominant diagonal) | σ2/σ1 | window resid K / X | window, solves | kept |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for _, line in sorted(rows):
    print(line)

h = load_coefficients("/tmp/otter2/otter_v_with_modes.npz")
mem = fit_with_modes(h)
w = h.omega
r = mem.response(w)
print()
print("| grid ω | entry | B file | B memory | A−A∞ file | A−A∞ memory |")
print("|---|---|---|---|---|---|")
for wq, (i, j) in [(8.213, (1, 1)), (8.213, (3, 3)), (8.630, (5, 5)), (10.715, (2, 2)),
                   (11.132, (4, 4)), (13.217, (1, 1)), (13.217, (5, 5)), (15.303, (4, 4)),
                   (16.554, (3, 3)), (16.971, (1, 1)), (16.971, (5, 5))]:
    k = int(np.argmin(abs(w - wq)))
    print(f"| {w[k]:.3f} | {otlib.DOF[i]}{'' if i == j else '-' + otlib.DOF[j]} | "
          f"{h.radiation_damping[k, i, j]:,.1f} | {r[k, i, j].real:,.1f} | "
          f"{h.added_mass[k, i, j] - h.added_mass_inf[i, j]:,.1f} | {r[k, i, j].imag / w[k]:,.1f} |")
