"""Measure a coefficient file with gap modes as test_gap_modes.py does.

usage: evaluate.py FILE_WITH_MODES.npz [--fine]
Prints: fit_with_modes(h).error (all grid points), the error outside omega0 +- 3 widths
(test_gap_modes._errors_where: each entry over its file-wide scale), the Hankel fit_memory
error of the file without its modes, narrow_peaks of the file and of smooth_part(h), the
memory's states and stability, per-diagonal errors, CPU times; with --fine, the memory against
the 0.05 rad/s local solve (B between grid points).
"""
import sys
sys.dont_write_bytecode = True
import time
from dataclasses import replace

import numpy as np

from boat_dynamics.physics.gap_modes import (band_mask, dof_blocks, fit_with_modes,
                                             smooth_part)
from boat_dynamics.physics.hydro import load_coefficients, narrow_peaks
from boat_dynamics.physics.radiation import MAX_ORDER, fit_memory

import otlib


def errors_where(response, hydro, keep):
    """test_gap_modes._errors_where: largest |dB|, |dA| at keep over each entry's file scale."""
    bs = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    as_ = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)
    w = hydro.omega[keep, None, None]
    b = np.abs(response[keep].real - hydro.radiation_damping[keep]).max(axis=0)
    a = np.abs(response[keep].imag / w - (hydro.added_mass[keep] - hydro.added_mass_inf))
    return (float((b / np.sqrt(np.outer(bs, bs))).max()),
            float((a.max(axis=0) / np.sqrt(np.outer(as_, as_))).max()))


def per_diagonal(response, hydro):
    w = hydro.omega
    bs = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    as_ = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)
    eb = [float(np.abs(response[:, i, i].real - hydro.radiation_damping[:, i, i]).max() / bs[i])
          for i in range(6)]
    ea = [float(np.abs(response[:, i, i].imag / w - (hydro.added_mass[:, i, i]
                                                     - hydro.added_mass_inf[i, i])).max() / as_[i])
          for i in range(6)]
    return eb, ea


def main(path, fine=False):
    h = load_coefficients(path)
    print(f"{path}: {len(h.gap_modes)} modes, {len(h.omega)} omegas")
    c0 = time.process_time()
    mem = fit_with_modes(h)
    c_fit = time.process_time() - c0
    keep = ~band_mask(h.omega, h.gap_modes)
    r = mem.response(h.omega)
    b, a = errors_where(r, h, keep)
    eb, ea = per_diagonal(r, h)
    print(f"fit_with_modes: error {mem.error:.4f}, states {mem.poles.shape[0]} (max {MAX_ORDER}),"
          f" modes' {2 * len(h.gap_modes)}, stable {bool(np.all(mem.poles.real < 0))}, "
          f"CPU {c_fit:.1f} s")
    print(f"outside omega0 +- 3 widths ({keep.sum()}/{len(keep)} points kept): B {b:.4f}, A {a:.4f}")
    print("per-diagonal (all points) B", np.round(eb, 3).tolist(), "A", np.round(ea, 3).tolist())
    kept_w = h.omega[~keep]
    print("excluded grid omegas:", np.round(kept_w, 3).tolist())
    c0 = time.process_time()
    plain = fit_memory(replace(h, gap_modes=()))
    print(f"Hankel fit_memory of the file without modes: error {plain.error:.4f} "
          f"(states {plain.poles.shape[0]}, CPU {time.process_time() - c0:.1f} s)")
    print("dof blocks", dof_blocks(h))
    before = narrow_peaks(replace(h, gap_modes=()))
    smooth = smooth_part(h)
    after = narrow_peaks(smooth)
    print(f"narrow_peaks(file): {len(before)}, max ratio {max((p.ratio for p in before), default=0):.2f}")
    print(f"narrow_peaks(smooth_part): {len(after)}")
    for p in after:
        print(f"   {p.omega:.4f} {p.dof} {p.quantity} ratio {p.ratio:.2f}")
    # passivity of the memory: min eigenvalue of sym(B_mem) on a fine grid
    wf = np.linspace(0.05, 34.0, 2000)
    rf = mem.response(wf).real
    mins = np.linalg.eigvalsh(0.5 * (rf + np.swapaxes(rf, 1, 2))).min(axis=1)
    k = int(mins.argmin())
    print(f"min eig sym(B_mem) on 0.05-34 rad/s: {mins[k]:.1f} at {wf[k]:.2f} rad/s")
    if fine:
        s = otlib.Solve(otlib.SOLVES / "fine05.npz")
        m = s.omega <= h.omega[-1] + 1e-9
        rf = mem.response(s.omega[m])
        bmax = np.abs(np.diagonal(s.B[m], axis1=1, axis2=2)).max(axis=0)
        d = [float(np.abs(rf[:, i, i].real - s.B[m][:, i, i]).max() / bmax[i]) for i in range(6)]
        amax = np.abs(np.diagonal(s.A[m], axis1=1, axis2=2)).max(axis=0)
        da = [float(np.abs(rf[:, i, i].imag / s.omega[m] - (s.A[m][:, i, i] - s.Ainf[i, i])).max()
                    / amax[i]) for i in range(6)]
        print(f"vs the 0.05 rad/s solve ({m.sum()} points to {h.omega[-1]:.2f}): max|dB|/max B",
              np.round(d, 3).tolist(), " max|dA|/max A", np.round(da, 3).tolist())
    return mem


if __name__ == "__main__":
    main(sys.argv[1], "--fine" in sys.argv)
