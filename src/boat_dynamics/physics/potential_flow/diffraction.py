"""The diffraction force: the incident waves scattered by the hull, from a BEM solution.

Linear potential flow around the mean position (Newman 1977, sec. 6.17; Falnes 2002,
ch. 5): a wave component a cos(theta), theta = k D . r - omega t + phi, scattered by the hull
exerts Re[a X_d(omega, beta - psi) e^{i theta_0}] on it, where X_d is the diffraction
transfer function per metre of amplitude (:attr:`HydroCoefficients.diffraction`, body axes,
about the centre of mass), beta - psi the wave's direction relative to the boat's heading
psi, and theta_0 the phase at the hull reference point. The Froude-Krylov part is here only
for the ``linear`` pressure model (the same formula with the Froude-Krylov transfer
function); the ``froude_krylov`` pressure integrates it on the instantaneous wetted hull.
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from ocean_sim.physics.waves import WaveField, component_phases, time_phase

__all__ = ["diffraction_wrench", "excitation_wrench"]


def diffraction_wrench(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                       heading: float | np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
    """The diffraction force: :func:`excitation_wrench` of ``hydro.diffraction``."""
    return excitation_wrench(hydro, sea, reference_xy, heading, t, "diffraction")


def excitation_wrench(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                      heading: float | np.ndarray, t: float,
                      part: Literal["diffraction", "froude_krylov", "both"],
                      velocity: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Force and torque about the centre of mass, body frame, of one boat or of several.

    At forward speed the hull meets each component at the encounter frequency
    omega_e = omega - k D . V (V its velocity over ground; omega - k U cos(beta) for a boat
    going ahead at U into waves from beta; Lewandowski 2004, "The Dynamics of Marine Craft",
    sec. 3.4; Faltinsen 1990, sec. 5.1), and the scattered waves are those of that frequency:
    the diffraction transfer function is looked up at omega_e. A wave the hull overtakes
    (omega_e < 0, theta growing in time) passes it from ahead: it is the wave of frequency
    |omega_e| travelling the opposite way with its phase reversed,
    Re[a X_d(|omega_e|, beta + pi - psi) e^{-i theta}]. The Froude-Krylov transfer function
    stays at the
    absolute frequency: it is the integral of the incident pressure, set by the wave's own
    k (the time dependence at encounter comes in through the phase at the moving hull).
    Below the file's lowest frequency the transfer functions are clamped to it.

    Args:
        hydro: the hull's coefficients (shared by the boats).
        sea: the components acting on the boats (their wave filter applied).
        reference_xy: (2,) m, world position of the hull reference point, or (G, 2) of G boats.
        heading: psi, rad, the boat's yaw, or (G,).
        t: s.
        part: ``diffraction``, or ``froude_krylov`` (the ``linear`` pressure model's
            incident-wave force: the same formula with the Froude-Krylov transfer functions),
            or ``both``: then (G, 6) diffraction and (G, 6) Froude-Krylov wrenches, force
            then torque.
        velocity: (2,) or (G, 2) m/s, the hulls' horizontal velocity over ground, world
            frame; None: at rest (the zero-speed frequencies).

    Returns:
        (3,) N and (3,) N m for one boat; (G, 3) and (G, 3) for G.
    """
    xy = np.asarray(reference_xy, dtype=float)
    many = xy.ndim == 2
    xy, psi = np.atleast_2d(xy), np.atleast_1d(np.asarray(heading, dtype=float))
    if not sea.components:
        zero = np.zeros((xy.shape[0], 6 if part == "both" else 3))
        return (zero, zero.copy()) if many or part == "both" else (zero[0], zero[0].copy())
    from boat_dynamics.physics.potential_flow.excitation_kernel import excitation_f64

    ar = sea.arrays
    v = np.zeros((xy.shape[0], 2)) if velocity is None else np.ascontiguousarray(
        np.broadcast_to(np.asarray(velocity, dtype=float), (xy.shape[0], 2)))
    common = (ar.a, ar.omega, ar.k, ar.dx, ar.dy, np.arctan2(ar.dy, ar.dx),
              np.ascontiguousarray(xy), ar.kd, time_phase(sea, t), psi, v)
    wrenches = []
    if part in ("diffraction", "both"):
        wrenches.append(excitation_f64(hydro.omega, hydro.directions, hydro.diffraction,
                                       *common, True))
    if part in ("froude_krylov", "both"):
        wrenches.append(excitation_f64(hydro.omega, hydro.directions, hydro.froude_krylov,
                                       *common, False))
    return _shaped(wrenches, part, many)


def _shaped(wrenches: list, part: str, many: bool):
    """:func:`excitation_wrench`'s result from its (G, 6) wrenches."""
    if part == "both":  # (G, 6) each: diffraction then Froude-Krylov
        return wrenches[0], wrenches[1]
    wrench = wrenches[0]
    if many:
        return wrench[:, :3], wrench[:, 3:]
    return wrench[0, :3], wrench[0, 3:]


def _excitation_numpy(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                      heading: float | np.ndarray, t: float,
                      part: Literal["diffraction", "froude_krylov", "both"],
                      velocity: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`excitation_wrench` in numpy: the compiled kernel's oracle (a sea with components)."""
    xy = np.asarray(reference_xy, dtype=float)
    many = xy.ndim == 2
    xy, psi = np.atleast_2d(xy), np.atleast_1d(np.asarray(heading, dtype=float))
    ar = sea.arrays
    relative = np.arctan2(ar.dy, ar.dx)[None, :] - psi[:, None]  # (G, M)
    phase = np.exp(1j * component_phases(sea, xy, t))  # (G, M)
    wrenches = []
    if part in ("diffraction", "both"):
        wrenches.append(_scattered(hydro, ar, relative, phase, velocity, xy.shape[0]))
    if part in ("froude_krylov", "both"):
        omega = np.broadcast_to(ar.omega, relative.shape)
        table = hydro.froude_krylov_at(omega.ravel(), relative.ravel())
        wrenches.append(_summed(ar.a, table.reshape(*relative.shape, 6), phase))
    return _shaped(wrenches, part, many)


def _scattered(hydro: HydroCoefficients, ar, relative: np.ndarray, phase: np.ndarray,
               velocity: np.ndarray | None, count: int) -> np.ndarray:
    """(G, 6) the diffraction wrench at the encounter frequencies (:func:`excitation_wrench`)."""
    shape = relative.shape
    if velocity is None:
        table = hydro.diffraction_at(np.broadcast_to(ar.omega, shape).ravel(), relative.ravel())
        return _summed(ar.a, table.reshape(*shape, 6), phase)
    v = np.broadcast_to(np.asarray(velocity, dtype=float), (count, 2))
    encounter = ar.omega[None, :] - ar.k[None, :] * (v[:, :1] * ar.dx + v[:, 1:] * ar.dy)
    overtaken = encounter < 0.0
    table = hydro.diffraction_at(np.abs(encounter).ravel(),
                                 np.where(overtaken, relative + np.pi, relative).ravel())
    return _summed(ar.a, table.reshape(*shape, 6), np.where(overtaken, np.conj(phase), phase))


def _summed(amplitude: np.ndarray, transfer: np.ndarray, phase: np.ndarray) -> np.ndarray:
    """(G, 6) sum over components of Re[a X e^{i theta}]."""
    return np.einsum("m,gmk,gm->gk", amplitude, transfer, phase).real
