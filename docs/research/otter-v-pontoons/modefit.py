"""Fit lightly damped pole pairs to local BEM solves (numpy only).

Mode term (passive, positive real):  K_m(s) = R * 2 zeta w0 s / (s^2 + 2 zeta w0 s + w0^2),  s = i w.
K = B + i w (A - A_inf).  Background per entry: complex quadratic in (w - wc).
"""
import sys; sys.dont_write_bytecode = True
import numpy as np
from boat_dynamics.physics.hydro import load_coefficients

CLASSES = {'SR': [(1, 1), (3, 3), (1, 3)], 'Y': [(5, 5)], 'H': [(2, 2)],
           'SP': [(0, 0), (4, 4), (0, 4)]}

def kernel(h):
    """(W,6,6) complex K = B + i w (A - A_inf)."""
    w = h.omega
    return h.radiation_damping + 1j * w[:, None, None] * (h.added_mass - h.added_mass_inf)

def g(w, w0, zeta):
    s = 1j * w
    return 2 * zeta * w0 * s / (s * s + 2 * zeta * w0 * s + w0 * w0)

FANO = True

def solve_linear(w, Y, params, npoly=3):
    """Y (W, E) complex. params [(w0, zeta), ...]. Returns residual norm, R (M, E) real, fit (W, E)."""
    wc = w.mean()
    cols = [g(w, w0, z) for w0, z in params]
    M = len(cols)
    # real unknowns: R_k (real, multiplies complex g), poly re (npoly), poly im (npoly)
    P = np.stack([(w - wc) ** k for k in range(npoly)], axis=1)
    G = np.stack(cols, axis=1) if M else np.zeros((len(w), 0))
    if FANO:  # exact real-kernel basis: Re rho -> q + q*, Im rho -> i (q - q*)
        D = []
        for w0, z in params:
            p = complex(-z * w0, w0 * np.sqrt(1 - z * z)); c = 2 * z * w0 * p / (p - p.conjugate())
            q = c / (1j * w - p); qs = np.conj(c) / (1j * w - p.conjugate())
            D.append(1j * (q - qs))
        G = np.concatenate([G, np.stack(D, axis=1)], axis=1)
    Xre = np.concatenate([G.real, P, np.zeros_like(P)], axis=1)
    Xim = np.concatenate([G.imag, np.zeros_like(P), P], axis=1)
    X = np.concatenate([Xre, Xim], axis=0)
    Yr = np.concatenate([Y.real, Y.imag], axis=0)
    coef, *_ = np.linalg.lstsq(X, Yr, rcond=None)
    fit = X @ coef
    res = np.linalg.norm(fit - Yr)
    W = len(w)
    return res, (coef[:M] + 1j * coef[M:2 * M] if FANO else coef[:M]), (fit[:W] + 1j * fit[W:])

def nelder_mead(f, x0, step, iters=400, tol=1e-10):
    n = len(x0); pts = [np.array(x0, float)]
    for i in range(n):
        p = np.array(x0, float); p[i] += step[i]; pts.append(p)
    vals = [f(p) for p in pts]
    for _ in range(iters):
        o = np.argsort(vals); pts = [pts[i] for i in o]; vals = [vals[i] for i in o]
        if abs(vals[-1] - vals[0]) <= tol * (abs(vals[0]) + 1e-30): break
        c = np.mean(pts[:-1], axis=0)
        xr = c + (c - pts[-1]); fr = f(xr)
        if fr < vals[0]:
            xe = c + 2 * (c - pts[-1]); fe = f(xe)
            pts[-1], vals[-1] = (xe, fe) if fe < fr else (xr, fr)
        elif fr < vals[-2]:
            pts[-1], vals[-1] = xr, fr
        else:
            xc = c + 0.5 * (pts[-1] - c); fc = f(xc)
            if fc < vals[-1]:
                pts[-1], vals[-1] = xc, fc
            else:
                pts = [pts[0] + 0.5 * (p - pts[0]) for p in pts]; vals = [f(p) for p in pts]
    o = np.argmin(vals)
    return pts[o], vals[o]

def fit_modes(w, Y, guesses, npoly=3):
    """guesses [(w0, zeta)]; returns params, R, fit, relative residual."""
    def unpack(x):
        return [(x[2 * k], np.exp(x[2 * k + 1])) for k in range(len(guesses))]
    def f(x):
        pr = unpack(x)
        if any(z <= 0 or z > 0.2 for _, z in pr): return 1e30
        return solve_linear(w, Y, pr, npoly)[0]
    x0 = np.concatenate([[w0, np.log(z)] for w0, z in guesses])
    stp = np.concatenate([[0.01 * w0 * z * 2 + 1e-3, 0.3] for w0, z in guesses])
    best = None
    for _ in range(4):  # restarts
        x, v = nelder_mead(f, x0, stp)
        x0, stp = x, stp * 0.3
        best = (x, v)
    pr = unpack(best[0])
    res, R, fit = solve_linear(w, Y, pr, npoly)
    rel = res / np.linalg.norm(np.concatenate([Y.real, Y.imag]))
    return pr, R, fit, rel
