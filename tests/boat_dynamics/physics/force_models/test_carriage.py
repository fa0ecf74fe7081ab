"""The towing carriage (physics/force_models/carriage.py, the ``carriage`` key): a towing tank."""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from ready_scenarios import SEED_MODEL

from boat_dynamics.physics.body.rigid_body import quat_from_euler, quat_to_euler, rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.model import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.force_models.carriage import Carriage, towed_velocity
from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
from ocean_sim.physics.waves import WaveComponent, WaveField

DT = 0.01
LINEAR, QUADRATIC = 300.0, 200.0  # N s/m, N s^2/m^2: surge resistance R(U) = a U + b U |U|


def _tow(boat: dict, sea: WaveField, seconds: float, yaw_deg: float = 30.0):
    """Tow ``boat`` from rest at its carriage speed; (times, towing (K, 3), states)."""
    sc = parse_scenario({"boats": [{**boat, "initial_pose": {"yaw_deg": yaw_deg}}]})
    system, state = pipeline.start(sc.boats, sea)
    inputs = FleetInputs.stack([BoatInputs()])
    towing, states = [], []
    for _ in range(round(seconds / DT)):
        step = pipeline.step(system, state, inputs, sea, DT)
        state = step.state
        towing.append(step.towing[0].copy())
        states.append(state)
    return np.array(towing), states


@pytest.mark.parametrize("speed", [0.5, 2.0, -1.0])
def test_the_towing_force_in_calm_water_is_the_hulls_resistance(speed):
    # R(U) = a U + b U |U| of the boat's surge damping, to rounding: the carriage's force is
    # what a resistance test measures; the boat runs down the line at U, on its heading
    boat = {**SEED_MODEL, "carriage": {"speed": speed},
            "damping": {"linear": [LINEAR, 4000, 0, 1000, 0, 3000],
                        "quadratic": [QUADRATIC, 0, 0, 0, 0, 0]}}
    towing, states = _tow(boat, WaveField(), 5.0)
    resistance = LINEAR * speed + QUADRATIC * speed * abs(speed)
    assert towing[-100:, 0].mean() == pytest.approx(resistance, rel=1e-9)
    assert np.abs(towing[-100:, 1:]).max() < 1e-6 * abs(resistance)
    last = states[-1]
    heading = math.radians(30.0)
    travelled = last.position[0, :2] - states[0].position[0, :2]
    assert travelled == pytest.approx(speed * (last.t - states[0].t) * np.array(
        [math.cos(heading), math.sin(heading)]), abs=1e-9)
    assert quat_to_euler(last.orientation[0])[2] == pytest.approx(heading, abs=1e-12)


def test_towed_into_head_seas_the_boat_heaves_and_pitches_and_meets_added_resistance():
    # the shipped default model, 1.5 m/s into a 0.1 m, 8 m wave: heave and pitch free (they
    # move with the encounter frequency), sway and yaw held, a mean towing force above calm
    # water's (measured: 709 against 581 N; heave 0.12 m and pitch 3.6 deg peak to
    # peak)
    boat = {"carriage": {"speed": 1.5}}
    wave = WaveField((WaveComponent(0.1, 8.0, math.radians(210.0), 0.3, 0.0),))
    calm, _ = _tow(boat, WaveField(), 20.0)
    waves, states = _tow(boat, wave, 20.0)
    late = slice(-1000, None)
    z = np.array([s.position[0, 2] for s in states])[late]
    pitch = np.array([quat_to_euler(s.orientation[0])[1] for s in states])[late]
    assert np.ptp(z) > 0.05 and math.degrees(np.ptp(pitch)) > 1.0
    assert waves[late, 0].mean() > calm[late, 0].mean() * 1.05 > 0.0
    heading = math.radians(30.0)
    across = np.array([-math.sin(heading), math.cos(heading)])
    offsets = [abs(across @ (s.position[0, :2] - states[0].position[0, :2])) for s in states]
    assert max(offsets) < 1e-3
    assert max(abs(quat_to_euler(s.orientation[0])[2] - heading) for s in states) < 1e-3


@settings(max_examples=50, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), speed=st.floats(-5.0, 5.0))
def test_the_constraint_is_met_by_the_least_action_impulse(seed, speed):
    # any mass matrix (coupled, as the added mass makes it), attitude and velocity: the
    # constrained velocities meet the three constraints, and the change is M^-1 C^T lambda
    # (Gauss: the carriage does nothing the constraints do not ask for)
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(6, 6))
    mass = a @ a.T + 6.0 * np.eye(6)
    roll, pitch, yaw = rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-3, 3)
    rotation = rotation_matrix(quat_from_euler(roll, pitch, yaw))
    carriage = Carriage(speed, np.array([1.0, -2.0]), yaw)
    position = np.array([1.0, -2.0, 0.0])
    nu = rng.normal(size=6)
    out, load = towed_velocity(carriage, mass, rotation, position, nu, DT)
    world_v, world_w = rotation @ out[:3], rotation @ out[3:]
    along = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    across = np.array([-math.sin(yaw), math.cos(yaw), 0.0])
    assert world_v @ along == pytest.approx(speed, abs=1e-9)
    assert world_v @ across == pytest.approx(0.0, abs=1e-9)  # on the line: nothing to correct
    assert world_w[2] == pytest.approx(0.0, abs=1e-9)
    rows = np.zeros((3, 6))
    rows[0, :3], rows[1, :3], rows[2, 3:] = along @ rotation, across @ rotation, rotation[2]
    np.testing.assert_allclose(mass @ (out - nu), rows.T @ (load * DT), atol=1e-9)


def test_a_towed_boat_beside_a_free_one_leaves_it_alone():
    sc = parse_scenario({"boats": [
        {"name": "towed", **SEED_MODEL, "carriage": {"speed": 1.0}},
        {"name": "free", **SEED_MODEL, "initial_pose": {"position": [0.0, 20.0, 0.0]}}]})
    alone = parse_scenario({"boats": [
        {"name": "free", **SEED_MODEL, "initial_pose": {"position": [0.0, 20.0, 0.0]}}]})
    sea = WaveField((WaveComponent(0.2, 15.0, 0.5, 0.4, 0.0),))
    system, state = pipeline.start(sc.boats, sea)
    single_system, single = pipeline.start(alone.boats, sea)
    for _ in range(100):
        step = pipeline.step(system, state, FleetInputs.stack([BoatInputs(0.5, 0.1)] * 2),
                             sea, DT)
        state = step.state
        single = pipeline.step(single_system, single, FleetInputs.stack([BoatInputs(0.5, 0.1)]),
                               sea, DT).state
    assert not step.towing[1].any() and step.towing[0, 0] != 0.0
    np.testing.assert_allclose(state.position[1], single.position[0], rtol=0, atol=1e-9)
    assert pipeline.step(single_system, single, FleetInputs.stack([BoatInputs()]), sea,
                         DT).towing is None


@pytest.mark.parametrize(("boat", "key", "allowed"), [
    ({"carriage": {"speed": 51.0}}, "boats[0].carriage.speed", "[-50, 50] m/s"),
    ({"carriage": {"speed": float("nan")}}, "boats[0].carriage.speed", "finite"),
    ({"carriage": {"heading": 1.0}}, "boats[0].carriage.heading", "allowed keys here: speed"),
    ({"carriage": 2.0}, "boats[0].carriage", "mapping"),
    ({"carriage": {"speed": 1.0}, "mooring": {"period": 60.0}}, "boats[0].mooring",
     "held by the carriage")])
def test_a_bad_carriage_is_refused_with_its_key(boat, key, allowed):
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [boat]})
    assert err.value.key == key and allowed in err.value.allowed


@given(st.floats(-math.pi, math.pi), st.floats(-0.5, 0.5), st.floats(-0.5, 0.5),
       st.floats(-math.pi, math.pi))
@example(0.5, 0.0, 0.0, 0.5)
@settings(max_examples=50, deadline=None)
def test_the_carriage_wrench_in_the_body_frame_is_the_world_one_turned(heading, roll, pitch,
                                                                        yaw):
    # wrench/carriage: R^T of the world force along and across the line and of the yaw moment
    from boat_dynamics.physics.force_models.carriage import body_wrench

    carriage = Carriage(1.0, np.zeros(2), heading)
    rotation = rotation_matrix(quat_from_euler(roll, pitch, yaw))
    body = body_wrench(carriage, rotation, np.array([120.0, -8.0, 15.0]))
    along = np.array([math.cos(heading), math.sin(heading), 0.0])
    across = np.array([-math.sin(heading), math.cos(heading), 0.0])
    np.testing.assert_allclose(rotation @ body[:3], 120.0 * along - 8.0 * across, atol=1e-9)
    np.testing.assert_allclose(rotation @ body[3:], [0.0, 0.0, 15.0], atol=1e-9)
    if roll == pitch == 0.0 and yaw == heading:  # on the line: along is surge
        np.testing.assert_allclose(body, [120.0, -8.0, 0.0, 0.0, 0.0, 15.0], atol=1e-9)
