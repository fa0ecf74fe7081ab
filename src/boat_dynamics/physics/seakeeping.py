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
from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics import pipeline
from boat_dynamics.physics.hydro import HydroCoefficients
from boat_dynamics.physics.model import BoatInputs, BoatParams, initial_state
from boat_dynamics.physics.mooring import soft_mooring
from boat_dynamics.physics.rigid_body import mass_matrix, quat_to_euler
from boat_dynamics.physics.system import FleetInputs, FleetState, System
from boat_dynamics.physics.tuning import horizontal_mass
from ocean_sim.physics.waves import WaveComponent, WaveField, angular_frequency

__all__ = ["MOORING_PERIODS", "Response", "potential_flow_rao", "regular_wave_response",
           "rigid_body_matrix"]

#: The natural period of the soft mooring of :func:`regular_wave_response`, in wave periods:
#: its spring then changes the surge and sway impedance at the wave's frequency by 1/15^2.
MOORING_PERIODS = 15.0


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
                          dt: float = 0.01, settle: float = 20.0, periods: int = 6,
                          tolerance: float = 0.01, max_time: float = 300.0) -> Response:
    """The boat's first-harmonic heave, roll and pitch in a regular wave (module docstring).

    The boat starts afloat at the origin heading +x (initialized here for this sea, so a
    ``froude_krylov`` hull is panelled for this wavelength), held there by a soft mooring of
    :data:`MOORING_PERIODS` wave periods (at least 30 s; :mod:`.mooring`, as a towing tank
    does: free, it would drift with the waves and meet them at another frequency), and runs
    ``settle`` s plus four
    periods; then windows of ``periods`` periods are analysed (the Fourier coefficient at
    omega) until three in a row agree within ``tolerance`` (of the value, or of 2 % of the
    wave's own scale, 1 m/m and k rad/m, for a motion near zero): a lightly damped mode near
    resonance takes long to forget its start, and its beat with the wave (at the difference
    of the frequencies) can make two windows agree by chance. At most ``max_time`` s.

    Args:
        params: the boat as a scenario gives it (``derive`` not yet applied) or derived.
        wavelength: m, > 0.
        direction: rad, relative to the bow.
        amplitude: m, small against the wavelength (linear theory).
        gravity: m/s^2.
        depth: m, water depth (inf = deep).
        dt: s, the step.
        settle: s before the four periods and the first window.
        periods: periods per window.
        tolerance: relative agreement of three windows in a row.
        max_time: s of simulated time at most.
    """
    wave = WaveComponent(amplitude, wavelength, direction, 0.0, 0.0)
    sea = WaveField((wave,), gravity, depth)
    omega = float(angular_frequency(wave.wavenumber, gravity, depth))
    inputs, period = FleetInputs.stack([BoatInputs()]), 2 * math.pi / omega
    start = initial_state(params, np.zeros(3))
    if params.derive is not None:  # this mooring, not the scenario's (``mooring`` key)
        params = replace(params, derive=replace(params.derive, mooring_period=None))
    params = replace(params, mooring=soft_mooring(
        np.array([start.position[0], start.position[1], 0.0]), horizontal_mass(params),
        max(MOORING_PERIODS * period, 30.0)))
    system, state = pipeline.init(System.build([params]), FleetState.stack([start]), sea)
    floor = 0.02 * np.array([1.0, wave.wavenumber, wave.wavenumber])
    state = _run(system, state, inputs, sea, dt, round((settle + 4 * period) / dt))[0]
    window = round(periods * period / dt)
    history: list[np.ndarray] = []
    while True:
        state, motion = _run(system, state, inputs, sea, dt, window)
        history.append(_first_harmonic(motion, omega) / amplitude)
        last = np.array(history[-3:])
        done = len(last) == 3 and np.all(
            np.ptp(last, axis=0) <= tolerance * np.maximum(last[-1], floor))
        if done or state.t + window * dt > max_time:
            return Response(wavelength, direction, omega, *map(float, history[-1]))



def _run(system: System, state: FleetState, inputs: FleetInputs, sea: WaveField, dt: float,
         steps: int) -> tuple[FleetState, np.ndarray]:
    """The state after ``steps`` steps, and (steps, 4) t, heave, roll, pitch after each."""
    rows = np.empty((steps, 4))
    for k in range(steps):
        state = pipeline.step(system, state, inputs, sea, dt).state
        rows[k] = (state.t, state.position[0, 2], *quat_to_euler(state.orientation[0])[:2])
    return state, rows


def _first_harmonic(motion: np.ndarray, omega: float) -> np.ndarray:
    """(3,) amplitudes at omega of heave, roll, pitch from :func:`_run`'s rows."""
    x = motion[:, 1:]
    first = np.exp(1j * omega * motion[:, 0]) @ (x - x.mean(axis=0))
    return 2.0 * np.abs(first) / motion.shape[0]


def rigid_body_matrix(params: BoatParams) -> np.ndarray:
    """(6, 6) the boat's rigid-body mass matrix about its centre of mass, body axes."""
    return mass_matrix(params.mass, params.inertia, params.inertia_products)


def potential_flow_rao(hydro: HydroCoefficients, mass_matrix: np.ndarray, omega: float,
                       direction: float, viscous: np.ndarray | None = None) -> np.ndarray:
    """(6,) complex motion per metre of wave amplitude by linear potential flow.

    Args:
        hydro: the hull's coefficients.
        mass_matrix: (6, 6) rigid-body mass matrix about the centre of mass
            (:func:`rigid_body_matrix`).
        omega: rad/s.
        direction: rad, the waves' direction of travel relative to the bow.
        viscous: (6,) linear damping added to B(omega) on the body's own velocity (the
            boat's viscous roll, pitch and yaw damping act so), or None.

    Returns:
        Surge, sway, heave (m/m) of the centre of mass, roll, pitch, yaw (rad/m), complex
        amplitudes (Re[x e^{-i omega t}], phase relative to the wave crest at the origin).
        Surge, sway and yaw have no restoring force: their values are the free body's.
    """
    w, beta = np.array([omega]), np.array([direction])
    excitation = (hydro.diffraction_at(w, beta) + hydro.froude_krylov_at(w, beta))[0]
    damping = hydro.damping_at(omega)
    if viscous is not None:
        damping = damping + np.diag(viscous)
    impedance = (-omega**2 * (mass_matrix + hydro.added_mass_at(omega))
                 - 1j * omega * damping + hydro.hydrostatic_stiffness)
    return np.linalg.solve(impedance, excitation)
