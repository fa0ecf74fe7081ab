"""Experiment: vector fitting (Gustavsen & Semlyen 1999) of the smooth part's blocks instead of
Hankel, weighted as radiation._fit_error, on the file grid (+ optional fine grid)."""
import sys; sys.dont_write_bytecode = True
import numpy as np, pickle, dataclasses
from boat_dynamics.physics.hydro import load_coefficients
from boat_dynamics.physics import radiation
from boat_dynamics.physics.radiation import RadiationMemory
import gapmodes as gm
from evaluate import ORIG
DOF = ['surge', 'sway', 'heave', 'roll', 'pitch', 'yaw']

def _solve(M, rhs, Wr, Wi):
    """Real LSQ of complex M x = rhs (x complex), Re rows weighted Wr, Im rows Wi."""
    Mr = np.block([[M.real * Wr[:, None], -M.imag * Wr[:, None]], [M.imag * Wi[:, None], M.real * Wi[:, None]]])
    br = np.concatenate([rhs.real * Wr, rhs.imag * Wi])
    x, *_ = np.linalg.lstsq(Mr, br, rcond=None); n = M.shape[1]
    return x[:n] + 1j * x[n:]


def vf(s, F, Wr, Wi, poles, iters=30):
    """Vector fitting without constant term: F(s) ~ sum_k r_k / (s - a_k) (a kernel's transform)."""
    P, E = F.shape
    for _ in range(iters):
        N = len(poles); C = 1.0 / (s[:, None] - poles[None, :])
        rows, rhs, wr, wi = [], [], [], []
        for e in range(E):
            blk = np.zeros((P, E * N + N), complex)
            blk[:, e * N:(e + 1) * N] = C
            blk[:, E * N:] = -F[:, e:e + 1] * C
            rows.append(blk); rhs.append(F[:, e]); wr.append(Wr[:, e]); wi.append(Wi[:, e])
        x = _solve(np.concatenate(rows), np.concatenate(rhs), np.concatenate(wr), np.concatenate(wi))
        rt = x[E * N:]
        new = np.linalg.eigvals(np.diag(poles) - np.ones((N, 1)) @ rt[None, :])
        poles = np.where(new.real > 0, -new.real + 1j * new.imag, new)
    C = 1.0 / (s[:, None] - poles[None, :])
    res = np.stack([_solve(C, F[:, e], Wr[:, e], Wi[:, e]) for e in range(E)], axis=1)
    return poles, res, np.zeros(E)


modes = gm.load_modes('otter_gap_modes.npz')
h = load_coefficients(ORIG); w = h.omega
use_fine = '--fine' in sys.argv
sm = gm.smooth_part(h, modes)
Kt = sm.radiation_damping + 1j * w[:, None, None] * (sm.added_mass - sm.added_mass_inf)
pts_w, pts_K = [w], [Kt]
if use_fine:
    f = load_coefficients('/tmp/cat/fine_lid.npz'); fs = gm.smooth_part(f, modes)
    pts_w.append(f.omega); pts_K.append(fs.radiation_damping + 1j * f.omega[:, None, None] * (fs.added_mass - fs.added_mass_inf))
keep0 = ~gm.band_mask(w, modes, 3, cap=0.21)  # weights from the scales away from the gap peaks
bsc = np.sqrt(np.abs(np.diagonal(h.radiation_damping[keep0], axis1=1, axis2=2)).max(0))
asc = np.sqrt(np.abs(np.diagonal(h.added_mass[keep0], axis1=1, axis2=2)).max(0))
extra = gm.mode_memory(modes); mode_resp = RadiationMemory(*extra, 0.0).response(w)
orders = dict(zip(['SP', 'SR', 'H', 'Y'], map(int, sys.argv[1].split(','))))
norder = sys.argv[1].replace(',', '-')
key = {(0, 4): 'SP', (1, 3): 'SR', (2,): 'H', (5,): 'Y'}
parts = []
for idx in gm.dof_blocks(sm):
    ents = [(i, j) for a, i in enumerate(idx) for j in idx[a:]]
    ss, FF, WW, WI = [], [], [], []
    for ww, kk in zip(pts_w, pts_K):
        for sign in (1, -1):
            ss.append(1j * sign * ww)
            FF.append(np.stack([kk[:, i, j] if sign > 0 else np.conj(kk[:, i, j]) for i, j in ents], 1))
            WW.append(np.stack([np.full(len(ww), 1.0 / (bsc[i] * bsc[j] + 1e-9)) for i, j in ents], 1))
            WI.append(np.stack([1.0 / (ww * asc[i] * asc[j] + 1e-9) for i, j in ents], 1))
    s_, F_, W_, Wi_ = np.concatenate(ss), np.concatenate(FF), np.concatenate(WW), np.concatenate(WI)
    n = orders[key[tuple(idx)]]
    im = np.linspace(0.5, 18.0, max(n // 2, 1))
    p0 = np.concatenate([-im / 50 + 1j * im, -im / 50 - 1j * im])[:n] if n > 1 else np.array([-1.0 + 0j])
    poles, res, d = vf(s_, F_, W_, Wi_, p0)
    # a constant d would be an A_inf change / B at infinity: dropped (kernel must vanish); report it
    # memory form: residue matrix per pole (n x n symmetric) -> rank-full: one state per (pole, column)
    R = np.zeros((len(poles), 6, 6), complex)
    for e, (i, j) in enumerate(ents):
        R[:, i, j] = res[:, e]; R[:, j, i] = res[:, e]
    pl, inp, out = [], [], []
    for k in range(len(poles)):
        u, sv, vh = np.linalg.svd(R[k])
        for q in range(len(idx)):
            if sv[q] > 1e-9 * sv[0]:
                pl.append(poles[k]); out.append(sv[q] * u[:, q]); inp.append(vh[q])
    parts.append((np.array(pl), np.array(inp), np.array(out).T))
    print('block', idx, 'poles', len(poles), 'states', len(pl), 'max|d|', np.abs(d).max().round(3))
mem = RadiationMemory(np.concatenate([p[0] for p in parts] + [extra[0]]), np.concatenate([p[1] for p in parts] + [extra[1]]),
                      np.concatenate([p[2] for p in parts] + [extra[2]], axis=1), 0.0)
r = mem.response(w)
err = radiation._fit_error(r, h)
keep = ~gm.band_mask(w, modes, 3, cap=0.21)
print(f'VF order {norder}: states {mem.poles.shape[0]} error (a) {err:.4f}  (b2 subset scales) {gm.fit_error_where(r, h, keep):.4f}')
bs = np.abs(np.diagonal(h.radiation_damping, axis1=1, axis2=2)).max(0); as_ = np.abs(np.diagonal(h.added_mass, axis1=1, axis2=2)).max(0)
print(' per-diag B', [round(float(np.abs(r[:, i, i].real - h.radiation_damping[:, i, i]).max() / bs[i]), 3) for i in range(6)],
      ' A', [round(float(np.abs(r[:, i, i].imag / w - (h.added_mass[:, i, i] - h.added_mass_inf[i, i])).max() / as_[i]), 3) for i in range(6)])
print(' unstable poles:', int((mem.poles.real >= 0).sum()))
sub = dataclasses.replace(h, omega=w[keep], added_mass=h.added_mass[keep], radiation_damping=h.radiation_damping[keep])
bs2 = np.abs(np.diagonal(sub.radiation_damping, axis1=1, axis2=2)).max(0); as2 = np.abs(np.diagonal(sub.added_mass, axis1=1, axis2=2)).max(0)
eb = np.abs(r[keep].real - sub.radiation_damping).max(0) / np.sqrt(np.outer(bs2, bs2)); ea = np.abs(r[keep].imag / w[keep, None, None] - (sub.added_mass - h.added_mass_inf)).max(0) / np.sqrt(np.outer(as2, as2))
print(' b2 per-diag B', np.round(np.diag(eb), 3).tolist(), 'A', np.round(np.diag(ea), 3).tolist(), 'worst B entry', np.unravel_index(eb.argmax(), eb.shape), 'worst A entry', np.unravel_index(ea.argmax(), ea.shape))
pickle.dump(mem, open(f'vf_memory_{norder}{"_fine" if use_fine else ""}.pkl', 'wb'))
