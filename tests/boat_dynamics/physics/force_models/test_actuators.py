"""Propulsion options, rudder models, keel reflection, Stokes drift option."""

import math
from dataclasses import replace

import numpy as np
import pytest
from ready_scenarios import SEED_MODEL, ready

from boat_dynamics.physics.core.boat import BoatInputs, initial_state, step
from boat_dynamics.physics.force_models.keel import reflect_off_keel
from boat_dynamics.physics.force_models.propulsion import Propulsion, lagged_throttle, thrust
from boat_dynamics.physics.force_models.rudder import Rudder, rudder_wrench
from boat_dynamics.physics.scenario import ScenarioError
from ocean_sim.physics.waves import WaveComponent, WaveField, stokes_drift

STERN = np.array([-2.0, 0.0, -0.3])
AHEAD = np.array([1.0, 0.0, 0.0])
COM = np.array([0.0, 0.0, -0.2])


def test_thrust_lag_is_first_order():
    model = Propulsion(1000.0, STERN, AHEAD, time_constant=2.0)
    actual, dt = 0.0, 0.01
    for _ in range(200):  # one time constant
        actual = lagged_throttle(model, actual, 1.0, dt)
    assert actual == pytest.approx(1 - math.exp(-1.0), rel=1e-12)
    assert lagged_throttle(Propulsion(1000.0, STERN, AHEAD), 0.3, -0.7, dt) == -0.7


def test_thrust_at_the_stern_below_the_com_pitches_and_at_the_com_does_not():
    stern = thrust(Propulsion(1000.0, STERN, AHEAD), 1.0, 0.0, COM)
    assert stern.force.tolist() == [1000.0, 0.0, 0.0]
    # r_z = -0.1 m: r x F = -100 N m about +y; in FLU that is bow up (+y rotation is bow down)
    assert stern.torque[1] == pytest.approx(-1000.0 * 0.1)
    at_com = thrust(Propulsion(1000.0, STERN, AHEAD, at_center_of_mass=True), 1.0, 0.3, COM)
    assert at_com.torque.tolist() == [0.0, 0.0, 0.0]


def test_steerable_nozzle_turns_the_bow_to_port_for_a_positive_angle():
    w = thrust(Propulsion(1000.0, STERN, AHEAD, steerable=True), 1.0, 0.3, COM)
    assert w.force[0] == pytest.approx(1000 * math.cos(0.3))
    assert w.force[1] == pytest.approx(-1000 * math.sin(0.3))  # stern pushed to starboard
    assert w.torque[2] > 0  # yaw to port
    fixed = thrust(Propulsion(1000.0, STERN, AHEAD), 1.0, 0.3, COM)
    assert fixed.torque[2] == 0.0


def _ahead(u: float, v: float = 0.0) -> np.ndarray:
    return np.array([u, v, 0.0])


STILL = np.zeros(3)


def test_rudder_models():
    lift = Rudder("lift", math.radians(35), 0.25, 1.0, np.array([-2.0, 0, -0.5]))
    w1 = rudder_wrench(lift, 0.3, _ahead(2.0), STILL, 1025.0, COM)
    w2 = rudder_wrench(lift, 0.3, _ahead(4.0), STILL, 1025.0, COM)
    assert w1.force[1] == pytest.approx(-0.5 * 1025 * 0.25 * 4.0 * math.sin(0.3))
    assert w2.torque[2] == pytest.approx(4 * w1.torque[2]) and w1.torque[2] > 0
    assert rudder_wrench(lift, 0.3, _ahead(-2.0), STILL, 1025.0, COM).torque[2] < 0  # astern
    assert rudder_wrench(lift, 0.3, _ahead(0.0), STILL, 1025.0, COM).torque[2] == 0.0

    arcade = Rudder("torque", 0.5, max_torque=800.0)
    for u in (0.0, 3.0):
        w = rudder_wrench(arcade, 0.25, _ahead(u), STILL, 1025.0, COM)
        assert w.torque.tolist() == [0.0, 0.0, 400.0] and not w.force.any()

    hybrid = Rudder("hybrid", 0.5, max_torque=800.0, base_torque=200.0, max_speed=4.0)
    assert rudder_wrench(hybrid, 0.5, _ahead(0.0), STILL, 1025.0, COM).torque[2] == (
        pytest.approx(200.0))
    assert rudder_wrench(hybrid, 0.5, _ahead(4.0), STILL, 1025.0, COM).torque[2] == (
        pytest.approx(1000.0))
    assert rudder_wrench(hybrid, -0.25, _ahead(2.0), STILL, 1025.0, COM).torque[2] == (
        pytest.approx(-300.0))
    assert not rudder_wrench(Rudder("none"), 0.5, _ahead(3.0), STILL, 1025.0, COM).torque.any()


def test_the_lift_rudder_meets_the_flow_at_its_angle_of_attack():
    """Fossen (2021), sec. 9.5: F_y = -1/2 rho C A V^2 sin(delta + beta_R), beta_R the drift."""
    lift = Rudder("lift", math.radians(35), 0.25, 2.5, np.array([-2.0, 0, -0.5]))
    u, v, delta = 2.0, 0.3, 0.2
    beta = math.atan2(v, u)
    w = rudder_wrench(lift, delta, _ahead(u, v), STILL, 1025.0, COM)
    assert w.force[1] == pytest.approx(
        -0.5 * 1025 * 2.5 * 0.25 * (u * u + v * v) * math.sin(delta + beta), rel=1e-12)
    # amidships, a boat drifting to port (v > 0) is pushed back at the stern: the bow turns
    # to port, into its path (weathervane stability, N_v > 0)
    drift = rudder_wrench(lift, 0.0, _ahead(u, v), STILL, 1025.0, COM)
    assert drift.force[1] < 0 and drift.torque[2] > 0
    # amidships, yawing to port (r > 0) sweeps the stern to starboard: the rudder resists (N_r)
    yawing = rudder_wrench(lift, 0.0, _ahead(u), np.array([0.0, 0.0, 0.2]), 1025.0, COM)
    assert yawing.torque[2] < 0
    assert yawing.force[1] == pytest.approx(
        -0.5 * 1025 * 2.5 * 0.25 * math.hypot(u, -0.4) * -0.4, rel=1e-12)
    # a skeg adds the same lift at the flow's angle alone
    skeg = replace(lift, skeg_area=0.5)
    with_skeg = rudder_wrench(skeg, 0.0, _ahead(u, v), STILL, 1025.0, COM)
    assert with_skeg.force[1] == pytest.approx(3.0 * drift.force[1], rel=1e-12)
    assert rudder_wrench(skeg, delta, _ahead(u), STILL, 1025.0, COM).force[1] == pytest.approx(
        rudder_wrench(lift, delta, _ahead(u), STILL, 1025.0, COM).force[1], rel=1e-12)


def test_keel_reflection_turns_drift_into_headway_keeping_speed():
    v = np.array([2.0, 1.5, 0.1])
    out = v
    for _ in range(100):
        out = reflect_off_keel(out, 2.0, 0.01)
    assert out[1] == pytest.approx(1.5 * math.exp(-2.0))
    assert np.hypot(out[0], out[1]) == pytest.approx(np.hypot(2.0, 1.5), rel=1e-12)
    assert out[2] == 0.1 and out[0] > 2.0
    back = reflect_off_keel(np.array([-1.0, 1.0, 0.0]), 5.0, 0.1)
    assert back[0] < -1.0  # astern stays astern


def test_stokes_drift_option_carries_the_boat_with_the_waves(boat_factory):
    sea = WaveField((WaveComponent(0.6, 15.0, 0.0, 0.0, 0.0),))  # sine wave: no Gerstner mean
    u_s = stokes_drift(sea)[0]
    params = boat_factory(model="mesh", linear=(3000, 20000, 20000, 5000, 20000, 5000))

    def mean_drift(flag):
        p = replace(params, stokes_drift=flag)
        s = initial_state(p, [0.0, 0.0, 0.0])
        for _ in range(6000):
            s = step(p, s, BoatInputs(), sea, 0.01)
        x0 = s.position[0]
        for _ in range(6000):
            s = step(p, s, BoatInputs(), sea, 0.01)
        return (s.position[0] - x0) / 60.0

    assert mean_drift(True) - mean_drift(False) == pytest.approx(u_s, rel=0.2)


def test_scenario_keys_for_actuators():
    sc = ready({"boats": [{
        "propulsion": {"steerable": True, "time_constant": 0.5, "at_center_of_mass": False},
        "rudder": {"model": "hybrid", "max_torque": 500, "base_torque": 100, "max_speed": 5},
        "keel": {"model": "reflection", "rate": 0.5}, "stokes_drift": True}]})
    p = sc.boats[0].params
    assert p.propulsion.steerable and p.propulsion.time_constant == 0.5
    assert p.rudder.model == "hybrid" and p.keel_rate == 0.5 and p.stokes_drift
    with pytest.raises(ScenarioError, match=r"boats\[0\].rudder.max_torque: None"):
        ready({"boats": [{"rudder": {"model": "torque"}}]})
    with pytest.raises(ScenarioError, match=r"boats\[0\].propulsion.steerable: 'yes'"):
        ready({"boats": [{"propulsion": {"steerable": "yes"}}]})


def test_notes_velocity_decay_is_v_over_1_plus_c_dt_per_step():
    from dataclasses import replace


    sc = ready({"boats": [{**SEED_MODEL, "rudder": {"model": "none"},  # no lift resisting
                           "damping": {"linear": [0] * 6, "quadratic": [0] * 6,
                                       "decay": [0.4, 0, 0, 0, 0, 0.8]}}]})
    params, rest = sc.boats[0].params, sc.boats[0].initial
    # separately: a yaw rate turns a body-frame surge velocity (w x v)
    gliding = replace(rest, velocity=np.array([2.0, 0.0, 0.0]))
    spinning = replace(rest, angular_velocity=np.array([0.0, 0.0, 0.3]))
    dt, n = 0.01, 300
    for _ in range(n):
        gliding = step(params, gliding, BoatInputs(0.0, 0.0), WaveField(), dt)
        spinning = step(params, spinning, BoatInputs(0.0, 0.0), WaveField(), dt)
    assert gliding.velocity[0] == pytest.approx(2.0 / (1 + 0.4 * dt) ** n, rel=1e-9)
    assert spinning.angular_velocity[2] == pytest.approx(0.3 / (1 + 0.8 * dt) ** n, rel=1e-9)
    # off by default, and refused when negative
    assert np.all(ready({}).boats[0].params.damping_decay == 0.0)
    from boat_dynamics.physics.scenario import ScenarioError

    with pytest.raises(ScenarioError, match=r"damping\.decay"):
        ready({"boats": [{"damping": {"decay": [0, 0, 0, 0, 0, -1]}}]})


def _twin(**extra):
    """A 4 x 2 x 1 m box with two thrusters 0.6 m either side of the centre line, 100 N each,
    and linear damping only (surge 2000 N s/m, yaw 3000 N m s: time constants of about 2 s),
    in flat water."""
    thrusters = [{"name": "left", "max_thrust": 100.0, "position": [-2.0, 0.6, -0.3]},
                 {"name": "right", "max_thrust": 100.0, "position": [-2.0, -0.6, -0.3]}]
    boat = ready({"boats": [{**SEED_MODEL, "propulsion": thrusters, "rudder": {"model": "none"},
                             "damping": {"linear": [2000, 4000, 0, 0, 0, 3000],
                                         "quadratic": [0] * 6}, **extra}]}).boats[0]
    return boat


def _run(boat, inputs, seconds=40.0, dt=0.01):
    state = boat.initial
    for _ in range(int(seconds / dt)):
        state = step(boat.params, state, inputs, WaveField(), dt)
    return state


def test_equal_thrust_on_two_thrusters_runs_straight_at_the_damping_speed():
    boat = _twin()
    assert boat.thrusters == ("left", "right")
    state = _run(boat, BoatInputs(throttle=[0.8, 0.8]), seconds=30.0)
    # 160 N against 2000 N s/m: 0.08 m/s, on the x axis, heading unchanged
    assert state.velocity[0] == pytest.approx(0.08, rel=1e-3)
    assert abs(state.position[1]) < 1e-9 and abs(state.angular_velocity[2]) < 1e-12
    # and a single throttle drives both thrusters alike
    same = _run(boat, BoatInputs(throttle=0.8), seconds=30.0)
    np.testing.assert_array_equal(same.position, state.position)


def test_opposite_thrust_turns_on_the_spot_at_the_moment_balances_yaw_rate():
    boat = _twin()
    state = _run(boat, BoatInputs(throttle=[-1.0, 1.0]), seconds=30.0)
    # r x F: the right thruster (y = -0.6) pushing ahead and the left one astern give
    # N = 2 x 0.6 x 100 = 120 N m to port; against 3000 N m s: r = 0.04 rad/s
    assert state.angular_velocity[2] == pytest.approx(0.04, rel=1e-3)
    assert np.hypot(*state.velocity[:2]) < 0.02  # on the spot (the turn's small sway)
    assert state.throttle[:2].tolist() == [-1.0, 1.0]


def test_a_steerable_thruster_of_a_list_turns_with_its_own_angle():
    thrusters = [{"name": "outboard", "max_thrust": 200.0, "position": [-2.0, 0.0, -0.3],
                  "steerable": True, "max_angle_deg": 30.0}]
    boat = ready({"boats": [{"propulsion": thrusters}]}).boats[0]
    assert boat.params.thrusters[0].max_angle == pytest.approx(math.radians(30.0))
    turned = _run(boat, BoatInputs(throttle=1.0, thruster_angle=[0.3]), seconds=5.0)
    rudder = _run(boat, BoatInputs(throttle=1.0, rudder=0.3), seconds=5.0)
    assert turned.angular_velocity[2] > 0.01  # + angle: bow to port
    straight = _run(boat, BoatInputs(throttle=1.0, rudder=0.3, thruster_angle=[0.0]), 5.0)
    assert abs(straight.angular_velocity[2]) < abs(rudder.angular_velocity[2])


@pytest.mark.parametrize(("propulsion", "key", "fragment"), [
    ([], "boats[0].propulsion", "1 to 8 thrusters"),
    ([{"max_thrust": 10}], "boats[0].propulsion[0].name", "is required"),
    ([{"name": "a"}, {"name": "a"}], "boats[0].propulsion[1].name", "unique"),
    ([{"name": "a", "max_angle_deg": 20}], "boats[0].propulsion[0].max_angle_deg",
     "only for a steerable thruster"),
    ([{"name": "a", "max_thrust": -1}], "boats[0].propulsion[0].max_thrust", "(0, 1e+08] N"),
    ([{"name": f"t{i}"} for i in range(9)], "boats[0].propulsion", "1 to 8 thrusters"),
])
def test_a_bad_thruster_list_is_refused_naming_the_key(propulsion, key, fragment):
    from boat_dynamics.physics.scenario import parse_scenario

    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"propulsion": propulsion}]})
    assert err.value.key == key
    assert fragment in err.value.allowed
