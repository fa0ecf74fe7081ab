"""The default box in regular waves against potential flow: heave and pitch RAOs in head seas,
roll in beam seas.

The boat with ``froude_krylov`` pressure and the Capytaine coefficient file
(tests/data/hydro/box_4x2x1_d0.5.npz: diffraction, and radiation by the Cummins equation, A_inf
6 x 6 and the fitted memory) is run in a small regular wave, held on station by a soft mooring
as in a towing tank (:func:`boat_dynamics.physics.experiments.seakeeping.regular_wave_response`),
until its
motion is periodic; its amplitude per metre of wave is compared with Capytaine's RAO at the
file's own frequencies (no interpolation), from 0.51 to 13 boat lengths, resonances included.
Asserted: the issue's bounds, 15 % (or 0.05 m/m for heave). Measured: heave -4 to +2 % down to
1.55 L, +13 % at 1.3 L, within 0.01 m/m below; pitch -5 to +3 %; roll -5 to +2 % (the roll
resonance, 1.55 L: +2 %). Free, without the mooring, a box in beam seas drifts sideways at
0.04 m/s and the roll near resonance grows to +60 % as it meets the waves at another
frequency. With ``radiation: resonance`` (constant coefficients at the natural frequencies)
long-wave heave is 9-15 % low and long-wave roll 27-34 % high (no sway-roll coupling); one
check keeps that option working.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics.experiments.seakeeping import (
    potential_flow_rao,
    regular_wave_response,
    rigid_body_matrix,
)
from boat_dynamics.physics.potential_flow.hydro import load_coefficients
from boat_dynamics.physics.scenario import parse_scenario

BOX = Path(__file__).resolve().parents[3] / "data" / "hydro" / "box_4x2x1_d0.5.npz"
HEAD_SEAS = 4  # index of 180 deg (waves travelling toward -x) in the file's directions
BEAM_SEAS = 2  # index of 90 deg (waves travelling toward +y, from starboard)


def _response(omega: float, a: float = 0.02, direction: float = math.pi,
              radiation: str = "cummins", max_time: float = 300.0
              ) -> tuple[float, float, float]:
    """Heave (m/m), roll and pitch (rad/m) amplitudes of the centre of mass.

    At most ``max_time`` s of simulated time (:func:`regular_wave_response`).
    """
    sc = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                    "buoyancy": {"pressure": "froude_krylov"},
                                    "damping": {"critical_ratio": [0, 0, 0]},
                                    "hydrodynamics": {"coefficients": str(BOX),
                                                      "radiation": radiation}}]})
    r = regular_wave_response(sc.boats[0].params, 2 * math.pi * 9.81 / omega**2, direction, a,
                              max_time=max_time)
    assert r.omega == pytest.approx(omega, rel=1e-12)
    return r.heave, r.roll, r.pitch


def _reference(index: int, direction: int) -> np.ndarray:
    with np.load(BOX) as data:
        return np.abs(data["rao"][index, direction])


# file index: omega rad/s, wavelength / L = 2 pi g / omega^2 / 4 m
# 2: 1.09, 13 | 3: 1.39, 8.0 | 5: 1.97, 4.0 | 7: 2.56, 2.3 | 8: 2.86, 1.9 | 9: 3.15, 1.55
# 10: 3.45, 1.3 | 11: 3.74, 1.1 | 12: 4.04, 0.94 | 14: 4.63, 0.72 | 16: 5.22, 0.57 | 17: 5.51, 0.51
@pytest.mark.parametrize("index", [2, 3, 5, 7, 8, 9, 10, 11, 12, 14, 16, 17])
def test_head_sea_raos_of_the_box_follow_potential_flow(index):
    rao = _reference(index, HEAD_SEAS)
    heave, _, pitch = _response(float(load_coefficients(BOX).omega[index]))
    assert heave == pytest.approx(rao[2], rel=0.15, abs=0.05)
    assert pitch == pytest.approx(rao[4], rel=0.15)


@pytest.mark.parametrize("index", [2, 3, 5, 7, 8, 9, 10, 11, 12, 14, 16])
def test_beam_sea_roll_of_the_box_follows_potential_flow(index):
    rao = _reference(index, BEAM_SEAS)
    _, roll, _ = _response(float(load_coefficients(BOX).omega[index]), a=0.01,
                           direction=math.pi / 2)
    assert roll == pytest.approx(rao[3], rel=0.15)


def test_the_resonance_radiation_option_still_follows_potential_flow_in_short_waves():
    # ``radiation: resonance``, kept for comparison: right where the coefficients at the
    # natural frequencies are the wave's (0.94 L: heave measured -0 %, pitch +20 % -> 15 %
    # not held; 0.72 L: heave within 0.05, pitch -3 %). Without the memory the heave's own
    # mode is hardly damped: it beats with the wave (0.034-0.042 m/m, window after window, to
    # 294 s) and never settles within regular_wave_response's 1 %, while the pitch has
    # settled (0.0354 rad/m) by 42 s. So 60 s, not the 300 s the run used to take to give up.
    rao = _reference(14, HEAD_SEAS)
    heave, _, pitch = _response(float(load_coefficients(BOX).omega[14]), radiation="resonance",
                                max_time=60.0)
    assert heave == pytest.approx(rao[2], rel=0.15, abs=0.05)
    assert pitch == pytest.approx(rao[4], rel=0.15)


def test_potential_flow_rao_is_capytaines_at_its_own_frequencies():
    # The frequency-domain solve (what `boatsim rao` prints beside the simulation) against
    # Capytaine's post_pro.rao, every frequency and direction of the file, heave, roll, pitch
    # (and surge, sway, yaw, which have no restoring force), with the boat's own mass matrix.
    ref = load_coefficients(BOX)
    params = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2]}]}).boats[0].params
    mass = rigid_body_matrix(params)
    assert np.allclose(mass, ref.inertia_matrix, rtol=1e-12)
    with np.load(BOX) as data:
        rao = data["rao"]
    for i, omega in enumerate(ref.omega):
        for j, direction in enumerate(ref.directions):
            got = potential_flow_rao(ref, mass, float(omega), float(direction))
            assert np.allclose(got, rao[i, j], rtol=1e-9, atol=1e-12 * np.abs(rao[i, j]).max())


def test_potential_flow_rao_mirrors_a_symmetric_hull():
    # Waves from port (-90 deg) move a centreplane-symmetric hull as from starboard, with roll
    # of the other sign (the file holds 0..180 deg only).
    ref = load_coefficients(BOX)
    starboard = potential_flow_rao(ref, ref.inertia_matrix, 3.0, math.pi / 2)
    port = potential_flow_rao(ref, ref.inertia_matrix, 3.0, -math.pi / 2)
    assert port[2] == pytest.approx(starboard[2], rel=1e-12)
    assert port[3] == pytest.approx(-starboard[3], rel=1e-12)


def _linear_box():
    return parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                      "buoyancy": {"pressure": "linear"},
                                      "damping": {"water_velocity": "hull",
                                                  "critical_ratio": [0, 0, 0]},
                                      "hydrodynamics": {"coefficients": str(BOX)}}]}
                          ).boats[0].params


@pytest.mark.parametrize("index", [3, 8, 10, 14, 16])
def test_linear_seakeeping_gives_potential_flows_raos(index):
    # `pressure: linear` (hydrostatics against the calm-water plane, the incident waves'
    # Froude-Krylov force and the diffraction from the file, Cummins radiation) with the damping
    # taken against the water over the hull: linear potential flow in the time domain. Heave,
    # pitch (head seas) within 5 % or 0.005, roll (beam seas) within 6 % (measured: within 2 %
    # but roll at 1.89 L, on the flank of its resonance, -5.1 %; short-wave heave 0.0377 /
    # 0.0376 at 0.72 L: with the water at the reference point, the default quadratic heave
    # drag, driven by the waves' orbital velocity there, took 29 % off it).
    rao_head, rao_beam = _reference(index, HEAD_SEAS), _reference(index, BEAM_SEAS)
    omega = float(load_coefficients(BOX).omega[index])
    wavelength = 2 * math.pi * 9.81 / omega**2
    head = regular_wave_response(_linear_box(), wavelength, math.pi, 0.02)
    beam = regular_wave_response(_linear_box(), wavelength, math.pi / 2, 0.01)
    assert head.heave == pytest.approx(rao_head[2], rel=0.05, abs=0.005)
    assert head.pitch == pytest.approx(rao_head[4], rel=0.05)
    assert beam.roll == pytest.approx(rao_beam[3], rel=0.06)


def _towed_box() -> object:
    return parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                      "buoyancy": {"pressure": "froude_krylov"},
                                      "hydrodynamics": {"coefficients": str(BOX)}}]}
                          ).boats[0].params


def test_a_towed_boat_meets_a_head_sea_at_the_encounter_frequency():
    # The box towed at 1 m/s into an 8 m head sea (omega 2.776 rad/s): its heave has its peak
    # at omega_e = omega + k U = 3.561 rad/s (a 0.003 rad/s scan of the spectrum, 40 s after
    # 10 s of settling), not at the wave's own frequency.
    from dataclasses import replace

    from boat_dynamics.physics.core import pipeline
    from boat_dynamics.physics.core.model import BoatInputs, initial_state
    from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
    from boat_dynamics.physics.force_models.carriage import Carriage
    from ocean_sim.physics.waves import WaveComponent, WaveField

    wave = WaveComponent(0.02, 8.0, math.pi, 0.0, 0.0)
    sea = WaveField((wave,))
    omega, k = math.sqrt(9.81 * wave.wavenumber), wave.wavenumber
    params = replace(_towed_box(), carriage=Carriage(1.0, np.full(2, np.nan), math.nan))
    system, state = pipeline.init(System.build([params]),
                                  FleetState.stack([initial_state(params, np.zeros(3))]), sea)
    inputs, t, z = FleetInputs.stack([BoatInputs()]), [], []
    for step in range(5000):
        state = pipeline.step(system, state, inputs, sea, 0.01).state
        if step >= 1000:
            t.append(state.t)
            z.append(state.position[0, 2])
    t, z = np.array(t), np.array(z) - np.mean(z)
    scan = np.arange(1.5, 6.0, 0.003)
    peak = scan[np.argmax(np.abs(np.exp(1j * np.outer(scan, t)) @ z))]
    assert peak == pytest.approx(omega + k * 1.0, abs=0.02)
    assert state.position[0, 0] == pytest.approx(50.0 + initial_state(params, np.zeros(3))
                                                 .position[0], abs=0.05)


def test_towed_in_head_seas_heave_and_pitch_follow_potential_flow_at_speed():
    # The box towed at 1 m/s (Froude number 0.16) in an 8 m head sea, met at 3.56 rad/s, near
    # its heave resonance: potential flow with the zero-speed coefficients at the encounter
    # frequency, surge held, and the radiation's U L terms (seakeeping module docstring).
    # Measured: heave 0.810 against 0.778 (without the U L terms 0.616), pitch
    # 27.8 against 27.7 deg/m (with surge free 26.1).
    from boat_dynamics.tools.rao import theory_curve

    params = _towed_box()
    r = regular_wave_response(params, 8.0, math.pi, 0.02, speed=1.0)
    assert r.encounter == pytest.approx(math.sqrt(9.81 * 2 * math.pi / 8) + 2 * math.pi / 8,
                                        rel=1e-12)
    heave, _, pitch = theory_curve(params, 9.81, math.inf, 1.0)(np.array([8.0]), math.pi)[0]
    assert r.heave == pytest.approx(heave, rel=0.08)
    assert r.pitch == pytest.approx(pitch, rel=0.05)
    zero_speed = theory_curve(params, 9.81, math.inf, 0.0)(np.array([8.0]), math.pi)[0]
    assert abs(r.heave - heave) < 0.3 * abs(r.heave - zero_speed[0])


def test_potential_flow_at_speed_has_salvesen_tuck_faltinsens_heave_pitch_terms():
    # The impedance's heave-from-pitch entry at speed U changes by U (B33 - i omega A33): STF's
    # A35 - U B33 / omega^2 and B35 + U A33 in -omega^2 A35 - i omega B35; zero speed and
    # no held dof give the zero-speed answer exactly.
    ref = load_coefficients(BOX)
    mass = ref.inertia_matrix
    plain = potential_flow_rao(ref, mass, 3.0, math.pi)
    assert np.array_equal(potential_flow_rao(ref, mass, 3.0, math.pi, encounter=3.0), plain)
    x = potential_flow_rao(ref, mass, 2.5, math.pi, encounter=3.2, speed=1.5, held=(0, 1, 5))
    assert x[0] == 0 and x[1] == 0 and x[5] == 0
    w = 3.2
    a, b = ref.added_mass_at(w), ref.damping_at(w)
    z = -w**2 * (mass + a) - 1j * w * b + ref.hydrostatic_stiffness
    z[2, 4] += 1.5 * (b[2, 2] - 1j * w * a[2, 2])
    z[3, 4] += 1.5 * (b[3, 2] - 1j * w * a[3, 2])
    z[4, 4] += 1.5 * (b[4, 2] - 1j * w * a[4, 2])
    force = (ref.froude_krylov_at(np.array([2.5]), np.array([math.pi]))[0]
             + ref.diffraction_at(np.array([3.2]), np.array([math.pi]))[0])
    free = [2, 3, 4]
    assert x[free] == pytest.approx(np.linalg.solve(z[np.ix_(free, free)], force[free]),
                                    rel=1e-10)
