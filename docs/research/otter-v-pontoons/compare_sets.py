"""Metrics of several gap-mode sets: the product's fit error (all grid points), outside
omega0 +- 3 widths, against the 0.05 rad/s solve, narrow peaks left in smooth_part, states."""
import sys
sys.dont_write_bytecode = True
from dataclasses import replace

import numpy as np

from boat_dynamics.physics.gap_modes import band_mask, fit_with_modes, smooth_part
from boat_dynamics.physics.hydro import narrow_peaks

import otlib
from evaluate import errors_where
from select_modes import H, MODES

FINE = otlib.Solve(otlib.SOLVES / "fine05.npz")
M = FINE.omega <= H.omega[-1] + 1e-9

PRIMARY = ["SR1:0", "Y1:0", "H1:0", "SP1:0", "SR2:0", "Y2:0", "H2:0", "SP2:0", "SR3n:0", "Y3:0"]
SECOND = ["SR2:1", "SR3:0", "Y3:1", "H2:1", "SP2:1", "H1:1", "SP1:1", "Y2:1", "SR1:1", "Y1:1"]


def metrics(specs):
    ms = tuple(sorted((MODES[s] for s in specs), key=lambda m: m.omega0))
    h = replace(H, gap_modes=ms)
    mem = fit_with_modes(h)
    keep = ~band_mask(h.omega, ms)
    b, a = errors_where(mem.response(h.omega), h, keep)
    rf = mem.response(FINE.omega[M])
    bm = np.abs(np.diagonal(FINE.B[M], axis1=1, axis2=2)).max(axis=0)
    am = np.abs(np.diagonal(FINE.A[M], axis1=1, axis2=2)).max(axis=0)
    fb = max(np.abs(rf[:, i, i].real - FINE.B[M][:, i, i]).max() / bm[i] for i in range(6))
    fa = max(np.abs(rf[:, i, i].imag / FINE.omega[M] - (FINE.A[M][:, i, i] - FINE.Ainf[i, i])).max()
             / am[i] for i in range(6))
    peaks = narrow_peaks(smooth_part(h))
    return mem.error, b, a, fb, fa, len(peaks), mem.poles.shape[0]


def show(label, specs):
    e, b, a, fb, fa, n, st = metrics(specs)
    print(f"{label:28s} {len(specs):2d} modes  error {e:.4f}  outside B {b:.4f} A {a:.4f}  "
          f"fine B {fb:.3f} A {fa:.3f}  smooth peaks {n}  states {st}", flush=True)


if __name__ == "__main__":
    show("primary 10", PRIMARY)
    for k in range(1, len(SECOND) + 1):
        show(f"primary + {k} ({SECOND[k - 1]})", PRIMARY + SECOND[:k])
    for extra in sys.argv[1:]:
        show(extra[:28], extra.split(","))
