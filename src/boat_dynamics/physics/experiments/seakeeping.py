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

At forward speed U (``speed``), as in a towing tank: the boat on a carriage
(:mod:`.carriage`, surge, sway and yaw held) meets the wave at the encounter frequency
omega_e = omega - k U cos(beta) (Lewandowski 2004, "The Dynamics of Marine Craft", sec. 3.4), at
which the motion is measured. Potential flow's answer is then that of the zero-speed
coefficients at |omega_e| (A, B, and the diffraction, with the Froude-Krylov force of the wave
itself) as the simulation uses them (:mod:`.diffraction`), with the speed terms the simulation
carries: its radiation (A_inf nu' and the Cummins memory) acts on the body-frame velocity, which
at speed U holds U times the attitude, w = z' + U theta and v = y' - U psi (theta bow down,
psi to port). Linearized, the radiation force is -A (xi'' + U L xi') - B (xi' + U L xi) with
L[heave, pitch] = 1, L[sway, yaw] = -1 (Fossen 2005, "A nonlinear unified state-space model for
ship maneuvering and control in a seaway", the U L term of the seakeeping-to-body transform),
which is Salvesen, Tuck & Faltinsen's (1970) A35 = A35_0 - U B33 / omega^2 and
B35 = B35_0 + U A33 (heave from pitch). Their pitch-from-heave and U^2 pitch terms (the Munk
moment's share, :mod:`.added_mass`) are not in the simulation, nor here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics.body.rigid_body import mass_matrix, quat_to_euler
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.model import BoatInputs, BoatParams, initial_state
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.core.tuning import horizontal_mass
from boat_dynamics.physics.force_models.carriage import Carriage
from boat_dynamics.physics.force_models.mooring import soft_mooring
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from ocean_sim.physics.waves import WaveComponent, WaveField, angular_frequency

__all__ = ["MIN_ENCOUNTERS", "MOORING_PERIODS", "Response", "encounter_frequency",
           "potential_flow_rao", "regular_wave_response", "rides", "rigid_body_matrix"]

#: The fewest encounters with the wave a towed run may have in its ``max_time``: fewer, and
#: the boat rides the wave (:func:`rides`).
MIN_ENCOUNTERS = 10

#: Fossen's (2005) L: the body-frame velocity at speed U is the seakeeping one plus U L xi.
_L = np.zeros((6, 6))
_L[2, 4], _L[1, 5] = 1.0, -1.0

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
        speed: m/s, the carriage's (0: held by a soft mooring).
        encounter: rad/s, |omega_e|, the frequency of the motion (omega at zero speed).
    """

    wavelength: float
    direction: float
    omega: float
    heave: float
    roll: float
    pitch: float
    speed: float = 0.0
    encounter: float = math.nan

    def __post_init__(self) -> None:
        if math.isnan(self.encounter):
            object.__setattr__(self, "encounter", self.omega)


def rides(encounter: float, max_time: float) -> bool:
    """Whether a boat meeting the wave at ``encounter`` (rad/s, >= 0) rides it.

    It does when it meets the wave fewer than :data:`MIN_ENCOUNTERS` times in ``max_time`` s.
    """
    return encounter * max_time < 2 * math.pi * MIN_ENCOUNTERS


def encounter_frequency(omega: float, wavenumber: float, speed: float, direction: float
                        ) -> float:
    """omega_e = omega - k U cos(beta), rad/s (negative: the boat overtakes the wave).

    Args:
        omega: rad/s, the wave's frequency.
        wavenumber: rad/m.
        speed: m/s, ahead.
        direction: rad, the wave's direction of travel relative to the bow.
    """
    return omega - wavenumber * speed * math.cos(direction)


def regular_wave_response(params: BoatParams, wavelength: float, direction: float,
                          amplitude: float, gravity: float = 9.81, depth: float = math.inf,
                          dt: float = 0.01, settle: float = 20.0, periods: int = 6,
                          tolerance: float = 0.01, max_time: float = 300.0,
                          speed: float = 0.0) -> Response:
    """The boat's first-harmonic heave, roll and pitch in a regular wave (module docstring).

    The boat starts afloat at the origin heading +x (initialized here for this sea, so a
    ``froude_krylov`` hull is panelled for this wavelength). At zero speed it is held there by
    a soft mooring of :data:`MOORING_PERIODS` wave periods (at least 30 s; :mod:`.mooring`, as
    a towing tank does: free, it would drift with the waves and meet them at another
    frequency); at a ``speed`` it starts at that speed on a carriage (:mod:`.carriage`) and
    the periods below are those of encounter. It runs ``settle`` s plus four
    periods; then windows of ``periods`` periods are analysed (the Fourier coefficient at
    omega) until three in a row agree within ``tolerance`` (of the value, or of 2 % of the
    wave's own scale, 1 m/m and k rad/m, for a motion near zero): a lightly damped mode near
    resonance takes long to forget its start, and its beat with the wave (at the difference
    of the frequencies) can make two windows agree by chance. At most ``max_time`` s.

    Args:
        params: the boat as a scenario gives it (``derive`` not yet applied) or derived; its
            own mooring or carriage is replaced.
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
        speed: m/s ahead (0: moored).

    Raises:
        ValueError: towed, the boat would ride the wave (encounter period over ``max_time`` /
            10).
    """
    wave = WaveComponent(amplitude, wavelength, direction, 0.0, 0.0)
    sea = WaveField((wave,), gravity, depth)
    omega = float(angular_frequency(wave.wavenumber, gravity, depth))
    encounter = abs(encounter_frequency(omega, wave.wavenumber, speed, direction))
    if speed != 0.0 and rides(encounter, max_time):
        raise ValueError(f"speed {speed} m/s meets the wave of {wavelength:g} m from "
                         f"{math.degrees(direction):g} deg at {encounter:.3g} rad/s: fewer than "
                         f"10 encounters in {max_time:g} s")
    inputs, period = FleetInputs.stack([BoatInputs()]), 2 * math.pi / encounter
    system, state = pipeline.init(System.build([_held(params, period, speed)]),
                                  FleetState.stack([initial_state(params, np.zeros(3))]), sea)
    if speed != 0.0:
        state = replace(state, velocity=state.velocity + np.array([[speed, 0.0, 0.0]]))
    floor = 0.02 * np.array([1.0, wave.wavenumber, wave.wavenumber])
    state = _run(system, state, inputs, sea, dt, round((settle + 4 * period) / dt))[0]
    window = round(periods * period / dt)
    history: list[np.ndarray] = []
    while True:
        state, motion = _run(system, state, inputs, sea, dt, window)
        history.append(_first_harmonic(motion, encounter) / amplitude)
        last = np.array(history[-3:])
        done = len(last) == 3 and np.all(
            np.ptp(last, axis=0) <= tolerance * np.maximum(last[-1], floor))
        if done or state.t + window * dt > max_time:
            return Response(wavelength, direction, omega, *map(float, history[-1]),
                            speed=speed, encounter=encounter)


def _held(params: BoatParams, period: float, speed: float) -> BoatParams:
    """``params`` on a carriage at ``speed`` m/s, or (0) on a soft mooring of the period (s).

    The boat's own mooring or carriage (scenario keys) is replaced; both are placed by
    :func:`.pipeline.init` where the boat starts.
    """
    if params.derive is not None:  # this mooring, not the scenario's (``mooring`` key)
        params = replace(params, derive=replace(params.derive, mooring_period=None))
    if speed != 0.0:
        return replace(params, mooring=None,
                       carriage=Carriage(speed, np.full(2, np.nan), math.nan))
    start = initial_state(params, np.zeros(3))
    return replace(params, carriage=None, mooring=soft_mooring(
        np.array([start.position[0], start.position[1], 0.0]), horizontal_mass(params),
        max(MOORING_PERIODS * period, 30.0)))


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
                       direction: float, viscous: np.ndarray | None = None,
                       encounter: float | None = None, speed: float = 0.0,
                       held: tuple[int, ...] = ()) -> np.ndarray:
    """(6,) complex motion per metre of wave amplitude by linear potential flow.

    Args:
        hydro: the hull's coefficients.
        mass_matrix: (6, 6) rigid-body mass matrix about the centre of mass
            (:func:`rigid_body_matrix`).
        omega: rad/s, the wave's frequency.
        direction: rad, the waves' direction of travel relative to the bow.
        viscous: (6,) linear damping added to B(omega) on the body's own velocity (the
            boat's viscous roll, pitch and yaw damping act so), or None.
        encounter: rad/s, omega_e at forward speed (:func:`encounter_frequency`; negative: an
            overtaken wave, met as the wave of |omega_e| from the opposite direction with its
            phase reversed, as :mod:`.diffraction` does), or None: omega (zero speed).
        speed: m/s ahead, for the radiation's U L terms (module docstring).
        held: the dofs (0-5) a carriage holds (their motion is zero).

    Returns:
        Surge, sway, heave (m/m) of the centre of mass, roll, pitch, yaw (rad/m), complex
        amplitudes (Re[x e^{-i |omega_e| t}], phase relative to the wave crest at the
        origin). Surge, sway and yaw have no restoring force: their values are the free body's.
    """
    w_e = omega if encounter is None else encounter
    met = abs(w_e)
    froude_krylov = hydro.froude_krylov_at(np.array([omega]), np.array([direction]))[0]
    if w_e < 0.0:
        excitation = (np.conj(froude_krylov)
                      + hydro.diffraction_at(np.array([met]), np.array([direction + np.pi]))[0])
    else:
        excitation = froude_krylov + hydro.diffraction_at(np.array([met]),
                                                          np.array([direction]))[0]
    added, radiation = hydro.added_mass_at(met), hydro.damping_at(met)
    damping = radiation if viscous is None else radiation + np.diag(viscous)
    impedance = (-met**2 * (mass_matrix + added) - 1j * met * damping
                 + hydro.hydrostatic_stiffness + speed * (radiation - 1j * met * added) @ _L)
    free = [k for k in range(6) if k not in held]
    motion = np.zeros(6, complex)
    motion[free] = np.linalg.solve(impedance[np.ix_(free, free)], excitation[free])
    return motion
