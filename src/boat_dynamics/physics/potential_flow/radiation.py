"""Wave radiation in the time domain: the Cummins equation with a fitted state-space memory.

A hull moving with body velocity nu(t) (6-vector: surge, sway, heave, roll, pitch, yaw, about
the centre of mass) in otherwise calm water feels, by linear potential flow (Cummins 1962;
Ogilvie 1964; Newman 1977, sec. 6.16)::

    F_rad(t) = -A_inf nu'(t) - integral_0^t K(t - tau) nu(tau) dtau

with A_inf the infinite-frequency added mass (6 x 6, in the mass matrix: see
:func:`boat_dynamics.physics.body.rigid_body.integrate_coupled`) and the retardation kernel

    K(t) = (2 / pi) integral_0^inf B(omega) cos(omega t) domega

from the radiation damping B(omega) of a BEM solution (:mod:`.hydro`). Here B is taken
piecewise linear on the file's grid, zero at omega = 0 and tapered linearly to zero between the
last frequency omega_W and 2 omega_W, so K has a closed form (:func:`retardation_kernel`).

The convolution is replaced by a state-space model (Kristiansen, Egeland & Fossen 2005; Perez
& Fossen 2008; WEC-Sim's ``ss`` radiation): K is sampled and realized with Kung's SVD of its
Hankel matrix (the eigensystem realization algorithm; Kung 1978), all 36 entries at once,
scaled by sqrt(K_ii(0) K_jj(0)); the realization is diagonalized, so the memory is N complex
modes::

    K(t) ~ Re[ output diag(exp(poles t)) input ],    z' = diag(poles) z + input nu,
    F_mem = -Re[output z]

The order N is the smallest (up to :data:`MAX_ORDER`) whose frequency response,
K^(omega) = B(omega) + i omega (A(omega) - A_inf), matches B and A - A_inf on the file's grid
within ``tolerance`` of each entry's scale (:func:`fit_memory`); :func:`advance` integrates z
exactly for a velocity linear over a step (first-order hold).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients

__all__ = ["MAX_ORDER", "POOR_FIT", "RadiationMemory", "advance", "fit_memory", "memory_wrench",
           "retardation_kernel"]

#: The largest number of complex modes of a fitted memory; every boat's state holds this many.
MAX_ORDER = 64

#: Orders tried by :func:`fit_memory`, smallest first.
_ORDERS = tuple(range(8, MAX_ORDER + 1, 4))


@dataclass(frozen=True)
class RadiationMemory:
    """The fitted radiation memory of one hull: K(t) ~ Re[output diag(e^{poles t}) input].

    Attributes:
        poles: (N,) complex, 1/s, all with negative real part.
        input: (N, 6) complex, 1 (per body velocity component).
        output: (6, N) complex, N s/m and N m s per mode (force rows, torque rows).
        error: the fit's largest error on the file's grid, relative to each entry's scale.
    """

    poles: np.ndarray
    input: np.ndarray
    output: np.ndarray
    error: float

    def padded(self, order: int = MAX_ORDER) -> RadiationMemory:
        """The same memory with ``order`` modes: the extra modes decay and are never driven."""
        n = order - self.poles.shape[0]
        return RadiationMemory(np.concatenate([self.poles, np.full(n, -1.0 + 0j)]),
                               np.concatenate([self.input, np.zeros((n, 6), complex)]),
                               np.concatenate([self.output, np.zeros((6, n), complex)], axis=1),
                               self.error)

    def response(self, omega: np.ndarray) -> np.ndarray:
        """(W, 6, 6) complex K^(omega) = B + i omega (A - A_inf) of the fitted memory."""
        w = np.asarray(omega, dtype=float)
        return np.einsum("in,wn,nj->wij", self.output,
                         1.0 / (1j * w[:, None] - self.poles[None, :]), self.input)


def _damping_grid(hydro: HydroCoefficients) -> tuple[np.ndarray, np.ndarray]:
    """(W + 2,) rad/s and (W + 2, 6, 6) B: the file's B with 0 at 0 and at 2 omega_W."""
    zero = np.zeros((1, 6, 6))
    omega = np.concatenate([[0.0], hydro.omega, [2.0 * hydro.omega[-1]]])
    return omega, np.concatenate([zero, hydro.radiation_damping, zero])


def retardation_kernel(hydro: HydroCoefficients, t: np.ndarray) -> np.ndarray:
    """(T, 6, 6) K(t), N/m and N m s^-1 per unit velocity, of B piecewise linear (closed form).

    Per segment [w_a, w_b] with B = B_a + s (w - w_a): integral B cos(w t) dw =
    [B(w) sin(w t) / t + s cos(w t) / t^2] from w_a to w_b (the trapezoid at t = 0).

    Args:
        hydro: the hull's coefficients.
        t: (T,) s, >= 0.
    """
    omega, damping = _damping_grid(hydro)
    tt = np.asarray(t, dtype=float)[:, None, None]
    at_zero = tt[:, 0, 0] == 0.0
    safe = np.where(tt == 0.0, 1.0, tt)
    out = np.zeros((tt.shape[0], 6, 6))
    for a in range(omega.shape[0] - 1):
        wa, wb, ba, bb = omega[a], omega[a + 1], damping[a], damping[a + 1]
        slope = (bb - ba) / (wb - wa)
        seg = ((bb * np.sin(wb * safe) - ba * np.sin(wa * safe)) / safe
               + slope * (np.cos(wb * safe) - np.cos(wa * safe)) / safe**2)
        seg[at_zero] = 0.5 * (ba + bb) * (wb - wa)
        out += seg
    return (2.0 / np.pi) * out


def _hankel_svd(samples: np.ndarray) -> tuple[np.ndarray, ...]:
    """The leading singular triplets of the Hankel matrix of samples, and its shifted twin.

    Samples (2R+1, 6, 6); Kung (1978). Only the :data:`MAX_ORDER` largest are used, so they
    are found by a randomized range finder with two power iterations (Halko, Martinsson &
    Tropp 2011, algorithms 4.4 and 5.1; a fixed seed: the same file gives the same memory),
    about 20 times faster than the full SVD of the 900 x 900 matrix, whose cost every boat
    with a coefficient file paid at initialization (0.3 s idle, 4 s on a busy core).
    """
    rows = (samples.shape[0] - 1) // 2
    h0, h1 = _hankel(samples, rows, 0), _hankel(samples, rows, 1)
    width = min(MAX_ORDER + _OVERSAMPLING, h0.shape[1])
    probe = np.random.default_rng(0).standard_normal((h0.shape[1], width))
    basis = np.linalg.qr(h0 @ probe)[0]
    for _ in range(2):  # power iterations: the spectrum of a smooth kernel falls fast
        basis = np.linalg.qr(h0 @ np.linalg.qr(h0.T @ basis)[0])[0]
    small_u, s, vt = np.linalg.svd(basis.T @ h0, full_matrices=False)
    return basis @ small_u, s, vt, h1


def _hankel(samples: np.ndarray, rows: int, shift: int) -> np.ndarray:
    """(6R, 6R) the block Hankel matrix [samples[i + j + shift]] of R x R blocks."""
    k = np.arange(rows)
    blocks = samples[k[:, None] + k[None, :] + shift]  # (R, R, 6, 6)
    return blocks.transpose(0, 2, 1, 3).reshape(6 * rows, 6 * rows)


#: Extra probe columns of the randomized range finder beyond the largest order.
_OVERSAMPLING = 16


def _realize(svd: tuple[np.ndarray, ...], order: int, step: float
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Kung's realization of ``order`` from :func:`_hankel_svd`, diagonalized.

    A pole the realization puts in the right half-plane (rare, of a weak mode) is reflected
    into the left one, so the memory is stable.

    Returns:
        (N,) continuous poles, 1/s, (N, 6) input, (6, N) output.
    """
    u, s, vt, h1 = svd
    root = np.sqrt(s[:order])
    left, right = u[:, :order] * root, root[:, None] * vt[:order]
    discrete = (u[:, :order].T @ h1 @ vt[:order].T) / (root[:, None] * root[None, :])
    lam, vectors = np.linalg.eig(discrete)
    poles = np.log(lam.astype(complex)) / step
    poles = np.where(poles.real < 0.0, poles, -np.abs(poles.real) - 1e-3 + 1j * poles.imag)
    return poles, np.linalg.solve(vectors, right[:, :6]), left[:6] @ vectors


def _fit_error(memory_response: np.ndarray, hydro: HydroCoefficients) -> float:
    """Largest error of B and A - A_inf on the grid, relative to sqrt(scale_i scale_j)."""
    w = hydro.omega
    b_err = np.abs(memory_response.real - hydro.radiation_damping).max(axis=0)
    a_err = np.abs(memory_response.imag / w[:, None, None]
                   - (hydro.added_mass - hydro.added_mass_inf)).max(axis=0)
    b_scale = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    a_scale = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)
    b_norm = np.sqrt(np.outer(b_scale, b_scale)) + 1e-12
    a_norm = np.sqrt(np.outer(a_scale, a_scale)) + 1e-12
    return float(max((b_err / b_norm).max(), (a_err / a_norm).max()))


#: A memory that misses its file by more than this (relative) is reported as a poor fit.
POOR_FIT = 0.1


def fit_memory(hydro: HydroCoefficients, tolerance: float = 0.03) -> RadiationMemory:
    """The state-space memory of ``hydro``'s radiation damping (module docstring).

    K is sampled 8 times per period of 2 omega_W, for 1.5 times as long as it takes to fall
    for good below 1 % of its peak (5 to 40 s; at most 150 Hankel block rows).

    Args:
        hydro: the hull's coefficients.
        tolerance: the largest relative error of B(omega) and A(omega) - A_inf accepted; the
            smallest order that meets it is returned, else the best up to :data:`MAX_ORDER`.

    Returns:
        The memory; its ``error`` says how well it fits.
    """
    step = np.pi / (8.0 * hydro.omega[-1])
    probe = retardation_kernel(hydro, np.arange(0.0, 60.0, step))
    envelope = np.abs(probe).max(axis=(1, 2))
    loud = np.nonzero(envelope > 0.01 * envelope.max())[0]
    duration = float(np.clip(1.5 * step * loud[-1], 5.0, 40.0))
    rows = int(min(np.ceil(duration / (2 * step)), 150))
    samples = probe[: 2 * rows + 1]
    scale = np.sqrt(np.maximum(np.diagonal(samples[0]), 1e-12 * samples[0].max()))
    svd = _hankel_svd(samples / scale[:, None] / scale[None, :])
    best = None
    for order in _ORDERS:
        poles, inp, out = _realize(svd, order, step)
        memory = RadiationMemory(poles, inp * scale[None, :], scale[:, None] * out, 0.0)
        error = _fit_error(memory.response(hydro.omega), hydro)
        if best is None or error < best.error:
            best = RadiationMemory(memory.poles, memory.input, memory.output, error)
        if error <= tolerance:
            break
    return best


def memory_wrench(output: np.ndarray, memory: np.ndarray, carried: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    """(B, 3) force and (B, 3) torque of the memory: -Re[output z], body frame, about the CoM.

    Compiled (:func:`.memory_kernel.memory_wrench_f64`; ``_memory_wrench_numpy`` its oracle).

    Args:
        output: (B, 6, N) complex, the boats' memory outputs.
        memory: (B, N) complex, their memory states z.
        carried: (B,) in [0, 1], the share of its fluid each hull carries (scales the
            wrench); None: 1.
    """
    from boat_dynamics.physics.potential_flow.memory_kernel import memory_wrench_f64

    share = np.ones(output.shape[0]) if carried is None else np.asarray(carried, dtype=float)
    return memory_wrench_f64(np.ascontiguousarray(output, dtype=complex),
                             np.ascontiguousarray(memory, dtype=complex), share)


def _memory_wrench_numpy(output: np.ndarray, memory: np.ndarray
                         ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`memory_wrench` in numpy (carried 1): the compiled kernel's oracle."""
    wrench = -np.einsum("bin,bn->bi", output, memory).real
    return wrench[:, :3], wrench[:, 3:]


def advance(poles: np.ndarray, input_: np.ndarray, memory: np.ndarray, before: np.ndarray,
            after: np.ndarray, dt: float) -> np.ndarray:
    """(B, N) memory states after ``dt``, for a body velocity linear from ``before`` to ``after``.

    Exact for that velocity (first-order hold): z+ = e^{p dt} z + psi0 u0 + psi1 (u1 - u0),
    u = input nu, psi0 = (e^{p dt} - 1) / p, psi1 = (e^{p dt} - 1 - p dt) / (p^2 dt).
    Compiled (:func:`.memory_kernel.advance_f64`; ``_advance_numpy`` its oracle).

    Args:
        poles: (B, N) complex, 1/s.
        input_: (B, N, 6) complex.
        memory: (B, N) complex, z at the start of the step.
        before: (B, 6) body velocity [v, w] at the start of the step.
        after: (B, 6) at its end.
        dt: s.
    """
    from boat_dynamics.physics.potential_flow.memory_kernel import advance_f64

    return advance_f64(np.ascontiguousarray(poles, dtype=complex),
                       np.ascontiguousarray(input_, dtype=complex),
                       np.ascontiguousarray(memory, dtype=complex),
                       np.ascontiguousarray(before, dtype=float),
                       np.ascontiguousarray(after, dtype=float), float(dt))


def _advance_numpy(poles: np.ndarray, input_: np.ndarray, memory: np.ndarray,
                   before: np.ndarray, after: np.ndarray, dt: float) -> np.ndarray:
    """:func:`advance` in numpy: the compiled kernel's oracle."""
    decay = np.exp(poles * dt)
    psi0 = (decay - 1.0) / poles
    psi1 = (decay - 1.0 - poles * dt) / (poles**2 * dt)
    u0 = np.einsum("bnj,bj->bn", input_, before)
    u1 = np.einsum("bnj,bj->bn", input_, after)
    return decay * memory + psi0 * u0 + psi1 * (u1 - u0)
