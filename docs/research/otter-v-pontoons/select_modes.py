"""Greedy choice of the gap modes to store (within MAX_ORDER = 64 memory states).

Pool: every fitted mode in fits/*.npz (listed below). With --backward: from the 20 strongest,
drop one mode at a time (the one whose removal leaves the least fit_with_modes(h).error, all 40
grid points, the product's metric) down to 10, and keep the best set on that path. Then (or
from a comma-separated set given as argument) greedy: drop or add the single mode that lowers
the error most; repeat until nothing improves. Prints each step.
"""
import sys
sys.dont_write_bytecode = True
from dataclasses import replace

import numpy as np

from boat_dynamics.physics.gap_modes import band_mask, fit_with_modes
from boat_dynamics.physics.hydro import GapMode, load_coefficients

import otlib
from evaluate import errors_where

POOL = ["SR1:0", "SR1:1", "Y1:0", "Y1:1", "H1:0", "H1:1", "H1:2", "SP1:0", "SP1:1", "SR2:0",
        "SR2:1", "SR2:2", "Y2:0", "Y2:1", "Y2:2", "H2:0", "H2:1", "H2:2", "SP2:0", "SP2:1",
        "SP2:2", "SR3n:0", "SR3:0", "SR3:1", "Y3:0", "Y3:1", "Y3:2", "Y3:3"]
START = ["SR1:0", "SR1:1", "Y1:0", "Y1:1", "H1:0", "H1:1", "SP1:0", "SP1:1", "SR2:0", "SR2:1",
         "Y2:0", "Y2:1", "H2:0", "H2:1", "SP2:0", "SP2:1", "SR3n:0", "SR3:0", "Y3:0", "Y3:1"]


def mode(spec):
    name, k = spec.split(":")
    f = np.load(f"/tmp/otter2/fits/{name}.npz")
    k = int(k)
    return GapMode(float(f["omega0"][k]), float(f["zeta"][k]), f["residue"][k].astype(complex),
                   f["excitation"][k].astype(complex))


MODES = {s: mode(s) for s in POOL}
H = load_coefficients(otlib.FILE)


def score(specs):
    ms = tuple(sorted((MODES[s] for s in specs), key=lambda m: m.omega0))
    h = replace(H, gap_modes=ms)
    mem = fit_with_modes(h)
    keep = ~band_mask(h.omega, ms)
    b, a = errors_where(mem.response(h.omega), h, keep)
    return mem.error, max(a, b), mem.poles.shape[0]


def backward(cur, stop=10):
    """Drop the mode whose removal leaves the least error, down to ``stop`` modes, each step
    also trying one swap in of a left-out pool mode; print the path."""
    path = []
    while len(cur) > stop:
        trials = [(score([c for c in cur if c != s]), s) for s in cur]
        trials.sort(key=lambda t: t[0][0])
        (err, out, states), s = trials[0]
        cur = [c for c in cur if c != s]
        path.append((err, out, states, list(cur)))
        print(f"-{s:7s} -> {len(cur)} modes: error {err:.4f}, outside {out:.4f}, states {states}",
              flush=True)
    err, out, states, best = min(path, key=lambda p: p[0])
    print(f"best on the path: {len(best)} modes, error {err:.4f}, outside {out:.4f}:",
          ",".join(sorted(best, key=lambda s: MODES[s].omega0)))
    return best


def main():
    if "--backward" in sys.argv:
        cur = backward(list(START))
        sys.argv = [a for a in sys.argv if a != "--backward"][:1] + [",".join(cur)]
    cur = list(START) if len(sys.argv) < 2 else sys.argv[1].split(",")
    best = score(cur)
    print(f"start {len(cur)} modes: error {best[0]:.4f}, outside {best[1]:.4f}, states {best[2]}",
          flush=True)
    while True:
        trials = []
        for s in cur:
            trials.append((score([c for c in cur if c != s]), "-" + s))
        for s in POOL:
            if s not in cur and 2 * (len(cur) + 1) <= 52:
                trials.append((score(cur + [s]), "+" + s))
        trials.sort(key=lambda t: t[0][0])
        (err, out, states), move = trials[0]
        if err >= best[0] - 1e-4:
            break
        cur = [c for c in cur if c != move[1:]] if move[0] == "-" else cur + [move[1:]]
        best = (err, out, states)
        print(f"{move:8s} -> {len(cur)} modes: error {err:.4f}, outside {out:.4f}, states {states}",
              flush=True)
    print("chosen:", ",".join(sorted(cur, key=lambda s: MODES[s].omega0)))


if __name__ == "__main__":
    main()
