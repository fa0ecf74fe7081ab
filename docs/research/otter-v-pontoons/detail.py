"""Where a gap-mode set's memory misses the file: per-diagonal worst entries, the states per
block, the narrow peaks left in smooth_part."""
import sys
sys.dont_write_bytecode = True
from dataclasses import replace

import numpy as np

from boat_dynamics.physics.gap_modes import dof_blocks, fit_with_modes, smooth_part
from boat_dynamics.physics.hydro import narrow_peaks

import otlib
from select_modes import H, MODES


def detail(specs):
    ms = tuple(sorted((MODES[s] for s in specs), key=lambda m: m.omega0))
    h = replace(H, gap_modes=ms)
    mem = fit_with_modes(h)
    w = h.omega
    r = mem.response(w)
    bs = np.abs(np.diagonal(h.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    as_ = np.abs(np.diagonal(h.added_mass, axis1=1, axis2=2)).max(axis=0)
    print(f"{len(specs)} modes, error {mem.error:.4f}")
    for i in range(6):
        db = np.abs(r[:, i, i].real - h.radiation_damping[:, i, i])
        da = np.abs(r[:, i, i].imag / w - (h.added_mass[:, i, i] - h.added_mass_inf[i, i]))
        kb, ka = db.argmax(), da.argmax()
        print(f"  {otlib.DOF[i]:5s} B {db[kb] / bs[i]:.3f} ({db[kb]:.1f} at {w[kb]:.2f}; max {bs[i]:.0f})"
              f"  A {da[ka] / as_[i]:.3f} ({da[ka]:.2f} at {w[ka]:.2f}; max {as_[i]:.1f})")
    # states per block: poles' output rows
    out = np.abs(mem.output)
    for blk in dof_blocks(h):
        n = int((out[blk].max(axis=0) > 0).sum())
        print(f"  block {[otlib.DOF[b] for b in blk]}: {n} states (modes included)")
    for p in narrow_peaks(smooth_part(h)):
        print(f"  smooth peak {p.omega:.3f} {p.dof} {p.quantity} ratio {p.ratio:.2f}")


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        detail(arg.split(","))
