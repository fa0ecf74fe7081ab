"""The diffraction force: the incident waves scattered by the hull, from a BEM solution.

Linear potential flow around the mean position (Newman 1977, sec. 6.17; Falnes 2002,
ch. 5): a wave component a cos(theta), theta = k D . r - omega t + phi, scattered by the hull
exerts Re[a X_d(omega, beta - psi) e^{i theta_0}] on it, where X_d is the diffraction
transfer function per metre of amplitude (:attr:`HydroCoefficients.diffraction`, body axes,
about the centre of mass), beta - psi the wave's direction relative to the boat's heading
psi, and theta_0 the phase at the hull reference point. The Froude-Krylov part is not here:
the ``froude_krylov`` pressure integrates it on the instantaneous wetted hull.
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.physics.hydro import HydroCoefficients
from ocean_sim.physics.waves import WaveField, component_phases

__all__ = ["diffraction_wrench"]


def diffraction_wrench(hydro: HydroCoefficients, sea: WaveField, reference_xy: np.ndarray,
                       heading: float | np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
    """Force and torque about the centre of mass, body frame, of one boat or of several.

    Args:
        hydro: the hull's coefficients (shared by the boats).
        sea: the components acting on the boats (their wave filter applied).
        reference_xy: (2,) m, world position of the hull reference point, or (G, 2) of G boats.
        heading: psi, rad, the boat's yaw, or (G,).
        t: s.

    Returns:
        (3,) N and (3,) N m for one boat; (G, 3) and (G, 3) for G.
    """
    xy = np.asarray(reference_xy, dtype=float)
    many = xy.ndim == 2
    xy, psi = np.atleast_2d(xy), np.atleast_1d(np.asarray(heading, dtype=float))
    if not sea.components:
        zero = np.zeros((xy.shape[0], 3))
        return (zero, zero.copy()) if many else (zero[0], zero[0].copy())
    ar = sea.arrays
    relative = np.arctan2(ar.dy, ar.dx)[None, :] - psi[:, None]  # (G, M)
    m = ar.omega.shape[0]
    transfer = hydro.diffraction_at(np.tile(ar.omega, xy.shape[0]), relative.ravel()
                                    ).reshape(xy.shape[0], m, 6)
    theta = component_phases(sea, xy, t)  # (G, M)
    wrench = np.einsum("m,gmk,gm->gk", ar.a, transfer, np.exp(1j * theta)).real
    if many:
        return wrench[:, :3], wrench[:, 3:]
    return wrench[0, :3], wrench[0, 3:]
