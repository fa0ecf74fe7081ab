"""Waves one boat makes, as another boat feels them: local plane waves and their force.

Linear superposition (Newman 1977, sec. 6.17): the sea a boat feels is the incident sea plus
the waves the other boats make, each radiated, scattered or left in a wake by one of them.
Near a receiving boat, far from the boat that made them, those waves are locally plane: the
wide-spacing approximation of multiple-body interaction (Simon 1982, J. Fluid Mech. 120,
1-25; McIver & Evans 1984, Appl. Ocean Res. 6(2), 101-107), which replaces the outgoing wave
of one body by the plane wave of its local amplitude, phase and direction at the other.
Each made wave is then one more component for the receiver's Froude-Krylov and diffraction
transfer functions (:mod:`.diffraction`), at its own frequency and direction: a
:class:`LocalWaves`. Interaction beyond the first order (the receiver's waves made by waves
made) is left out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients

__all__ = ["LocalWaves", "local_wrench", "local_wrenches"]


@dataclass(frozen=True)
class LocalWaves:
    """N plane waves standing in, near the point ``at``, for waves made by other boats.

    Near ``at`` and at times near ``t``, their elevation is
    eta(x, t') = sum_n a_n cos(k_n D_n . (x - at) - omega_n (t' - t) + phase_n),
    with D_n = (cos direction_n, sin direction_n): the convention of the sea's components
    (:mod:`ocean_sim.physics.waves`, theta = k D . r - omega t + phi), so the transfer
    functions of :mod:`.diffraction` apply to them unchanged.

    Attributes:
        at: (2,) m, world x, y of the point they stand for (the receiver's reference point).
        t: s, the time their phases are taken at.
        amplitude: (N,) m, >= 0.
        omega: (N,) rad/s, > 0, the frequency over ground (earth frame).
        wavenumber: (N,) rad/m, > 0 (deep water: omega^2 / g).
        direction: (N,) rad, world frame, the direction each travels toward.
        phase: (N,) rad, each one's phase at ``at`` and ``t``.
    """

    at: np.ndarray
    t: float
    amplitude: np.ndarray
    omega: np.ndarray
    wavenumber: np.ndarray
    direction: np.ndarray
    phase: np.ndarray

    @classmethod
    def none(cls, at: np.ndarray, t: float) -> LocalWaves:
        """No made waves at ``at``."""
        empty = np.zeros(0)
        return cls(np.asarray(at, dtype=float), t, empty, empty, empty, empty, empty)

    @property
    def count(self) -> int:
        """N, the number of plane waves."""
        return int(self.amplitude.shape[0])

    def elevation(self, xy: np.ndarray) -> np.ndarray:
        """(P,) m, their elevation at time ``t`` at P points ``xy`` (P, 2) m near ``at``."""
        d = np.asarray(xy, dtype=float).reshape(-1, 2) - self.at
        along = d[:, :1] * np.cos(self.direction) + d[:, 1:] * np.sin(self.direction)
        return np.cos(along * self.wavenumber + self.phase) @ self.amplitude


def local_wrench(hydro: HydroCoefficients, waves: LocalWaves, heading: float,
                 velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The made waves' diffraction and Froude-Krylov wrenches on the boat at ``waves.at``.

    The transfer functions of ``hydro`` (per metre of amplitude, about the centre of mass,
    body axes) at each wave's encounter frequency, as for the sea's own components
    (:func:`.diffraction.excitation_wrench`); :func:`local_wrenches` of one boat.

    Args:
        hydro: the receiving hull's coefficients.
        waves: the plane waves at its hull reference point, at the time of the step.
        heading: rad, its yaw.
        velocity: (2,) m/s, its horizontal velocity over ground, world frame.

    Returns:
        (6,) diffraction and (6,) Froude-Krylov wrench, force (N) then torque (N m), body
        frame. Zeros when there are no waves.
    """
    scattered, incident = local_wrenches(
        hydro, np.zeros(waves.count, dtype=np.intp), np.array([float(heading)]),
        np.asarray(velocity, dtype=float).reshape(1, 2), waves.amplitude, waves.omega,
        waves.wavenumber, waves.direction, waves.phase)
    return scattered[0], incident[0]


def local_wrenches(hydro: HydroCoefficients, owner: np.ndarray, heading: np.ndarray,
                   velocity: np.ndarray, amplitude: np.ndarray, omega: np.ndarray,
                   wavenumber: np.ndarray, direction: np.ndarray, phase: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The diffraction and Froude-Krylov wrenches of N plane waves on G boats of one hull.

    Each wave acts on its ``owner`` boat, its phase taken at that boat's reference point:
    sum Re[a X e^{i phase}], X the transfer function at (omega_e, beta - psi), omega_e =
    omega - k D . V its encounter frequency (a wave the hull overtakes, omega_e < 0: the
    wave of |omega_e| from the opposite side, phase reversed; Lewandowski 2004, sec. 3.4),
    the Froude-Krylov one at omega (:func:`.diffraction.excitation_wrench`'s rules).

    Args:
        hydro: the hulls' coefficients.
        owner: (N,) int in 0..G-1.
        heading: (G,) rad, the boats' yaws.
        velocity: (G, 2) m/s, their horizontal velocities over ground, world frame.
        amplitude: (N,) m.
        omega: (N,) rad/s, over ground.
        wavenumber: (N,) rad/m.
        direction: (N,) rad, world, toward which each travels.
        phase: (N,) rad, each one's phase at its owner's reference point now.

    Returns:
        (G, 6) diffraction and (G, 6) Froude-Krylov wrenches, force (N) then torque (N m),
        body frames.
    """
    count = heading.shape[0]
    out = np.zeros((count, 6)), np.zeros((count, 6))
    if owner.shape[0] == 0:
        return out
    dx, dy = np.cos(direction), np.sin(direction)
    relative = direction - heading[owner]
    v = velocity[owner]
    encounter = omega - wavenumber * (v[:, 0] * dx + v[:, 1] * dy)
    overtaken = encounter < 0.0
    scattered = hydro.diffraction_at(np.abs(encounter),
                                     np.where(overtaken, relative + np.pi, relative))
    incident = hydro.froude_krylov_at(omega, relative)
    turn = np.exp(1j * phase)
    for table, rotated, into in ((scattered, np.where(overtaken, np.conj(turn), turn), out[0]),
                                 (incident, turn, out[1])):
        values = (amplitude[:, None] * table * rotated[:, None]).real  # (N, 6)
        for q in range(6):
            into[:, q] = np.bincount(owner, weights=values[:, q], minlength=count)
    return out
