"""Variable-projection fit of pole pairs to local solves in one window of one symmetry class.

usage: fitwin.py CLASS LO HI SOLVES W0:ZETA [W0:ZETA ...] [--npoly N] [--save NAME]
                 [--subtract FIT:INDEX ...] [--exclude LO:HI ...]
  SOLVES: comma-separated tags in /tmp/otter2/solves (merged)
Fits the class's K entries (B + i w (A - A_inf)) with the pole pairs plus a complex polynomial
background (modefit.fit_modes: complex residues, Fano), then the class's diffraction forces with
the same poles (C conj(h) + complex polynomial). Prints omega0, zeta, FWHM, residues, residuals.
--save writes /tmp/otter2/fits/NAME.npz (class, omega0, zeta, residue (M,6,6), excitation (M,D,6)).
"""
import argparse
import sys
sys.dont_write_bytecode = True
from pathlib import Path

import numpy as np

import modefit
import otlib


def excitation_fit(w, X, params, npoly):
    """X (W, E) complex ~ sum_k C_k conj(h_k) + poly: complex linear LS. Returns C (M, E), rel."""
    wc = w.mean()
    cols = [np.conj(modefit.g(w, w0, z)) for w0, z in params]
    cols += [(w - wc) ** k + 0j for k in range(npoly)]
    G = np.stack(cols, axis=1)
    coef, *_ = np.linalg.lstsq(G, X, rcond=None)
    fit = G @ coef
    rel = np.linalg.norm(fit - X) / np.linalg.norm(X)
    return coef[:len(params)], rel


def fit_window(cls, lo, hi, tags, guesses, npoly=3, subtract=(), exclude=()):
    s = otlib.merge([otlib.SOLVES / f"{t}.npz" for t in tags])
    w, Y, X = otlib.class_data(s, cls, lo, hi)
    for spec in subtract:  # a mode fitted before (FIT:INDEX): its K and X taken out first
        name, k = spec.split(":")
        f = np.load(f"/tmp/otter2/fits/{name}.npz")
        k = int(k)
        w0, z = float(f["omega0"][k]), float(f["zeta"][k])
        p = complex(-z * w0, w0 * np.sqrt(1 - z * z))
        c = 2 * z * w0 * p / (p - p.conjugate())
        q, qs = c / (1j * w - p), np.conj(c) / (1j * w - p.conjugate())
        rho = np.array([f["residue"][k][i, j] for i, j in otlib.CLASSES[cls]])
        Y = Y - (rho.real[None] * (q + qs)[:, None] + 1j * rho.imag[None] * (q - qs)[:, None])
        exc = f["excitation"][k][:, otlib.CLASS_DOFS[cls]].reshape(-1)
        X = X - np.conj(modefit.g(w, w0, z))[:, None] * exc[None]
    keep = np.ones(w.shape, bool)
    for band in exclude:
        a, b = (float(x) for x in band.split(":"))
        keep &= (w < a) | (w > b)
    w, Y, X = w[keep], Y[keep], X[keep]
    params, R, fit, rel = modefit.fit_modes(w, Y, guesses, npoly)
    C, xrel = excitation_fit(w, X, params, npoly)
    nd = len(otlib.CLASS_DOFS[cls])
    D = s.X.shape[1]
    modes = []
    for k, (w0, z) in enumerate(params):
        rho = np.zeros((6, 6), complex)
        for e, (i, j) in enumerate(otlib.CLASSES[cls]):
            rho[i, j] = rho[j, i] = R[k, e]
        exc = np.zeros((D, 6), complex)
        exc[:, otlib.CLASS_DOFS[cls]] = C[k].reshape(D, nd)
        modes.append((w0, z, rho, exc))
    # per-entry relative residual of K
    ent = np.linalg.norm(fit - Y, axis=0) / np.linalg.norm(Y, axis=0)
    return modes, rel, xrel, ent, len(w)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cls")
    ap.add_argument("lo", type=float)
    ap.add_argument("hi", type=float)
    ap.add_argument("solves")
    ap.add_argument("guesses", nargs="+")
    ap.add_argument("--npoly", type=int, default=3)
    ap.add_argument("--save")
    ap.add_argument("--subtract", nargs="*", default=[], help="FIT:INDEX modes taken out first")
    ap.add_argument("--exclude", nargs="*", default=[], help="LO:HI bands left out")
    a = ap.parse_args()
    guesses = [tuple(float(x) for x in g.split(":")) for g in a.guesses]
    modes, rel, xrel, ent, n = fit_window(a.cls, a.lo, a.hi, a.solves.split(","), guesses,
                                          a.npoly, a.subtract, a.exclude)
    print(f"{a.cls} [{a.lo}, {a.hi}] {n} points: K resid {rel:.2e} (entries "
          f"{', '.join(f'{e:.1e}' for e in ent)}), X resid {xrel:.2e}")
    for w0, z, rho, exc in modes:
        dofs = otlib.CLASS_DOFS[a.cls]
        diag = ", ".join(f"{otlib.DOF[d]} {rho[d, d].real:.1f}{rho[d, d].imag:+.1f}j" for d in dofs)
        sv = np.linalg.svd(rho[np.ix_(dofs, dofs)], compute_uv=False)
        print(f"  w0 {w0:.5f} zeta {z:.3e} FWHM {2 * z * w0:.5f} Q {1 / (2 * z):.0f}: {diag}; "
              f"s2/s1 {sv[-1] / sv[0]:.3f}; |X| max {np.abs(exc).max():.1f}")
    if a.save:
        Path("/tmp/otter2/fits").mkdir(exist_ok=True)
        np.savez(f"/tmp/otter2/fits/{a.save}.npz", cls=a.cls, lo=a.lo, hi=a.hi,
                 solves=a.solves, omega0=[m[0] for m in modes], zeta=[m[1] for m in modes],
                 residue=np.array([m[2] for m in modes]),
                 excitation=np.array([m[3] for m in modes]), resid_k=rel, resid_x=xrel)


if __name__ == "__main__":
    main()
