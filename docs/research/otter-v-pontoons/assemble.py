"""Write /tmp/otter2/otter_v_with_modes.npz: the solved file plus the chosen gap modes.

usage: assemble.py OUT.npz FIT:INDEX [FIT:INDEX ...]
  FIT: a /tmp/otter2/fits/FIT.npz written by fitwin.py --save; INDEX: the mode in it (0-based).
The modes are sorted by omega0 and stored as gap_mode_omega (M,), gap_mode_zeta (M,),
gap_mode_residue (M, 6, 6) complex, gap_mode_excitation (M, D, 6) complex, plus a
gap_mode_source text; every other array is the solved file's, unchanged.
"""
import sys
sys.dont_write_bytecode = True

import numpy as np

import otlib


def collect(specs):
    modes = []
    for spec in specs:
        name, idx = spec.split(":")
        f = np.load(f"/tmp/otter2/fits/{name}.npz")
        k = int(idx)
        modes.append((float(f["omega0"][k]), float(f["zeta"][k]), f["residue"][k],
                      f["excitation"][k], f"{name}:{k}"))
    modes.sort(key=lambda m: m[0])
    return modes


def main(out, specs):
    modes = collect(specs)
    with np.load(otlib.FILE, allow_pickle=False) as d:
        arrays = {k: d[k] for k in d.files}
    arrays.update(
        gap_mode_omega=np.array([m[0] for m in modes]),
        gap_mode_zeta=np.array([m[1] for m in modes]),
        gap_mode_residue=np.array([m[2] for m in modes]).astype(complex),
        gap_mode_excitation=np.array([m[3] for m in modes]).astype(complex),
        gap_mode_source=np.array(
            f"{len(modes)} gap modes fitted (variable projection, pole pairs with complex "
            f"residues) to local Capytaine re-solves on this file's own mesh (1656 hull + 320 "
            f"lid panels) at 0.01-0.0002 rad/s steps: /tmp/otter2/REPORT.md"))
    np.savez_compressed(out, **arrays)
    for m in modes:
        print(f"  {m[4]:8s} w0 {m[0]:.5f} zeta {m[1]:.3e}")
    print(out, len(modes), "modes")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
