"""Wind loads and the current on a boat: closed forms (Fossen 2021, sec. 10.1)."""

import math

import numpy as np
import pytest
from ready_scenarios import SEED_MODEL, ready

from boat_dynamics.physics.body.hull import BoxHull, box_mesh
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.core.boat import BoatInputs, evaluate_forces, step
from boat_dynamics.physics.force_models.wind import windage_of_hull
from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
from ocean_sim.physics.constants import AIR_DENSITY
from ocean_sim.physics.environment import Environment, Wind
from ocean_sim.physics.waves import WaveField

CX, CY, CN = 0.70, 0.825, 0.125


def test_a_box_windage_is_its_freeboard_times_its_beam_and_length():
    # 4 x 2 x 1 m box with its reference point 0.2 m above the water: 0.7 m of freeboard
    w = windage_of_hull(box_mesh(BoxHull(4.0, 2.0, 1.0)), 0.2, 4.0)
    assert (w.frontal_area, w.lateral_area) == pytest.approx((1.4, 2.8), rel=1e-12)
    assert w.centre == pytest.approx([0.0, 0.0, 0.15], abs=1e-12)  # mid-freeboard


def _boat(**extra):
    # the seed notes' model: the closed forms below hold without added mass
    return ready({"boats": [{**SEED_MODEL, "damping": {"linear": [2000, 2000, 0, 0, 0, 4000],
                                                       "quadratic": [0] * 6}, **extra}]}).boats[0]


@pytest.mark.parametrize(("direction_deg", "expected"), [
    # wind going toward +x (from astern): X = +q c_x A_F
    (0.0, lambda q, af, al, lo: (q * CX * af, 0.0, 0.0)),
    # toward +y (from starboard): Y = +q c_y A_L, no yaw moment
    (90.0, lambda q, af, al, lo: (0.0, q * CY * al, 0.0)),
    # toward -x (head wind): X = -q c_x A_F
    (180.0, lambda q, af, al, lo: (-q * CX * af, 0.0, 0.0)),
    # from 45 deg off the starboard bow (toward 135 deg): pushed aft and to port, and the bow
    # falls off to port, away from the wind (C_N = c_n sin 2 gamma, gamma = 45 deg in FLU)
    (135.0, lambda q, af, al, lo: (-q * CX * math.cos(math.radians(45)) * af,
                                    q * CY * math.sin(math.radians(45)) * al,
                                    q * CN * al * lo)),
])
def test_the_steady_wind_load_is_fossens_formula(direction_deg, expected):
    boat = _boat()
    w = boat.params.windage
    env = Environment(wind=Wind.make(8.0, math.radians(direction_deg)))
    f = evaluate_forces(boat.params, boat.initial, BoatInputs(), WaveField(), env).wind
    q = 0.5 * AIR_DENSITY * 8.0**2
    x, y, n = expected(q, w.frontal_area, w.lateral_area, w.length)
    assert (w.frontal_area, w.lateral_area) == pytest.approx((1.0, 2.0))  # half draft
    assert f.force == pytest.approx([x, y, 0.0], abs=1e-9)
    lever = w.centre - boat.params.center_of_mass  # the side force heels the boat
    assert f.torque[0] == pytest.approx(-lever[2] * y, abs=1e-9)
    assert f.torque[2] == pytest.approx(n + lever[0] * y, abs=1e-9)
    calm = evaluate_forces(boat.params, boat.initial, BoatInputs(), WaveField(),
                           Environment()).wind
    assert np.all(calm.force == 0.0)


def test_a_boat_drifts_before_the_wind_until_its_damping_balances_the_load():
    boat = _boat()
    env = Environment(wind=Wind.make(10.0, 0.0))
    state = boat.initial
    for _ in range(3000):
        state = step(boat.params, state, BoatInputs(), WaveField(), 0.01, env)
    # X = q c_x A_F with the relative wind (U - u): 2000 u = 0.5 rho (10 - u)^2 0.7 x 1.0
    u = state.velocity[0]
    assert 2000.0 * u == pytest.approx(0.5 * AIR_DENSITY * (10.0 - u) ** 2 * CX * 1.0,
                                       rel=1e-3)


def test_a_free_floating_boat_takes_the_currents_velocity():
    boat = _boat()
    env = Environment(current_speed=0.5, current_direction=math.radians(30.0))
    state = boat.initial
    for _ in range(3000):  # 30 s, time constants of about 2 s
        state = step(boat.params, state, BoatInputs(), WaveField(), 0.01, env)
    # world frame: the rudder's lift turns the boat a little while the current takes it
    world = rotation_matrix(state.orientation) @ state.velocity
    np.testing.assert_allclose(world, [0.5 * math.cos(math.radians(30.0)),
                                       0.5 * math.sin(math.radians(30.0)), 0.0], atol=1e-4)
    assert state.position[0] == pytest.approx(0.433 * 30.0, rel=0.1)


def test_environment_and_windage_keys_are_checked():
    sc = parse_scenario({"environment": {"current": {"speed": 0.3, "direction_deg": 90},
                                         "wind": {"speed": 7, "gusts": "norsok",
                                                  "components": 20}},
                         "boats": [{"windage": {"frontal_area": 3.0}}]})
    assert sc.environment.current == pytest.approx([0.0, 0.3, 0.0], abs=1e-12)
    assert sc.environment.wind.frequencies.shape == (20,)
    for data, key in [
        ({"environment": {"current": {"speed": -1}}}, "environment.current.speed"),
        ({"environment": {"wind": {"gusts": "harris"}}}, "environment.wind.gusts"),
        ({"environment": {"wind": {"components": 0}}}, "environment.wind.components"),
        ({"environment": {"tide": {}}}, "environment.tide"),
        ({"boats": [{"windage": {"coefficients": [0.7, 5, 0.1]}}]},
         "boats[0].windage.coefficients"),
        ({"boats": [{"windage": {"lateral_area": math.nan}}]}, "boats[0].windage.lateral_area"),
    ]:
        with pytest.raises(ScenarioError) as err:
            parse_scenario(data)
        assert err.value.key == key
    boat = ready({"boats": [{"windage": {"frontal_area": 3.0}}]}).boats[0]
    assert boat.params.windage.frontal_area == 3.0
    assert boat.params.windage.lateral_area == pytest.approx(2.0)  # from the hull
