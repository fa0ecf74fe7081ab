"""Response amplitude operators: a boat run in regular waves, and potential flow's prediction.

:func:`regular_wave_response` steps one boat, as a scenario gives it, in a single small regular
wave until the motion is periodic, and measures the first harmonic of its heave, roll and pitch
(of the centre of mass) per metre of wave amplitude: the RAO as a towing tank measures it
(ITTC 7.5-02-07-02.1). :func:`potential_flow_rao` is the frequency-domain answer of linear
potential flow from a coefficient file: the complex motion x solving

    (-omega^2 (M + A(omega)) - i omega B(omega) + C) x = F_FK + F_D

(Newman 1977, sec. 6.19; Falnes 2002, ch. 5; the convention of :mod:`.hydro`, Re[x e^{-i omega
t}]), with A, B and the excitation interpolated on the file's grid, M the boat's rigid-body
mass matrix about its centre of mass and C the file's hydrostatic stiffness.

Directions: ``direction`` is the direction the waves travel toward relative to the bow (rad,
counter-clockwise): pi = head seas, pi / 2 = beam seas from starboard, 0 = following seas.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics import pipeline
from boat_dynamics.physics.hydro import HydroCoefficients
from boat_dynamics.physics.model import BoatInputs, BoatParams, initial_state
from boat_dynamics.physics.rigid_body import inertia_tensor, quat_to_euler
from boat_dynamics.physics.system import FleetInputs, FleetState, System
from ocean_sim.physics.waves import WaveComponent, WaveField, angular_frequency

__all__ = ["Response", "potential_flow_rao", "regular_wave_response", "rigid_body_matrix"]


@dataclass(frozen=True)
class Response:
    """A boat's steady motion in one regular wave, per metre of wave amplitude.

    Attributes:
        wavelength: m.
        direction: rad, the waves' direction of travel relative to the bow.
        omega: rad/s, the wave's frequency.
        heave: m/m, of the centre of mass.
        roll: rad/m.
        pitch: rad/m.
    """

    wavelength: float
    direction: float
    omega: float
    heave: float
    roll: float
    pitch: float


def regular_wave_response(params: BoatParams, wavelength: float, direction: float,
                          amplitude: float, gravity: float = 9.81, depth: float = math.inf,
                          dt: float = 0.01, settle: float = 20.0, periods: int = 6
                          ) -> Response:
    """The boat's first-harmonic heave, roll and pitch in a regular wave (module docstring).

    The boat starts afloat at the origin heading +x (initialized here for this sea, so a
    ``froude_krylov`` hull is panelled for this wavelength), runs ``settle`` s plus four
    periods, then ``periods`` periods are analysed (the Fourier coefficient at omega).

    Args:
        params: the boat as a scenario gives it (``derive`` not yet applied) or derived.
        wavelength: m, > 0.
        direction: rad, relative to the bow.
        amplitude: m, small against the wavelength (linear theory).
        gravity: m/s^2.
        depth: m, water depth (inf = deep).
        dt: s, the step.
        settle: s before the four periods and the analysis.
        periods: periods analysed.
    """
    wave = WaveComponent(amplitude, wavelength, direction, 0.0, 0.0)
    sea = WaveField((wave,), gravity, depth)
    omega = float(angular_frequency(wave.wavenumber, gravity, depth))
    state = FleetState.stack([initial_state(params, np.zeros(3))])
    system, state = pipeline.init(System.build([params]), state, sea)
    inputs, period = FleetInputs.stack([BoatInputs()]), 2 * math.pi / omega
    record = round((settle + 4 * period) / dt)
    steps = record + round(periods * period / dt)
    rows, times = [], []
    for k in range(steps):
        state = pipeline.step(system, state, inputs, sea, dt).state
        if k >= record:
            rows.append([state.position[0, 2], *quat_to_euler(state.orientation[0])[:2]])
            times.append(state.t)
    x = np.array(rows)
    first = np.exp(1j * omega * np.array(times)) @ (x - x.mean(axis=0))
    heave, roll, pitch = 2.0 * np.abs(first) / len(times) / amplitude
    return Response(wavelength, direction, omega, float(heave), float(roll), float(pitch))


def rigid_body_matrix(params: BoatParams) -> np.ndarray:
    """(6, 6) the boat's rigid-body mass matrix about its centre of mass, body axes."""
    matrix = np.zeros((6, 6))
    matrix[:3, :3] = params.mass * np.eye(3)
    matrix[3:, 3:] = inertia_tensor(np.asarray(params.inertia, dtype=float),
                                    np.asarray(params.inertia_products, dtype=float))
    return matrix


def potential_flow_rao(hydro: HydroCoefficients, mass_matrix: np.ndarray, omega: float,
                       direction: float) -> np.ndarray:
    """(6,) complex motion per metre of wave amplitude by linear potential flow.

    Args:
        hydro: the hull's coefficients.
        mass_matrix: (6, 6) rigid-body mass matrix about the centre of mass
            (:func:`rigid_body_matrix`).
        omega: rad/s.
        direction: rad, the waves' direction of travel relative to the bow.

    Returns:
        Surge, sway, heave (m/m) of the centre of mass, roll, pitch, yaw (rad/m), complex
        amplitudes (Re[x e^{-i omega t}], phase relative to the wave crest at the origin).
        Surge, sway and yaw have no restoring force: their values are the free body's.
    """
    w, beta = np.array([omega]), np.array([direction])
    excitation = (hydro.diffraction_at(w, beta) + hydro.froude_krylov_at(w, beta))[0]
    impedance = (-omega**2 * (mass_matrix + hydro.added_mass_at(omega))
                 - 1j * omega * hydro.damping_at(omega) + hydro.hydrostatic_stiffness)
    return np.linalg.solve(impedance, excitation)
