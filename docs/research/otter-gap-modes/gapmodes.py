"""Gap (sloshing) modes of a multi-hull as explicit lightly damped resonances.

Each narrow gap resonance of a BEM file is modelled as one second-order pole pair in the
radiation kernel K^(omega) = B(omega) + i omega (A(omega) - A_inf), s = i omega:

    h(s; omega0, zeta) = 2 zeta omega0 s / (s^2 + 2 zeta omega0 s + omega0^2)
                       = c / (s - p) + conj(c) / (s - conj p),
    p = -zeta omega0 + i omega0 sqrt(1 - zeta^2),  c = 2 zeta omega0 p / (p - conj p),
    K_m(s) = rho c / (s - p) + conj(rho c) / (s - conj p)         (= rho h(s) for real rho)

rho is a symmetric 6 x 6 residue, B_m(omega0) ~ Re rho. For real PSD rho (rank one, v v^T):
Re h = (2 zeta omega0 omega)^2 / |D|^2 >= 0, so B_m is PSD at every frequency (the impedance
of a parallel spring-mass-dashpot: passive), A_m - A_inf = rho 2 zeta omega0 (omega0^2 -
omega^2) / |D|^2 (2 zeta rho / omega0 at omega = 0, ~1/omega^2 at infinity): A and B of the
term are Kramers-Kronig consistent by construction. The Otter's modes have a small imaginary
part (Im/Re up to 0.13: a Fano-shaped peak, interference with the background); that part is
dispersive in B (negative on one side, at most 2 % of the peak for the Otter) and gives
K_m(0) = -2 zeta Im rho. The wave excitation (Capytaine's e^{-i omega t} convention, so its
poles sit at conj p) is C conj(h) with C complex (D, 6).

Damping treatment: with the coupling alpha = 2 zeta omega0 rho held fixed (the body-to-mode
coupling does not depend on how the mode dissipates), raising zeta to zeta' gives
K_m' = (rho zeta / zeta') h(s; omega0, zeta') = K_m D(s) / D'(s) (exactly for real rho, to
O(zeta) for complex), D = s^2 + 2 zeta omega0 s + omega0^2, and the same for the excitation.
Far from omega0 the terms are unchanged to O(zeta'); the peak drops by zeta / zeta'.

Importable with boatsim's own venv (numpy only).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics import radiation
from boat_dynamics.physics.hydro import HydroCoefficients
from boat_dynamics.physics.radiation import MAX_ORDER, RadiationMemory


@dataclass(frozen=True)
class GapMode:
    """One gap resonance: K_m = residue h(s; omega0, zeta), X_m = excitation h(s; omega0, zeta).

    Attributes:
        omega0: rad/s, undamped natural frequency of the pole pair.
        zeta: damping ratio (FWHM of B's peak = 2 zeta omega0).
        residue: (6, 6) symmetric, real (PSD: a pure Lorentzian B peak, B_m(omega0) =
            residue) or complex (a Fano-shaped peak: the imaginary part is the dispersive
            part of the interference with the background); mode_kernel gives the exact form.
        excitation: (D, 6) complex, the mode's diffraction force at omega0 per unit wave
            amplitude, on the file's directions (zeros if unknown).
    """

    omega0: float
    zeta: float
    residue: np.ndarray
    excitation: np.ndarray


def shape(omega: np.ndarray, omega0: float, zeta: float) -> np.ndarray:
    """(W,) complex h(i omega) = 2 zeta omega0 s / (s^2 + 2 zeta omega0 s + omega0^2)."""
    s = 1j * np.asarray(omega, dtype=float)
    return 2.0 * zeta * omega0 * s / (s * s + 2.0 * zeta * omega0 * s + omega0 * omega0)


def pole(omega0: float, zeta: float) -> tuple[complex, complex]:
    """The upper pole p = -zeta omega0 + i omega0 sqrt(1 - zeta^2) and c, h = c/(s-p) + cc."""
    p = complex(-zeta * omega0, omega0 * np.sqrt(1.0 - zeta**2))
    return p, 2.0 * zeta * omega0 * p / (p - p.conjugate())


def mode_kernel(modes: list[GapMode], omega: np.ndarray) -> np.ndarray:
    """(W, 6, 6) complex sum of the modes' K_m(i omega) = B_m + i omega (A_m - A_inf).

    K_m = rho c / (s - p) + conj(rho c) / (s - conj p): the kernel of a real K(t); for a real
    residue rho it is rho h(s). A complex rho (a Fano-shaped peak) stays a real kernel.
    """
    s = 1j * np.asarray(omega, dtype=float)
    out = np.zeros((len(s), 6, 6), complex)
    for m in modes:
        p, c = pole(m.omega0, m.zeta)
        r = np.asarray(m.residue, complex) * c
        out += r[None] / (s - p)[:, None, None] + r.conj()[None] / (s - p.conjugate())[:, None, None]
    return out


def mode_excitation(modes: list[GapMode], omega: np.ndarray) -> np.ndarray:
    """(W, D, 6) complex sum of the modes' diffraction terms, excitation conj(h(i omega)).

    The file's excitation is Capytaine's, in the e^{-i omega t} convention, so its poles sit
    at conj(p): the term is C conj(h) (checked: fits the local solves to 0.1-2 %, h does not).
    """
    return sum(np.conj(shape(omega, m.omega0, m.zeta))[:, None, None] * m.excitation[None]
               for m in modes)


def psd_part(residue: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (6,) and eigenvectors (6, 6) of the symmetric real part of a residue."""
    re = np.real(residue)
    return np.linalg.eigh(0.5 * (re + re.T))


def mode_memory(modes: list[GapMode], rank: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Poles (N,), input (N, 6), output (6, N) of the modes' pole pairs (RadiationMemory form).

    Per mode the pole-p residue r = rho c is cut to its ``rank`` leading singular triplets
    (a single gap mode is rank one: r = sigma u v^H); each is a pole p with output sigma u,
    input v^H, and its mirror conj(p) with the conjugates.
    """
    poles, inputs, outputs = [], [], []
    for m in modes:
        p, c = pole(m.omega0, m.zeta)
        u, sig, vh = np.linalg.svd(np.asarray(m.residue, complex) * c)
        for k in range(rank):
            for pk, out, inp in ((p, sig[k] * u[:, k], vh[k]),
                                 (p.conjugate(), np.conj(sig[k] * u[:, k]), np.conj(vh[k]))):
                poles.append(pk)
                inputs.append(inp)
                outputs.append(out)
    if not poles:
        return np.zeros(0, complex), np.zeros((0, 6), complex), np.zeros((6, 0), complex)
    return np.array(poles), np.array(inputs), np.array(outputs).T


def with_kernel_change(hydro: HydroCoefficients, delta_k: np.ndarray,
                       delta_x: np.ndarray | None = None, note: str = "") -> HydroCoefficients:
    """hydro with B += Re dK, A += Im dK / omega (and diffraction += dX); A_inf unchanged."""
    w = hydro.omega[:, None, None]
    diffraction = hydro.diffraction if delta_x is None else hydro.diffraction + delta_x
    return dataclasses.replace(
        hydro, radiation_damping=hydro.radiation_damping + delta_k.real,
        added_mass=hydro.added_mass + delta_k.imag / w, diffraction=diffraction,
        source=hydro.source + note)


def smooth_part(hydro: HydroCoefficients, modes: list[GapMode]) -> HydroCoefficients:
    """The file minus the modes: K_smooth = K_file - sum K_m (A, B and the diffraction force)."""
    return with_kernel_change(hydro, -mode_kernel(modes, hydro.omega),
                              -mode_excitation(modes, hydro.omega), " (gap modes removed)")


def _fit_smooth(smooth: HydroCoefficients, target: HydroCoefficients, extra: tuple,
                max_order: int) -> RadiationMemory:
    """radiation.fit_memory's Hankel fit of ``smooth``, orders <= max_order, each realization
    joined with the ``extra`` poles and judged by _fit_error against ``target``; the best."""
    step = np.pi / (8.0 * smooth.omega[-1])
    probe = radiation.retardation_kernel(smooth, np.arange(0.0, 60.0, step))
    envelope = np.abs(probe).max(axis=(1, 2))
    loud = np.nonzero(envelope > 0.01 * envelope.max())[0]
    duration = float(np.clip(1.5 * step * loud[-1], 5.0, 40.0))
    rows = int(min(np.ceil(duration / (2 * step)), 150))
    samples = probe[: 2 * rows + 1]
    scale = np.sqrt(np.maximum(np.diagonal(samples[0]), 1e-12 * samples[0].max()))
    svd = radiation._hankel_svd(samples / scale[:, None] / scale[None, :])
    best = None
    for order in range(4, max_order + 1, 2):
        poles, inp, out = radiation._realize(svd, order, step)
        memory = RadiationMemory(np.concatenate([poles, extra[0]]),
                                 np.concatenate([inp * scale[None, :], extra[1]]),
                                 np.concatenate([scale[:, None] * out, extra[2]], axis=1), 0.0)
        error = radiation._fit_error(memory.response(target.omega), target)
        if best is None or error < best.error:
            best = dataclasses.replace(memory, error=error)
    return best


def fit_with_modes(hydro: HydroCoefficients, modes: list[GapMode], blockwise: bool = True,
                   fine: HydroCoefficients | None = None, fitter: str = "vf") -> RadiationMemory:
    """Memory = Hankel fit of (file - modes) joined with the modes' exact pole pairs.

    The smooth part gets the orders left after the modes' poles (MAX_ORDER in all). With
    ``blockwise`` it is realized per block of dofs that the file couples (for a hull symmetric
    fore-aft and port-starboard: surge-pitch, sway-roll, heave, yaw), the orders shared to
    minimize the largest block error (each judged on all points with the file's scales and on
    the points outside min(3 FWHM, 0.21 rad/s) of the modes with their own scales), then the
    rest spent; else with radiation's one 6 x 6 realization. ``fitter``: "vf" (default) fits
    each block by vector fitting in the frequency domain (:func:`_fit_blocks_vf`), "hankel" by
    Kung's realization like the product. The returned ``error`` is radiation._fit_error of the
    union against the original ``hydro`` (Otter: 0.079 vf, 0.132 hankel blockwise, 0.201 with
    one realization, 0.80 for radiation.fit_memory of the file alone).
    ``fine``: a solve of the same mesh on a finer grid (same last frequency); its B minus the
    modes makes the kernel (the file's 0.42 rad/s grid under-samples the smooth part's own
    humps: KK of its piecewise-linear B misses the file's A by up to 6.7 %, of the fine one's
    by up to 4.7 %).
    """
    extra = mode_memory(modes)
    smooth = smooth_part(hydro if fine is None else fine, modes)
    budget = MAX_ORDER - extra[0].shape[0]
    if not blockwise:
        return _fit_smooth(smooth, hydro, extra, budget)
    if fitter == "vf":
        return _fit_blocks_vf(smooth, hydro, extra, budget, ~band_mask(hydro.omega, modes, cap=0.21),
                              None if fine is None else smooth)
    return _fit_blocks(smooth, hydro, extra, budget, ~band_mask(hydro.omega, modes, cap=0.21),
                       None if fine is None else smooth)


def dof_blocks(hydro: HydroCoefficients, rel: float = 1e-6) -> list[list[int]]:
    """Groups of dofs coupled in B or A (connected components; |X_ij| > rel sqrt(X_ii X_jj))."""
    b = np.abs(hydro.radiation_damping).max(axis=0) + np.abs(hydro.added_mass - hydro.added_mass_inf).max(axis=0)
    d = np.sqrt(np.outer(np.diag(b), np.diag(b))) + 1e-300
    link = b > rel * d
    groups, seen = [], set()
    for i in range(6):
        if i in seen:
            continue
        todo, g = [i], set()
        while todo:
            k = todo.pop()
            if k not in g:
                g.add(k)
                todo += [j for j in range(6) if link[k, j]]
        seen |= g
        groups.append(sorted(g))
    return groups


#: Kernel samples per period of 2 omega_W, and the seconds of kernel the block Hankel covers.
SAMPLES_PER_PERIOD, KERNEL_SECONDS = 3.0, 30.0


def _block_realizations(samples: np.ndarray, step: float, max_order: int) -> list[tuple]:
    """Kung realizations (poles, input, output) of orders 1..max_order of a (T, n, n) kernel."""
    n = samples.shape[1]
    rows = (samples.shape[0] - 1) // 2
    k = np.arange(rows)
    h0 = samples[k[:, None] + k[None, :]].transpose(0, 2, 1, 3).reshape(n * rows, n * rows)
    h1 = samples[k[:, None] + k[None, :] + 1].transpose(0, 2, 1, 3).reshape(n * rows, n * rows)
    u, s, vt = np.linalg.svd(h0)
    out = []
    for order in range(1, min(max_order, len(s)) + 1):
        root = np.sqrt(s[:order])
        left, right = u[:, :order] * root, root[:, None] * vt[:order]
        disc = (u[:, :order].T @ h1 @ vt[:order].T) / (root[:, None] * root[None, :])
        lam, vec = np.linalg.eig(disc)
        poles = np.log(lam.astype(complex)) / step
        poles = np.where(poles.real < 0.0, poles, -np.abs(poles.real) - 1e-3 + 1j * poles.imag)
        out.append((poles, np.linalg.solve(vec, right[:, :n]), left[:n] @ vec))
    return out


def _kernel_of(h: HydroCoefficients) -> np.ndarray:
    """(W, 6, 6) K^ = B + i omega (A - A_inf) of coefficients."""
    return h.radiation_damping + 1j * h.omega[:, None, None] * (h.added_mass - h.added_mass_inf)


#: Refit the outputs of each block realization to K^ by linear least squares (fixed poles).
#: Off: on the Otter it did not help (0.24 on the file grid alone, 0.16 with the fine grid).
REFIT = False


def _fit_blocks(smooth: HydroCoefficients, target: HydroCoefficients, extra: tuple,
                budget: int, keep: np.ndarray | None = None,
                fine_smooth: HydroCoefficients | None = None) -> RadiationMemory:
    """Per-block Hankel realizations of ``smooth`` (plus the modes ``extra``), orders shared by
    :func:`_share_orders` within ``budget``, each judged by :func:`_block_error` against
    ``target`` with the modes' response included."""
    step = np.pi / (SAMPLES_PER_PERIOD * smooth.omega[-1])  # per period of 2 omega_W
    rows = int(np.ceil(KERNEL_SECONDS / (2 * step)))
    samples = radiation.retardation_kernel(smooth, np.arange(0.0, (2 * rows + 1) * step, step))[: 2 * rows + 1]
    w = target.omega
    mode_resp = RadiationMemory(*extra, 0.0).response(w) if extra[0].size else np.zeros((len(w), 6, 6), complex)
    k_target = [(w, _kernel_of(target) - mode_resp)]
    if fine_smooth is not None:
        k_target.append((fine_smooth.omega, _kernel_of(fine_smooth)))
    bsc = np.sqrt(np.abs(np.diagonal(target.radiation_damping, axis1=1, axis2=2)).max(axis=0)) + 1e-9
    asc = np.sqrt(np.abs(np.diagonal(target.added_mass, axis1=1, axis2=2)).max(axis=0)) + 1e-9
    blocks, cands, errs = dof_blocks(smooth), [], []
    for idx in blocks:
        sub = samples[:, idx][:, :, idx]
        scale = np.sqrt(np.maximum(np.diagonal(sub[0]), 1e-12 * np.abs(sub[0]).max()))
        reals = _block_realizations(sub / scale[:, None] / scale[None, :], step, budget)
        c, e = [], []
        for poles, inp, out in reals:
            inp6 = np.zeros((len(poles), 6), complex); inp6[:, idx] = inp * scale[None, :]
            out6 = np.zeros((6, len(poles)), complex); out6[idx] = scale[:, None] * out
            if REFIT:
                tg = [(ww, kk[:, idx][:, :, idx]) for ww, kk in k_target]
                out6[idx] = _refit_outputs(poles, inp6[:, idx], tg, bsc[idx], asc[idx])
            resp = RadiationMemory(poles, inp6, out6, 0.0).response(w) + mode_resp
            c.append((poles, inp6, out6))
            e.append(_block_error(resp, target, idx, keep))
        cands.append(c); errs.append(np.array(e))
    order = _share_orders(errs, budget)
    parts = [cands[b][order[b]] for b in range(len(blocks))] + [extra]
    mem = RadiationMemory(np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
                          np.concatenate([p[2] for p in parts], axis=1), 0.0)
    return dataclasses.replace(mem, error=radiation._fit_error(mem.response(w), target))


def _refit_outputs(poles: np.ndarray, inp: np.ndarray,
                   targets: list[tuple[np.ndarray, np.ndarray]], bsc: np.ndarray,
                   asc: np.ndarray) -> np.ndarray:
    """(n, N) outputs for fixed poles (N,) and inputs (N, n) fitting a block's K^ (W, n, n).

    Linear least squares on K^(omega) and K^(-omega) = conj K^(omega) (so the kernel stays
    real), the B part of entry (i, j) weighted 1 / (bsc_i bsc_j) and the A part (Im K^ / omega)
    1 / (asc_i asc_j), as radiation._fit_error weighs them.
    """
    n, N = inp.shape[1], len(poles)
    out = np.zeros((n, N), complex)
    for i in range(n):
        mats, rhs = [], []
        for w, k in targets:
            for sign in (1.0, -1.0):
                g = 1.0 / (1j * sign * w[:, None] - poles[None, :])
                kk = k if sign > 0 else np.conj(k)
                for j in range(n):
                    basis = g * inp[None, :, j]
                    full = np.concatenate([basis, 1j * basis], axis=1)  # real unknowns Re, Im
                    wb = bsc[i] * bsc[j]
                    wa = asc[i] * asc[j] * np.abs(w)[:, None]
                    mats += [full.real / wb, full.imag / wa]
                    rhs += [kk[:, i, j].real / wb, kk[:, i, j].imag / wa[:, 0]]
        x, *_ = np.linalg.lstsq(np.concatenate(mats), np.concatenate(rhs), rcond=None)
        out[i] = x[:N] + 1j * x[N:]
    return out


def _vf_poles(s: np.ndarray, F: np.ndarray, wr: np.ndarray, wi: np.ndarray, poles: np.ndarray,
              iters: int = 30) -> np.ndarray:
    """Vector fitting's pole relocation (Gustavsen & Semlyen 1999), no constant term:
    F(s) (P, E) ~ sum_k r_k / (s - a_k); the real and imaginary parts of each row weighted wr,
    wi (P, E). Unstable poles are reflected."""
    P, E = F.shape
    for _ in range(iters):
        N = len(poles)
        C = 1.0 / (s[:, None] - poles[None, :])
        M = np.zeros((P * E, E * N + N), complex)
        for e in range(E):
            M[e * P:(e + 1) * P, e * N:(e + 1) * N] = C
            M[e * P:(e + 1) * P, E * N:] = -F[:, e:e + 1] * C
        x = _weighted_lstsq(M, F.T.reshape(-1), wr.T.reshape(-1), wi.T.reshape(-1))
        new = np.linalg.eigvals(np.diag(poles) - np.ones((N, 1)) @ x[None, E * N:])
        poles = np.where(new.real > 0.0, -new.real + 1j * new.imag, new)
    return poles


def _weighted_lstsq(M: np.ndarray, rhs: np.ndarray, wr: np.ndarray, wi: np.ndarray) -> np.ndarray:
    """Complex x minimizing |wr Re(M x - rhs)|^2 + |wi Im(M x - rhs)|^2."""
    big = np.block([[M.real * wr[:, None], -M.imag * wr[:, None]],
                    [M.imag * wi[:, None], M.real * wi[:, None]]])
    x = np.linalg.lstsq(big, np.concatenate([rhs.real * wr, rhs.imag * wi]), rcond=None)[0]
    return x[:M.shape[1]] + 1j * x[M.shape[1]:]


def _vf_block(targets: list[tuple[np.ndarray, np.ndarray]], idx: list[int], bsc: np.ndarray,
              asc: np.ndarray, npoles: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vector fit of one block's smooth K^ with ``npoles`` poles (a conjugate-closed set).

    Fitted at +omega and -omega (conj) so the kernel is real; each entry (i, j) weighted as
    radiation._fit_error: B by 1 / (bsc_i bsc_j), A = Im K^ / omega by 1 / (asc_i asc_j).
    Returns the memory's (poles, input (N, 6), output (6, N)): one state per pole and per
    nonzero singular value of its residue matrix, conjugate poles with conjugate vectors.
    """
    ents = [(i, j) for a, i in enumerate(idx) for j in idx[a:]]
    ss, ff, wr, wi = [], [], [], []
    for w, k in targets:
        for sign in (1.0, -1.0):
            ss.append(1j * sign * w)
            ff.append(np.stack([k[:, i, j] if sign > 0 else np.conj(k[:, i, j]) for i, j in ents], 1))
            wr.append(np.stack([np.full(len(w), 1.0 / (bsc[i] * bsc[j])) for i, j in ents], 1))
            wi.append(np.stack([1.0 / (w * asc[i] * asc[j]) for i, j in ents], 1))
    s, F, WR, WI = (np.concatenate(x) for x in (ss, ff, wr, wi))
    im = np.linspace(0.5, 18.0, max(npoles // 2, 1))
    poles = _vf_poles(s, F, WR, WI, np.concatenate([-im / 50 + 1j * im, -im / 50 - 1j * im]))
    poles = poles[poles.imag >= 0.0]  # keep the upper half, mirror it below
    full = np.concatenate([poles, np.conj(poles[poles.imag > 0.0])])
    C = 1.0 / (s[:, None] - full[None, :])
    res = np.stack([_weighted_lstsq(C, F[:, e], WR[:, e], WI[:, e]) for e in range(len(ents))], 1)
    pl, inp, out = [], [], []
    for k, p in enumerate(poles):
        r = np.zeros((6, 6), complex)
        for e, (i, j) in enumerate(ents):
            r[i, j] = r[j, i] = res[k, e]
        if p.imag == 0.0:
            r = r.real.astype(complex)
        u, sv, vh = np.linalg.svd(r)
        for q in range(len(idx)):
            if sv[q] > 1e-9 * sv[0]:
                pl.append(p); out.append(sv[q] * u[:, q]); inp.append(vh[q])
                if p.imag > 0.0:
                    pl.append(np.conj(p)); out.append(np.conj(sv[q] * u[:, q])); inp.append(np.conj(vh[q]))
    return np.array(pl), np.array(inp).reshape(-1, 6), np.array(out).reshape(-1, 6).T


#: Judge the VF candidates also on the points away from the peaks with their own scales (the
#: stricter (b) metric); off: by radiation._fit_error on all points (Otter: 0.079 vs 0.198).
VF_JUDGE_SUBSET = False


def _fit_blocks_vf(smooth: HydroCoefficients, target: HydroCoefficients, extra: tuple,
                   budget: int, keep: np.ndarray, fine_smooth: HydroCoefficients | None = None
                   ) -> RadiationMemory:
    """Per-block vector fits of ``smooth`` (weights from the scales at ``keep``, away from the
    gap peaks), 2..16 poles each, the states shared by :func:`_share_orders` within ``budget``,
    each block judged by :func:`_block_error` with the modes' response included."""
    w = target.omega
    mode_resp = RadiationMemory(*extra, 0.0).response(w) if extra[0].size else np.zeros((len(w), 6, 6), complex)
    targets = [(w, _kernel_of(target) - mode_resp)]
    if fine_smooth is not None:
        targets.append((fine_smooth.omega, _kernel_of(fine_smooth)))
    bsc = np.sqrt(np.abs(np.diagonal(target.radiation_damping[keep], axis1=1, axis2=2)).max(axis=0)) + 1e-9
    asc = np.sqrt(np.abs(np.diagonal(target.added_mass[keep], axis1=1, axis2=2)).max(axis=0)) + 1e-9
    blocks, cands, errs = dof_blocks(smooth), [], []
    for idx in blocks:
        c, e = [], []
        for npoles in range(2, 17, 2):
            mem = _vf_block(targets, idx, bsc, asc, npoles)
            resp = RadiationMemory(*mem, 0.0).response(w) + mode_resp
            c.append(mem); e.append(_block_error(resp, target, idx, keep if VF_JUDGE_SUBSET else None))
        cands.append(c); errs.append(e)
    pick = _share_states(errs, [[len(m[0]) for m in c] for c in cands], budget)
    parts = [cands[b][pick[b]] for b in range(len(blocks))] + [extra]
    mem = RadiationMemory(np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
                          np.concatenate([p[2] for p in parts], axis=1), 0.0)
    return dataclasses.replace(mem, error=radiation._fit_error(mem.response(w), target))


def _share_states(errs: list[list[float]], costs: list[list[int]], budget: int) -> list[int]:
    """Candidate per block minimizing the largest block error with total cost <= budget, then
    the rest spent on the worst blocks (candidates cost ``costs`` states)."""
    def cheapest(b, tau):
        ok = [k for k in range(len(errs[b])) if errs[b][k] <= tau]
        return min(ok, key=lambda k: costs[b][k]) if ok else None
    pick = None
    for tau in sorted({e for es in errs for e in es}):
        cand = [cheapest(b, tau) for b in range(len(errs))]
        if None not in cand and sum(costs[b][k] for b, k in enumerate(cand)) <= budget:
            pick = cand
            break
    if pick is None:
        return [int(np.argmin(costs[b])) for b in range(len(errs))]
    for b in sorted(range(len(errs)), key=lambda b: -errs[b][pick[b]]):
        room = budget - sum(costs[c][k] for c, k in enumerate(pick)) + costs[b][pick[b]]
        ok = [k for k in range(len(errs[b])) if costs[b][k] <= room]
        pick[b] = min(ok, key=lambda k: errs[b][k])
    return pick


def _share_orders(errs: list[np.ndarray], budget: int) -> list[int]:
    """Indices (order - 1) per block minimizing the largest block error with total <= budget:
    the smallest threshold tau whose cheapest orders meeting it fit the budget."""
    def need(tau):
        return [int(np.nonzero(e <= tau)[0][0]) if (e <= tau).any() else None for e in errs]
    taus = np.unique(np.concatenate(errs))
    best = [int(np.argmin(e[:max(1, budget // len(errs))])) for e in errs]
    for tau in taus:
        idx = need(tau)
        if None not in idx and sum(i + 1 for i in idx) <= budget:
            break
    else:
        return best
    for b in sorted(range(len(errs)), key=lambda b: -errs[b][idx[b]]):  # spend what is left
        room = budget - sum(i + 1 for i in idx) + idx[b]
        idx[b] = int(np.argmin(errs[b][: room + 1]))
    return idx


def _block_error(resp: np.ndarray, target: HydroCoefficients, idx: list[int],
                 keep: np.ndarray | None = None) -> float:
    """radiation._fit_error restricted to the entries of the dofs ``idx``; with ``keep``, the
    larger of that and the same on the grid points ``keep`` alone (their own scales)."""
    if keep is not None and not keep.all():
        sub = dataclasses.replace(target, omega=target.omega[keep], added_mass=target.added_mass[keep],
                                  radiation_damping=target.radiation_damping[keep])
        return max(_block_error(resp, target, idx), _block_error(resp[keep], sub, idx))
    full = np.zeros_like(resp)
    k = np.ix_(range(resp.shape[0]), idx, idx)
    full[k] = resp[k]
    w = target.omega
    b = target.radiation_damping.copy(); a = target.added_mass - target.added_mass_inf
    mask = np.zeros((6, 6), bool); mask[np.ix_(idx, idx)] = True
    b_err = np.where(mask, np.abs(full.real - b).max(axis=0), 0.0)
    a_err = np.where(mask, np.abs(full.imag / w[:, None, None] - a).max(axis=0), 0.0)
    bs = np.abs(np.diagonal(target.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    as_ = np.abs(np.diagonal(target.added_mass, axis1=1, axis2=2)).max(axis=0)
    return float(max((b_err / (np.sqrt(np.outer(bs, bs)) + 1e-12)).max(),
                     (a_err / (np.sqrt(np.outer(as_, as_)) + 1e-12)).max()))


def band_mask(omega: np.ndarray, modes: list[GapMode], widths: float = 3.0,
              floor: float = 0.0, cap: float = np.inf) -> np.ndarray:
    """(W,) True within omega0 +- min(max(widths * FWHM, floor), cap) of any mode."""
    m = np.zeros(len(omega), bool)
    for g in modes:
        m |= np.abs(omega - g.omega0) <= min(max(widths * 2.0 * g.zeta * g.omega0, floor), cap)
    return m


def fit_error_where(response: np.ndarray, hydro: HydroCoefficients, keep: np.ndarray) -> float:
    """radiation._fit_error restricted to the grid points ``keep`` (scales from those points)."""
    sub = dataclasses.replace(hydro, omega=hydro.omega[keep],
                              added_mass=hydro.added_mass[keep],
                              radiation_damping=hydro.radiation_damping[keep])
    return radiation._fit_error(response[keep], sub)


def treat_gap_modes(hydro: HydroCoefficients, modes: list[GapMode],
                    zeta: float | list[float]) -> HydroCoefficients:
    """The coefficients with each mode's damping ratio raised to ``zeta`` (never lowered).

    Coupling held fixed: K_m -> K_m D / D', X_m -> X_m D / D' (module docstring); applied to
    A, B (Kramers-Kronig consistent by construction) and to the diffraction force.
    """
    zetas = np.broadcast_to(np.asarray(zeta, float), (len(modes),))
    new = [treated_modes([m], z)[0] for m, z in zip(modes, zetas)]
    dk = mode_kernel(new, hydro.omega) - mode_kernel(modes, hydro.omega)
    dx = mode_excitation(new, hydro.omega) - mode_excitation(modes, hydro.omega)
    return with_kernel_change(hydro, dk, dx, f" (gap modes damped to zeta {zetas.max():g})")


def treated_modes(modes: list[GapMode], zeta: float) -> list[GapMode]:
    """The modes with zeta raised to ``zeta`` at fixed coupling (residues scaled zeta/zeta'):
    as :func:`treat_gap_modes` leaves them, for the memory of the treated file."""
    return [dataclasses.replace(m, zeta=max(zeta, m.zeta), residue=m.residue * m.zeta / max(zeta, m.zeta),
                                excitation=m.excitation * m.zeta / max(zeta, m.zeta)) for m in modes]


def save_like(original_path: str, out_path: str, hydro: HydroCoefficients) -> None:
    """Write ``hydro``'s A, B and diffraction into a copy of the original .npz (same format)."""
    with np.load(original_path, allow_pickle=False) as d:
        arrays = {k: d[k] for k in d.files}
    arrays["added_mass"] = hydro.added_mass
    arrays["radiation_damping"] = hydro.radiation_damping
    arrays["diffraction"] = hydro.diffraction
    np.savez_compressed(out_path, **arrays)


def save_modes(path: str, modes: list[GapMode], names: list[str]) -> None:
    """Write modes to an .npz (omega0 (M,), zeta (M,), residue (M,6,6), excitation (M,D,6))."""
    np.savez_compressed(path, names=np.array(names), omega0=np.array([m.omega0 for m in modes]),
                        zeta=np.array([m.zeta for m in modes]),
                        residue=np.array([m.residue for m in modes]),
                        excitation=np.array([m.excitation for m in modes]))


def load_modes(path: str) -> list[GapMode]:
    """The modes :func:`save_modes` wrote."""
    with np.load(path, allow_pickle=False) as d:
        return [GapMode(float(w0), float(z), r, x) for w0, z, r, x in
                zip(d["omega0"], d["zeta"], d["residue"], d["excitation"])]
