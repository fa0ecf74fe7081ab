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

from boat_dynamics.physics.hydro import HydroCoefficients
from ocean_sim.physics.waves import WaveField, component_phases

__all__ = ["diffraction_wrench", "excitation_wrench"]


def diffraction_wrench(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                       heading: float | np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
    """The diffraction force: :func:`excitation_wrench` of ``hydro.diffraction``."""
    return excitation_wrench(hydro, sea, reference_xy, heading, t, "diffraction")


def excitation_wrench(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                      heading: float | np.ndarray, t: float,
                      part: Literal["diffraction", "froude_krylov", "both"]
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Force and torque about the centre of mass, body frame, of one boat or of several.

    Args:
        hydro: the hull's coefficients (shared by the boats).
        sea: the components acting on the boats (their wave filter applied).
        reference_xy: (2,) m, world position of the hull reference point, or (G, 2) of G boats.
        heading: psi, rad, the boat's yaw, or (G,).
        t: s.
        part: ``diffraction``, or ``froude_krylov`` (the ``linear`` pressure model's
            incident-wave force: the same formula with the Froude-Krylov transfer functions),
            or ``both`` in one interpolation: then (G, 6) diffraction and (G, 6)
            Froude-Krylov wrenches, force then torque.

    Returns:
        (3,) N and (3,) N m for one boat; (G, 3) and (G, 3) for G.
    """
    xy = np.asarray(reference_xy, dtype=float)
    many = xy.ndim == 2
    xy, psi = np.atleast_2d(xy), np.atleast_1d(np.asarray(heading, dtype=float))
    if not sea.components:
        zero = np.zeros((xy.shape[0], 6 if part == "both" else 3))
        return (zero, zero.copy()) if many or part == "both" else (zero[0], zero[0].copy())
    ar = sea.arrays
    relative = np.arctan2(ar.dy, ar.dx)[None, :] - psi[:, None]  # (G, M)
    m = ar.omega.shape[0]
    if part == "both":
        table = hydro.excitation_at(np.tile(ar.omega, xy.shape[0]), relative.ravel())
    else:
        at = hydro.diffraction_at if part == "diffraction" else hydro.froude_krylov_at
        table = at(np.tile(ar.omega, xy.shape[0]), relative.ravel())
    transfer = table.reshape(xy.shape[0], m, table.shape[1])
    theta = component_phases(sea, xy, t)  # (G, M)
    wrench = np.einsum("m,gmk,gm->gk", ar.a, transfer, np.exp(1j * theta)).real
    if part == "both":  # (G, 12): diffraction then Froude-Krylov
        return wrench[:, :6], wrench[:, 6:]
    if many:
        return wrench[:, :3], wrench[:, 3:]
    return wrench[0, :3], wrench[0, 3:]
