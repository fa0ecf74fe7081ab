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
