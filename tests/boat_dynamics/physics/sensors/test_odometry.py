"""The noisy odometry: white noise of the configured sigmas, covariances filled."""

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_to_euler
from boat_dynamics.physics.sensors import OdometryNoise, OdometrySpec, measure_odometry, stream_key


def test_noisy_odometry_has_the_configured_spread_and_covariance():
    spec = OdometrySpec(noise=OdometryNoise(0.4, 0.02, 0.1, 0.01))
    key = stream_key(9, "boat", "odometry")
    truth = (np.array([1.0, 2.0, 0.0]), np.array([0.0, 0.0, 0.0, 1.0]), np.array([1.5, 0, 0]),
             np.zeros(3))
    rows = []
    for k in range(10000):
        r = measure_odometry(spec, key, k, *truth)
        rows.append(np.concatenate([r.position, quat_to_euler(r.orientation), r.velocity,
                                    r.angular_velocity]))
    rows = np.array(rows)
    sigma = np.repeat([0.4, 0.02, 0.1, 0.01], 3)
    np.testing.assert_allclose(rows.std(axis=0), sigma, rtol=0.05)
    expected = np.concatenate([truth[0], np.zeros(3), truth[2], truth[3]])
    assert np.all(np.abs(rows.mean(axis=0) - expected) < 0.05 * sigma)
    assert np.diag(r.pose_covariance) == pytest.approx([0.16] * 3 + [4e-4] * 3)
    assert np.diag(r.twist_covariance) == pytest.approx([0.01] * 3 + [1e-4] * 3)
    again = measure_odometry(spec, key, 9999, *truth)
    np.testing.assert_array_equal(again.position, r.position)


def _reckon(spec, seed, true_v=(0.0, 0.0, 0.0), true_w=(0.0, 0.0, 0.0), n=50):
    from boat_dynamics.physics.sensors import DeadReckoning, dead_reckon

    key, state, reading = stream_key(seed, "boat", spec.name), DeadReckoning(), None
    for _ in range(n + 1):  # the first reading starts it; then n intervals
        reading, state = dead_reckon(spec, key, state, np.array([3.0, -2.0, 0.0]),
                                     np.array([0.0, 0.0, 0.0, 1.0]), np.array(true_v),
                                     np.array(true_w))
    return reading, state


def test_a_drifting_odometry_walks_away_as_sigma_v_dt_sqrt_n():
    # At rest, heading held (no angular noise): after n intervals each horizontal coordinate
    # is off by sigma_v dt sqrt(n), 1 sigma; its covariance says so. 400 streams, n = 50:
    # the variance within 15 % (chi-square, 400 samples: 1 sigma 7 %).
    spec = OdometrySpec(rate_hz=10.0, drift=True,
                        noise=OdometryNoise(velocity_sigma=0.1, angular_velocity_sigma=0.0))
    errors = np.array([_reckon(spec, seed)[0].position - [3.0, -2.0, 0.0]
                       for seed in range(400)])
    expected = 50 * (0.1 * 0.1) ** 2
    assert errors[:, :2].var(axis=0) == pytest.approx([expected, expected], rel=0.15)
    reading, state = _reckon(spec, 0)
    assert state.sample == 51
    np.testing.assert_allclose(np.diag(reading.pose_covariance)[:3], expected)


def test_a_drifting_odometry_follows_the_motion_without_noise():
    # 2 m/s ahead while turning at 0.1 rad/s, noiseless: a circle of radius 20 m, exactly as
    # the integration of the same steps (10 Hz over 5 s: 0.5 rad of heading).
    spec = OdometrySpec(rate_hz=10.0, drift=True,
                        noise=OdometryNoise(velocity_sigma=0.0, angular_velocity_sigma=0.0))
    reading, _ = _reckon(spec, 0, (2.0, 0.0, 0.0), (0.0, 0.0, 0.1))
    yaw = quat_to_euler(reading.orientation)[2]
    assert yaw == pytest.approx(0.5, abs=1e-12)
    # x' = x + R(yaw_k) v dt with the heading after each step: a sum of chords
    steps = np.arange(50)
    x = 3.0 + np.sum(2.0 * 0.1 * np.cos(0.01 * steps))
    y = -2.0 + np.sum(2.0 * 0.1 * np.sin(0.01 * steps))
    np.testing.assert_allclose(reading.position[:2], [x, y], atol=1e-12)
