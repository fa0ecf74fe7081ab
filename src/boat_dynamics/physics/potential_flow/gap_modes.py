"""A multihull's gap resonances as explicit pole pairs, and the radiation memory around them.

Between the hulls of a catamaran the water sloshes at frequencies omega^2 ~ g n pi / b (b the
gap): potential flow gives each a resonance narrower than any practical frequency grid (the
shipped Otter's are 0.002 to 0.38 rad/s wide, Q 25 to 8,600), whose height on the grid means
nothing and whose added-mass tails no smooth fit can follow. A file that carries its gap modes
(:class:`~boat_dynamics.physics.potential_flow.hydro.GapMode`, from local solves around each narrow
peak) is fitted in two parts: the modes' pole pairs exactly (each rank one), and the rest of the
file, K - sum K_m, which is smooth and Kramers-Kronig consistent, by vector fitting
(Gustavsen & Semlyen 1999, "Rational approximation of frequency domain responses by vector
fitting", IEEE Trans. Power Delivery 14(3)) per block of dofs the file couples. The memory
keeps the modes as potential flow gives them (no added gap damping).

Measured (96 states): the shipped Otter's file (V pontoons, 17 modes) within
4.2 % (B) and 4.4 % (A) of the file outside omega0 +- 3 widths of every mode, 4.4 % at every
grid point; the box-pontoon Otter's (15 modes) within 4.4 %, where the Hankel fit of
:func:`.radiation.fit_memory` misses it by 80 %.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import GapMode, HydroCoefficients
from boat_dynamics.physics.potential_flow.radiation import RadiationMemory, _fit_error, fit_memory

__all__ = ["MODE_MAX_ORDER", "band_mask", "dof_blocks", "fit_with_modes", "memory_of",
           "mode_excitation", "mode_kernel", "mode_memory", "smooth_part"]

#: The states of a memory with gap modes (the modes' two each included). The Otter's 17 modes
#: and the surge-pitch interference between its pontoons need 96 to fit within 5 % (64 give 6.6 %).
MODE_MAX_ORDER = 96
#: Vector fitting's pole relocations per candidate.
RELOCATIONS = 30
#: The candidate pole counts of each block's fit.
POLE_COUNTS = tuple(range(2, 17, 2))
#: A relocated pole whose imaginary part is at most this fraction of its modulus is real.
REAL_POLE = 1e-6


def memory_of(hydro: HydroCoefficients) -> RadiationMemory:
    """The radiation memory of a file.

    :func:`fit_with_modes` if it has gap modes, else :func:`.radiation.fit_memory`.
    """
    return fit_with_modes(hydro) if hydro.gap_modes else fit_memory(hydro)


def _pole(mode: GapMode) -> tuple[complex, complex]:
    """The upper pole p and c of h = c / (s - p) + conj(c) / (s - conj p)."""
    p = complex(-mode.zeta * mode.omega0, mode.omega0 * np.sqrt(1.0 - mode.zeta**2))
    return p, 2.0 * mode.zeta * mode.omega0 * p / (p - p.conjugate())


def mode_kernel(modes: tuple[GapMode, ...], omega: np.ndarray) -> np.ndarray:
    """(W, 6, 6) complex, the modes' K_m(i omega) = B_m + i omega (A_m - A_inf), summed."""
    s = 1j * np.asarray(omega, dtype=float)[:, None, None]
    out = np.zeros((s.shape[0], 6, 6), complex)
    for m in modes:
        p, c = _pole(m)
        r = np.asarray(m.residue, complex) * c
        out += r / (s - p) + r.conj() / (s - p.conjugate())
    return out


def mode_excitation(modes: tuple[GapMode, ...], omega: np.ndarray) -> np.ndarray:
    """(W, D, 6) complex, the modes' diffraction forces C conj(h(i omega)), summed."""
    w = np.asarray(omega, dtype=float)
    out = 0.0
    for m in modes:
        s = 1j * w
        h = 2.0 * m.zeta * m.omega0 * s / (s * s + 2.0 * m.zeta * m.omega0 * s + m.omega0**2)
        out = out + np.conj(h)[:, None, None] * m.excitation[None]
    return out


def smooth_part(hydro: HydroCoefficients) -> HydroCoefficients:
    """The file without its gap modes: A, B and the diffraction force less the modes'."""
    k = mode_kernel(hydro.gap_modes, hydro.omega)
    return replace(hydro, radiation_damping=hydro.radiation_damping - k.real,
                   added_mass=hydro.added_mass - k.imag / hydro.omega[:, None, None],
                   diffraction=hydro.diffraction - mode_excitation(hydro.gap_modes,
                                                                   hydro.omega),
                   gap_modes=())


def mode_memory(modes: tuple[GapMode, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Poles (2M,), input (2M, 6), output (6, 2M): each mode's rank-one pole pair.

    The residue rho c of the pole p is cut to its leading singular triplet sigma u v^H (a gap
    mode is rank one: the second singular value of the Otter's is under 2.5 % of the first):
    the pole p with output sigma u and input v^H, and conj(p) with their conjugates.
    """
    poles, inputs, outputs = [], [], []
    for m in modes:
        p, c = _pole(m)
        u, sig, vh = np.linalg.svd(np.asarray(m.residue, complex) * c)
        poles += [p, p.conjugate()]
        outputs += [sig[0] * u[:, 0], np.conj(sig[0] * u[:, 0])]
        inputs += [vh[0], np.conj(vh[0])]
    if not poles:
        return np.zeros(0, complex), np.zeros((0, 6), complex), np.zeros((6, 0), complex)
    return np.array(poles), np.array(inputs), np.array(outputs).T


def band_mask(omega: np.ndarray, modes: tuple[GapMode, ...], widths: float = 3.0
              ) -> np.ndarray:
    """(W,) bool, True within omega0 +- ``widths`` half-height widths (2 zeta omega0) of a mode."""
    near = np.zeros(np.shape(omega), bool)
    for m in modes:
        near |= np.abs(np.asarray(omega) - m.omega0) <= widths * 2.0 * m.zeta * m.omega0
    return near


def dof_blocks(hydro: HydroCoefficients, rel: float = 1e-6) -> list[list[int]]:
    """The groups of dofs that A - A_inf or B couple (above ``rel`` of their diagonals).

    For a hull symmetric fore-aft and port-starboard: surge-pitch, sway-roll, heave, yaw.
    """
    size = (np.abs(hydro.radiation_damping).max(axis=0)
            + np.abs(hydro.added_mass - hydro.added_mass_inf).max(axis=0))
    link = size > rel * np.sqrt(np.outer(np.diag(size), np.diag(size))) + 1e-300
    groups: list[list[int]] = []
    seen: set[int] = set()
    for start in range(6):
        if start in seen:
            continue
        todo, group = [start], set()
        while todo:
            k = todo.pop()
            if k not in group:
                group.add(k)
                todo += [j for j in range(6) if link[k, j]]
        seen |= group
        groups.append(sorted(group))
    return groups


def fit_with_modes(hydro: HydroCoefficients) -> RadiationMemory:
    """The memory of a file with gap modes: their pole pairs plus a vector fit of the rest.

    Each block of :func:`dof_blocks` gets a vector fit of ``hydro`` less the modes' pole pairs
    (:func:`mode_memory`) with 2 to
    16 poles; the candidates are shared out so that the largest block error is least within
    :data:`MODE_MAX_ORDER` states in all (the modes' included), each judged as
    :func:`.radiation.fit_memory` judges a fit, against the file itself. The ``error`` is
    that of the whole memory against the file.
    """
    modes = mode_memory(hydro.gap_modes)
    w = hydro.omega
    around = ~band_mask(w, hydro.gap_modes)
    bsc = np.sqrt(np.abs(np.diagonal(hydro.radiation_damping[around], axis1=1, axis2=2))
                  .max(axis=0)) + 1e-9
    asc = np.sqrt(np.abs(np.diagonal(hydro.added_mass[around], axis1=1, axis2=2))
                  .max(axis=0)) + 1e-9
    of_modes = RadiationMemory(*modes, 0.0).response(w)  # the rank-one pairs' own response
    kernel = (hydro.radiation_damping + 1j * w[:, None, None]
              * (hydro.added_mass - hydro.added_mass_inf) - of_modes)
    candidates, errors = [], []
    for block in dof_blocks(hydro):
        fits = [_fit_block(w, kernel, block, bsc, asc, n) for n in POLE_COUNTS]
        candidates.append(fits)
        errors.append([_block_error(RadiationMemory(*f, 0.0).response(w) + of_modes, hydro,
                                    block) for f in fits])
    pick = _share_states(errors, [[f[0].shape[0] for f in c] for c in candidates],
                         MODE_MAX_ORDER - modes[0].shape[0])
    parts = [c[k] for c, k in zip(candidates, pick, strict=True)] + [modes]
    memory = RadiationMemory(np.concatenate([p[0] for p in parts]),
                             np.concatenate([p[1] for p in parts]),
                             np.concatenate([p[2] for p in parts], axis=1), 0.0)
    return replace(memory, error=_fit_error(memory.response(w), hydro))


def _fit_block(w: np.ndarray, kernel: np.ndarray, block: list[int], bsc: np.ndarray,
               asc: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vector fit of one block of ``kernel`` (W, 6, 6) with ``count`` poles: memory arrays.

    Fitted at +omega and -omega (the conjugate) so that the kernel is real; the B part of
    entry (i, j) weighted 1 / (bsc_i bsc_j), the A part 1 / (omega asc_i asc_j), as
    :func:`.radiation.fit_memory` judges. One state per pole and per non-zero singular value
    of its residue matrix.
    """
    entries = [(i, j) for a, i in enumerate(block) for j in block[a:]]
    s = np.concatenate([1j * w, -1j * w])
    data = np.stack([np.concatenate([kernel[:, i, j], np.conj(kernel[:, i, j])])
                     for i, j in entries], axis=1)
    wr = np.stack([np.full(2 * w.size, 1.0 / (bsc[i] * bsc[j])) for i, j in entries], axis=1)
    wi = np.stack([np.concatenate([1.0 / (w * asc[i] * asc[j])] * 2) for i, j in entries],
                  axis=1)
    im = np.linspace(0.5, 1.06 * w[-1], max(count // 2, 1))
    poles = _relocate(s, data, wr, wi, np.concatenate([-im / 50 + 1j * im, -im / 50 - 1j * im]))
    # A pair that relocates onto the real axis comes back as two real poles with imaginary
    # parts of +-1e-9 relative (complex arithmetic): made real, each is one state, not a pair.
    poles = np.where(np.abs(poles.imag) <= REAL_POLE * np.abs(poles), poles.real + 0j, poles)
    poles = poles[poles.imag >= 0.0]
    both = np.concatenate([poles, np.conj(poles[poles.imag > 0.0])])
    basis = 1.0 / (s[:, None] - both[None, :])
    res = np.stack([_weighted_lstsq(basis, data[:, e], wr[:, e], wi[:, e])
                    for e in range(len(entries))], axis=1)
    return _states(poles, res, entries, len(block))


def _states(poles: np.ndarray, residues: np.ndarray, entries: list[tuple[int, int]], n: int
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Memory arrays from the upper poles and their residues per entry (a conjugate mirror)."""
    pl, inp, out = [], [], []
    for k, p in enumerate(poles):
        r = np.zeros((6, 6), complex)
        for e, (i, j) in enumerate(entries):
            r[i, j] = r[j, i] = residues[k, e]
        if p.imag == 0.0:
            r = r.real.astype(complex)
        u, sv, vh = np.linalg.svd(r)
        for q in range(n):
            if sv[q] > 1e-9 * sv[0]:
                pl.append(p)
                out.append(sv[q] * u[:, q])
                inp.append(vh[q])
                if p.imag > 0.0:
                    pl.append(np.conj(p))
                    out.append(np.conj(sv[q] * u[:, q]))
                    inp.append(np.conj(vh[q]))
    return (np.array(pl, complex), np.array(inp, complex).reshape(-1, 6),
            np.array(out, complex).reshape(-1, 6).T)


def _relocate(s: np.ndarray, data: np.ndarray, wr: np.ndarray, wi: np.ndarray,
              poles: np.ndarray) -> np.ndarray:
    """Vector fitting's pole relocation (Gustavsen & Semlyen 1999), no constant term.

    data (P, E) ~ sum_k r_k / (s - a_k), the real and imaginary parts of each row weighted wr,
    wi (P, E); :data:`RELOCATIONS` relocations, unstable poles reflected into the left half.
    """
    rows, entries = data.shape
    for _ in range(RELOCATIONS):
        n = poles.shape[0]
        basis = 1.0 / (s[:, None] - poles[None, :])
        system = np.zeros((rows * entries, entries * n + n), complex)
        for e in range(entries):
            system[e * rows:(e + 1) * rows, e * n:(e + 1) * n] = basis
            system[e * rows:(e + 1) * rows, entries * n:] = -data[:, e:e + 1] * basis
        x = _weighted_lstsq(system, data.T.reshape(-1), wr.T.reshape(-1), wi.T.reshape(-1))
        new = np.linalg.eigvals(np.diag(poles) - np.ones((n, 1)) @ x[None, entries * n:])
        poles = np.where(new.real > 0.0, -new.real + 1j * new.imag, new)
    return poles


def _weighted_lstsq(matrix: np.ndarray, rhs: np.ndarray, wr: np.ndarray, wi: np.ndarray
                    ) -> np.ndarray:
    """Complex x minimizing |wr Re(M x - rhs)|^2 + |wi Im(M x - rhs)|^2."""
    big = np.block([[matrix.real * wr[:, None], -matrix.imag * wr[:, None]],
                    [matrix.imag * wi[:, None], matrix.real * wi[:, None]]])
    x = np.linalg.lstsq(big, np.concatenate([rhs.real * wr, rhs.imag * wi]), rcond=None)[0]
    return x[:matrix.shape[1]] + 1j * x[matrix.shape[1]:]


def _block_error(response: np.ndarray, hydro: HydroCoefficients, block: list[int]) -> float:
    """:func:`.radiation.fit_memory`'s error restricted to the entries of the dofs ``block``."""
    idx = np.ix_(range(response.shape[0]), block, block)
    b_err = np.abs(response.real[idx] - hydro.radiation_damping[idx]).max(axis=0)
    a_err = np.abs(response.imag[idx] / hydro.omega[:, None, None]
                   - (hydro.added_mass - hydro.added_mass_inf)[idx]).max(axis=0)
    bs = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)[block]
    as_ = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)[block]
    return float(max((b_err / (np.sqrt(np.outer(bs, bs)) + 1e-12)).max(),
                     (a_err / (np.sqrt(np.outer(as_, as_)) + 1e-12)).max()))


def _share_states(errors: list[list[float]], costs: list[list[int]], budget: int) -> list[int]:
    """The candidate per block with the least largest error within ``budget`` states in all.

    Then what is left is spent on the worst blocks.
    """
    def cheapest(b: int, bound: float) -> int | None:
        ok = [k for k, e in enumerate(errors[b]) if e <= bound]
        return min(ok, key=lambda k: costs[b][k]) if ok else None

    pick = None
    for bound in sorted({e for es in errors for e in es}):
        choice = [cheapest(b, bound) for b in range(len(errors))]
        if None not in choice and sum(costs[b][k] for b, k in enumerate(choice)) <= budget:
            pick = choice
            break
    if pick is None:
        return [int(np.argmin(c)) for c in costs]
    for b in sorted(range(len(errors)), key=lambda b: -errors[b][pick[b]]):
        room = budget - sum(costs[c][k] for c, k in enumerate(pick)) + costs[b][pick[b]]
        pick[b] = min((k for k in range(len(errors[b])) if costs[b][k] <= room),
                      key=lambda k: errors[b][k])
    return pick
