"""The soft mooring of the RAO runs: a critically damped spring on x, y and heading."""

import math
from dataclasses import replace

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_to_euler, rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.model import BoatInputs, initial_state
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.force_models.mooring import mooring_wrench, soft_mooring
from boat_dynamics.physics.scenario import parse_scenario
from ocean_sim.physics.waves import WaveField

NO_DAMPING = {"linear": [0.0] * 6, "quadratic": [0.0] * 6}


def _moored_box(period: float):
    params = parse_scenario({"boats": [{"damping": NO_DAMPING, "buoyancy": {
        "pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}}]}).boats[0].params
    mass = np.array([params.mass, params.mass, params.inertia[2]])
    return replace(params, mooring=soft_mooring(np.zeros(3), mass, period))


@pytest.mark.parametrize(("offset", "yaw"), [((1.0, 0.0), 0.0), ((0.0, -0.5), 0.0),
                                             ((0.0, 0.0), 0.3)])
def test_a_displaced_hull_returns_as_a_critically_damped_oscillator(offset, yaw):
    # x(t) = x0 (1 + omega t) e^{-omega t} (no overshoot), in still water, no other damping:
    # within 1 % of the start offset at a quarter, half and one natural period.
    period = 20.0
    params = _moored_box(period)
    sea = WaveField()
    start = initial_state(params, np.array([*offset, 0.0]), yaw=yaw)
    system, state = pipeline.init(System.build([params]), FleetState.stack([start]), sea)
    omega, dt = 2 * math.pi / period, 0.01
    inputs = FleetInputs.stack([BoatInputs()])
    x0 = np.array([*offset, yaw])
    for t_end in (period / 4, period / 2, period):
        while state.t < t_end - dt / 2:
            state = pipeline.step(system, state, inputs, sea, dt).state
        now = np.array([*(state.position[0, :2] - params.center_of_mass[:2]),
                        quat_to_euler(state.orientation[0])[2]])
        expected = x0 * (1 + omega * state.t) * math.exp(-omega * state.t)
        assert np.abs(now - expected).max() <= 0.01 * np.abs(x0).max()


def test_the_mooring_pulls_horizontally_at_the_centre_of_mass():
    # Upright: no vertical force, no roll or pitch moment; the force opposes the offset and
    # the yaw moment the heading error (the shorter way round: 350 deg is -10 deg).
    rotation = rotation_matrix(np.array([0.0, 0.0, math.sin(math.radians(175)),
                                         math.cos(math.radians(175))]))[None]
    w = mooring_wrench(np.array([[100.0, 200.0, 50.0]]), np.zeros((1, 3)), np.zeros((1, 3)),
                       np.array([[1.0, -2.0, 0.3]]), rotation, np.zeros((1, 3)),
                       np.zeros((1, 3)))
    world_force = rotation[0] @ w.force[0]
    assert world_force == pytest.approx([-100.0, 400.0, 0.0])
    assert w.torque[0, :2] == pytest.approx([0.0, 0.0], abs=1e-12)
    assert w.torque[0, 2] == pytest.approx(50.0 * math.radians(10.0))


def test_a_free_boat_beside_a_moored_one_steps_as_if_alone():
    moored = _moored_box(30.0)
    free = parse_scenario({"boats": [{"damping": NO_DAMPING}]}).boats[0].params
    sea = WaveField()
    starts = [initial_state(moored, np.array([0.5, 0.0, 0.0])),
              initial_state(free, np.array([10.0, 0.0, 0.0]))]
    both, state = pipeline.init(System.build([moored, free]), FleetState.stack(starts), sea)
    alone, single = pipeline.init(System.build([free]), FleetState.stack(starts[1:]), sea)
    inputs2, inputs1 = (FleetInputs.stack([BoatInputs(0.5, 0.1)] * n) for n in (2, 1))
    for _ in range(200):
        step = pipeline.step(both, state, inputs2, sea, 0.01)
        state = step.state
        single = pipeline.step(alone, single, inputs1, sea, 0.01).state
    # as tests/boat_dynamics/physics/core/test_pipeline.py's fleet test: equal to summation order
    np.testing.assert_allclose(state.position[1], single.position[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(state.orientation[1], single.orientation[0], rtol=0, atol=1e-12)
    assert np.abs(step.forces.mooring.force[0]).max() > 0.0
    assert not step.forces.mooring.force[1].any()


def test_the_mooring_key_holds_a_boat_where_it_starts():
    # `mooring: {period: 20}`: anchored at the start pose of each boat (two boats sharing their
    # parameters, each its own anchor); started at 0.5 m/s ahead in still water without other
    # damping, x(t) = v0 t e^{-omega t} (critically damped, peak v0 / (omega e) at 1 / omega),
    # within 1 % of the peak, and back to the anchor
    period, v0 = 20.0, 0.5
    boat = {"damping": NO_DAMPING, "buoyancy": {"pressure": "hydrostatic"},
            "hydrodynamics": {"coefficients": "none"}, "mooring": {"period": period}}
    sc = pipeline.init_scenario(parse_scenario({"boats": [
        {"name": "a", **boat, "initial_pose": {"position": [5.0, -3.0, 0.0], "yaw_deg": 30.0,
                                               "velocity": [v0, 0.0, 0.0]}},
        {"name": "b", **boat, "initial_pose": {"position": [-5.0, 0.0, 0.0]}}]}))
    a, b = sc.boats
    assert a.params.mooring.anchor == pytest.approx([5.0, -3.0, math.radians(30.0)])
    assert b.params.mooring.anchor == pytest.approx([-5.0, 0.0, 0.0])
    system, state = pipeline.start(sc.boats, WaveField())
    omega, dt = 2 * math.pi / period, 0.01
    inputs = FleetInputs.stack([BoatInputs()] * 2)
    along = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    for t_end in (1 / omega, 2 / omega, 3 * period):
        while state.t < t_end - dt / 2:
            state = pipeline.step(system, state, inputs, WaveField(), dt).state
        x = float((state.position[0, :2] - [5.0, -3.0]) @ along)
        expected = v0 * state.t * math.exp(-omega * state.t)
        assert x == pytest.approx(expected, abs=0.01 * v0 / (omega * math.e)), state.t
    assert np.abs(state.position[1, :2] - [-5.0, 0.0]).max() < 1e-9  # b: never moved
    assert parse_scenario({"boats": [boat]}).boats[0].params.derive.mooring_period == period
    assert parse_scenario({"boats": [{}]}).boats[0].params.derive.mooring_period is None


@pytest.mark.parametrize(("value", "key", "allowed"), [
    ({"period": 2.0}, "boats[0].mooring.period", "[5, 3600] s"),
    ({"period": float("inf")}, "boats[0].mooring.period", "finite"),
    ({"stiffness": 3.0}, "boats[0].mooring.stiffness", "allowed keys here: period"),
    (5, "boats[0].mooring", "mapping")])
def test_a_bad_mooring_is_refused_with_its_key(value, key, allowed):
    from boat_dynamics.physics.scenario import ScenarioError

    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"mooring": value}]})
    assert err.value.key == key and allowed in err.value.allowed


def test_boatsim_rao_holds_a_moored_boat_with_its_own_mooring():
    # regular_wave_response sets a mooring of 15 wave periods; a scenario's stiff 5 s
    # mooring, which would change the response near it, is cleared: the same answer bit for bit
    from boat_dynamics.physics.experiments.seakeeping import regular_wave_response

    boat = {"buoyancy": {"pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}}
    free = parse_scenario({"boats": [boat]}).boats[0].params
    moored = parse_scenario({"boats": [{**boat, "mooring": {"period": 5.0}}]}).boats[0].params
    run = {"settle": 1.0, "periods": 2, "max_time": 10.0}  # one window: the first answer
    assert regular_wave_response(moored, 12.0, math.pi / 2, 0.05, **run) == (
        regular_wave_response(free, 12.0, math.pi / 2, 0.05, **run))
