"""Informational: the 20-mode set with a larger state budget than the product's 64
(gap_modes.MAX_ORDER patched in this process only)."""
import sys
sys.dont_write_bytecode = True
from dataclasses import replace

import numpy as np

import boat_dynamics.physics.gap_modes as gm
from boat_dynamics.physics.hydro import load_coefficients

import otlib
from evaluate import errors_where

h = load_coefficients("/tmp/otter2/variants/m20.npz")
s = otlib.Solve(otlib.SOLVES / "fine05.npz")
m = s.omega <= h.omega[-1] + 1e-9
for budget in (64, 72, 80, 96):
    gm.MAX_ORDER = budget
    mem = gm.fit_with_modes(h)
    keep = ~gm.band_mask(h.omega, h.gap_modes)
    b, a = errors_where(mem.response(h.omega), h, keep)
    rf = mem.response(s.omega[m])
    bm = np.abs(np.diagonal(s.B[m], axis1=1, axis2=2)).max(axis=0)
    fb = [np.abs(rf[:, i, i].real - s.B[m][:, i, i]).max() / bm[i] for i in range(6)]
    print(f"budget {budget}: states {mem.poles.shape[0]}, error {mem.error:.4f}, outside B {b:.4f} "
          f"A {a:.4f}, fine B {np.round(fb, 3).tolist()}")
