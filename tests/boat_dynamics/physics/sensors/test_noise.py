"""Dropouts drawn from a sensor's noise stream, apart from its readings' noise."""

import math

import numpy as np

from boat_dynamics.physics.sensors import dropped, stream_key


def test_a_dropout_loses_its_share_of_readings_the_same_ones_every_run():
    key = stream_key(5, "alpha", "imu")
    lost = np.array([dropped(key, k, 0.2) for k in range(10_000)])
    assert abs(lost.mean() - 0.2) < 3 * math.sqrt(0.2 * 0.8 / 10_000)  # binomial, 3 sigma
    assert np.array_equal(lost, [dropped(key, k, 0.2) for k in range(10_000)])
    # runs of losses as independent draws make them (no correlation between neighbours)
    assert abs(np.corrcoef(lost[:-1], lost[1:])[0, 1]) < 3 / math.sqrt(10_000)
    assert not any(dropped(key, k, 0.0) for k in range(1000))
    assert all(dropped(key, k, 1.0) for k in range(1000))
    # another sensor loses other readings
    other = np.array([dropped(stream_key(5, "alpha", "gnss"), k, 0.2) for k in range(10_000)])
    assert (lost != other).mean() > 0.2

