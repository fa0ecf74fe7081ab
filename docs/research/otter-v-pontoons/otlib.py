"""Shared helpers for the otter_v gap-mode study (numpy only; main venv)."""
import sys
sys.dont_write_bytecode = True
from pathlib import Path

import numpy as np

FILE = Path("/tmp/otter2/hydro/hull_2x1.04x0.4_d0.177_e884bec0fcfc08bc.npz")
SOLVES = Path("/tmp/otter2/solves")
DOF = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
# Symmetry classes of a hull symmetric fore-aft and port-starboard, and their K entries.
CLASSES = {"SR": [(1, 1), (3, 3), (1, 3)], "Y": [(5, 5)], "H": [(2, 2)],
           "SP": [(0, 0), (4, 4), (0, 4)]}
CLASS_DOFS = {"SR": [1, 3], "Y": [5], "H": [2], "SP": [0, 4]}


class Solve:
    """A solve (the file or a local re-solve): omega, A, B, A_inf, diffraction (W, D, 6)."""

    def __init__(self, path):
        d = np.load(path)
        self.path = str(path)
        self.omega = d["omega"]
        self.A = d["added_mass"]
        self.B = d["radiation_damping"]
        self.Ainf = d["added_mass_inf"]
        self.X = d["diffraction"]
        self.FK = d["froude_krylov"]
        self.cpu = float(d["cpu_seconds"]) if "cpu_seconds" in d.files else float("nan")

    @property
    def K(self):
        """(W, 6, 6) complex B + i omega (A - A_inf)."""
        return self.B + 1j * self.omega[:, None, None] * (self.A - self.Ainf)


def merge(paths):
    """One Solve of several, sorted by omega, duplicates dropped."""
    solves = [Solve(p) for p in paths]
    out = solves[0]
    w = np.concatenate([s.omega for s in solves])
    order = np.argsort(w, kind="stable")
    w = w[order]
    keep = np.concatenate([[True], np.diff(w) > 1e-9])
    for name in ("A", "B", "X", "FK"):
        setattr(out, name, np.concatenate([getattr(s, name) for s in solves])[order][keep])
    out.omega = w[keep]
    out.cpu = sum(s.cpu for s in solves)
    return out


def class_data(s, cls, lo=None, hi=None):
    """(w, Y (W, E) complex K entries, Xc (W, D*ndof) complex diffraction) in [lo, hi]."""
    w = s.omega
    m = np.ones(w.shape, bool)
    if lo is not None:
        m &= w >= lo
    if hi is not None:
        m &= w <= hi
    K = s.K[m]
    Y = np.stack([K[:, i, j] for i, j in CLASSES[cls]], axis=1)
    X = s.X[m][:, :, CLASS_DOFS[cls]].reshape(m.sum(), -1)
    return w[m], Y, X
