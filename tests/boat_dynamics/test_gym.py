"""boat_dynamics.gym: Gymnasium environments over the physics core (no ROS)."""

import math
import runpy
import warnings
from pathlib import Path

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from boat_dynamics.gym import (
    ACTION_FIELDS,
    OBSERVATION_FIELDS,
    BoatEnv,
    BoatVectorEnv,
    InvalidValueError,
    Task,
)
from boat_dynamics.physics.scenario import parse_scenario

#: One default box (sample points: cheap) in a regular swell, and a second boat to pick.
SCENARIO = parse_scenario({
    "ocean": {"components": [{"amplitude": 0.3, "wavelength": 25.0, "direction_deg": 30.0,
                              "steepness": 0.5}]},
    "boats": [{"name": "a"}, {"name": "b", "initial_pose": {"position": [0, 20, 0]}}]})
TASK = Task(episode_time=1.0)
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "gym_waypoints.py"


def _rollout(env, seed, actions):
    obs, _ = env.reset(seed=seed)
    out = [obs]
    for a in actions:
        obs, reward, terminated, truncated, _ = env.step(a)
        out += [obs, np.atleast_1d(reward), np.atleast_1d(terminated | truncated)]
    return out


def test_the_boat_env_passes_gymnasiums_checker():
    env = BoatEnv(SCENARIO, task=TASK)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    # only the unbounded positions and velocities are remarked upon
    assert all("infinity" in str(w.message) for w in caught), [str(w.message) for w in caught]
    assert env.observation_space.shape == (len(OBSERVATION_FIELDS),)
    assert env.action_space.shape == (len(ACTION_FIELDS),)
    limit = SCENARIO.boats[0].params.rudder.max_angle
    assert env.action_space.high.tolist() == [1.0, limit]


def test_the_same_seed_gives_the_same_episode_to_the_last_bit():
    actions = [[1.0, 0.3]] * 5 + [[-0.5, -0.2]] * 5
    a = _rollout(BoatEnv(SCENARIO, task=TASK), 7, actions)
    b = _rollout(BoatEnv(SCENARIO, task=TASK), 7, actions)
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))
    c = _rollout(BoatEnv(SCENARIO, task=TASK), 8, actions)  # another waypoint
    assert not np.array_equal(a[0], c[0])
    # the boat got going (surge after 0.5 s at full throttle), and after 1 s the episode was
    # truncated
    assert a[1 + 3 * 4][6] > 0.1 and a[-1][0]


def test_an_env_reset_again_repeats_its_episode():
    env = BoatEnv(SCENARIO, boat="b", task=TASK)
    actions = [[0.8, 0.1]] * 4
    assert all(np.array_equal(x, y) for x, y in zip(
        _rollout(env, 3, actions), _rollout(env, 3, actions), strict=True))


def test_a_batch_reset_with_the_same_seed_repeats_to_the_last_bit():
    actions = np.array([[1.0, 0.2], [0.3, -0.5]])
    runs = []
    for _ in range(2):
        vec = BoatVectorEnv(SCENARIO, 2, boat="b", task=TASK)
        out = [vec.reset(seed=11)[0]]
        out += [vec.step(actions)[0] for _ in range(3)]
        runs.append(np.array(out))
    assert np.array_equal(runs[0], runs[1])


def test_many_boats_step_together_as_each_alone():
    waypoints = np.array([[30.0, 0.0], [0.0, -40.0], [-25.0, 25.0]])
    vec = BoatVectorEnv(SCENARIO, 3, task=TASK)
    obs, _ = vec.reset(seed=1, options={"waypoints": waypoints})
    assert obs.shape == (3, len(OBSERVATION_FIELDS))
    actions = np.array([[1.0, 0.0], [0.5, 0.4], [-1.0, -0.4]])
    for _ in range(5):
        obs, reward, _, _, info = vec.step(actions)
    for i in range(3):
        env = BoatEnv(SCENARIO, task=TASK)
        env.reset(seed=1, options={"waypoint": waypoints[i]})
        for _ in range(5):
            alone, r, *_ = env.step(actions[i])
        np.testing.assert_allclose(obs[i], alone, rtol=1e-12, atol=1e-12)
        assert reward[i] == pytest.approx(r, abs=1e-12)
    assert np.array_equal(info["waypoint"], waypoints)


def test_a_copy_that_arrives_ends_its_episode_and_restarts_next_step():
    vec = BoatVectorEnv(SCENARIO, 2, task=Task(episode_time=60.0, arrival_radius=3.0))
    start = SCENARIO.boats[0].initial.position[:2]
    obs, _ = vec.reset(seed=0, options={"waypoints": [start + [2.0, 0.0], start + [50.0, 0]]})
    obs, reward, terminated, truncated, info = vec.step(np.zeros((2, 2)))
    assert terminated.tolist() == [True, False] and not truncated.any()
    assert reward[0] == pytest.approx(10.0, abs=0.1)
    t = info["episode_time"][1]
    obs, reward, terminated, truncated, info = vec.step(np.zeros((2, 2)))
    # next-step autoreset: a new waypoint, reward 0, its episode's clock at 0
    assert reward[0] == 0.0 and not terminated.any()
    assert info["episode_time"].tolist() == [0.0, pytest.approx(t + 0.1)]
    assert not np.array_equal(info["waypoint"][0], start + [2.0, 0.0])
    assert np.isfinite(obs).all()


def test_out_of_range_actions_are_clamped_and_nan_is_refused():
    env = BoatEnv(SCENARIO, task=TASK)
    env.reset(seed=0)
    *_, info = env.step([5.0, -9.0])
    assert info["clamped"]
    clamped = env._fleet.intake.boats[0]
    assert clamped.throttle == 1.0 and clamped.rudder == -SCENARIO.boats[0].params.rudder.max_angle
    with pytest.raises(InvalidValueError, match=r"action\[1\] \(rudder\): nan is not allowed"):
        env.step([0.5, math.nan])
    vec = BoatVectorEnv(SCENARIO, 2, task=TASK)
    vec.reset(seed=0)
    with pytest.raises(InvalidValueError, match=r"action\[1\]\[0\] \(throttle\): inf"):
        vec.step([[0.0, 0.0], [math.inf, 0.0]])
    with pytest.raises(InvalidValueError, match=r"action: .* must be \(2, 2\) numbers"):
        vec.step([1.0, 0.0])
    with pytest.raises(InvalidValueError, match=r"action: 'fast' is not allowed: must be "
                                                r"\(2,\) numbers: throttle, rudder"):
        env.step("fast")


@pytest.mark.parametrize(("make", "match"), [
    (lambda: BoatEnv(SCENARIO, boat="c"), r"boat: 'c' is not allowed: must be one of \['a', 'b'\]"),
    (lambda: BoatEnv(SCENARIO, task=Task(control_period=0.015)),
     r"task.control_period: 0.015 .* whole number of the scenario's physics steps of 0.01 s"),
    (lambda: Task(waypoint_range=(5.0, 1.0)), r"task.waypoint_range"),
    (lambda: BoatVectorEnv(SCENARIO, 0), r"num_envs: 0 is not allowed"),
    (lambda: BoatEnv(SCENARIO).reset(options={"waypoint": [1.0]}), r"options.waypoint"),
])
def test_bad_settings_are_refused_by_name(make, match):
    with pytest.raises(InvalidValueError, match=match):
        make()


def test_the_example_helmsman_brings_every_boat_in(tmp_path, capsys):
    scenario = tmp_path / "swell.yaml"
    scenario.write_text("ocean:\n  components:\n    - {amplitude: 0.3, wavelength: 25.0, "
                        "direction_deg: 30.0, steepness: 0.5}\nboats:\n  - {name: a}\n")
    main = runpy.run_path(str(EXAMPLE))["main"]
    assert main([str(scenario), "--boats", "3", "--seed", "1"]) == 0
    assert capsys.readouterr().out.startswith("3 of 3 boats arrived")
