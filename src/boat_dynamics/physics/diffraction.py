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
                       heading: float, t: float) -> tuple[np.ndarray, np.ndarray]:
    """(3,) N force and (3,) N m torque about the centre of mass, body frame.

    Args:
        hydro: the hull's coefficients.
        sea: the components acting on the boat (its wave filter applied).
        reference_xy: (2,) m, world position of the hull reference point.
        heading: psi, rad, the boat's yaw.
        t: s.
    """
    if not sea.components:
        return np.zeros(3), np.zeros(3)
    ar = sea.arrays
    relative = np.arctan2(ar.dy, ar.dx) - heading
    transfer = hydro.diffraction_at(ar.omega, relative)  # (M, 6)
    theta = component_phases(sea, np.asarray(reference_xy, dtype=float)[None, :], t)[0]
    wrench = (ar.a[:, None] * transfer * np.exp(1j * theta)[:, None]).sum(axis=0).real
    return wrench[:3], wrench[3:]
