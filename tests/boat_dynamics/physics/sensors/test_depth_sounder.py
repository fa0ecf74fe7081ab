"""The depth sounder: slant ranges against closed forms, REP-117's limits, noise statistics."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_from_euler, rotation_matrix
from boat_dynamics.physics.sensors import (
    DepthSounderSpec,
    measure_depth,
    slant_range,
    stream_key,
)

LEVEL = quat_from_euler(0.0, 0.0, 0.0)
QUIET = DepthSounderSpec(range_sigma=0.0)


def test_a_level_boat_reads_the_depth_less_the_transducer_s_draft():
    # the reference point 0.1 m above the mean level, the transducer 0.5 m below it: its draft
    # is 0.4 m, and it reads 20 - 0.4 m whatever the yaw
    for yaw in (0.0, 1.0, -2.5):
        q = quat_from_euler(0.0, 0.0, yaw)
        transducer = np.array([3.0, -1.0, 0.1]) + rotation_matrix(q) @ [0.8, 0.2, -0.5]
        assert slant_range(transducer, q, 20.0) == pytest.approx(19.6, abs=1e-12)
        reading = measure_depth(QUIET, stream_key(0, "a", "s"), 0, transducer, q, 20.0)
        assert reading.range == pytest.approx(19.6, abs=1e-12) and reading.variance == 0.0


@pytest.mark.parametrize("roll, pitch", [(0.2, 0.0), (0.0, -0.3), (0.25, 0.15), (-0.4, 0.3)])
def test_a_tilted_beam_reads_the_depth_over_the_cosine_of_the_tilt(roll, pitch):
    # body -z in the world: (-sin p cos r ... , -cos r cos p): cos(tilt) = cos(roll) cos(pitch)
    q = quat_from_euler(roll, pitch, 0.7)
    tilt = math.acos(math.cos(roll) * math.cos(pitch))
    assert slant_range(np.zeros(3), q, 15.0) == pytest.approx(15.0 / math.cos(tilt), rel=1e-12)
    # from 0.3 m below the mean level: (h - 0.3) / cos(tilt)
    assert slant_range(np.array([0.0, 0.0, -0.3]), q, 15.0) == pytest.approx(
        14.7 / math.cos(tilt), rel=1e-12)


def test_no_echo_reads_plus_inf_and_a_floor_too_near_minus_inf():
    key = stream_key(0, "a", "s")
    # deep water; a beam at or above the horizontal (rolled 90 deg, capsized)
    assert measure_depth(QUIET, key, 0, np.zeros(3), LEVEL, math.inf).range == math.inf
    assert slant_range(np.zeros(3), quat_from_euler(math.pi / 2 + 1e-9, 0, 0), 10.0) == math.inf
    assert measure_depth(QUIET, key, 0, np.zeros(3), quat_from_euler(math.pi / 2, 0, 0),
                         10.0).range == math.inf  # grazing: 1e17 m, beyond max_range
    assert slant_range(np.zeros(3), quat_from_euler(math.pi, 0, 0), 10.0) == math.inf
    # beyond max_range; nearer than min_range (and a transducer in the floor)
    spec = DepthSounderSpec(range_sigma=0.0, min_range=0.5, max_range=50.0)
    assert measure_depth(spec, key, 0, np.zeros(3), LEVEL, 50.5).range == math.inf
    assert measure_depth(spec, key, 0, np.zeros(3), LEVEL, 49.5).range == pytest.approx(49.5)
    assert measure_depth(spec, key, 0, np.zeros(3), LEVEL, 0.4).range == -math.inf
    assert measure_depth(spec, key, 0, np.array([0, 0, -3.0]), LEVEL, 2.0).range == -math.inf


def test_white_noise_has_the_configured_sigma_and_zero_mean():
    sigma, n = 0.08, 20000
    spec = DepthSounderSpec(range_sigma=sigma)
    key, q = stream_key(5, "alpha", "sounder"), quat_from_euler(0.1, -0.05, 0.0)
    truth = slant_range(np.zeros(3), q, 30.0)
    errors = np.array([measure_depth(spec, key, k, np.zeros(3), q, 30.0).range - truth
                       for k in range(n)])
    # mean within 4 standard errors, the spread within 4 standard errors of sigma (2.8 %)
    assert abs(errors.mean()) < 4 * sigma / math.sqrt(n)
    assert errors.std() == pytest.approx(sigma, rel=4 / math.sqrt(2 * n))
    assert measure_depth(spec, key, 0, np.zeros(3), q, 30.0).variance == pytest.approx(sigma**2)
    # reading k of a stream is the same whenever it is drawn
    assert measure_depth(spec, key, 17, np.zeros(3), q, 30.0).range == errors[17] + truth


def _beach(slope: float):
    """A shore east of x = 40 (a square 40..140 x -50..50), its floor rising at ``slope``."""
    from boat_dynamics.physics.world.obstacles import Prism, World, floor_depth

    world = World((Prism.make("beach", [[40, -50], [140, -50], [140, 50], [40, 50]], 2.0,
                              slope),))
    return lambda xy: float(floor_depth(world, np.asarray(xy)[None, :], 30.0)[0])


@pytest.mark.parametrize("roll, pitch, yaw", [(0.0, 0.0, 0.0), (0.2, 0.0, 0.0),
                                              (0.0, -0.25, 0.0), (0.15, 0.2, 1.2)])
def test_over_a_shelving_shore_the_beam_meets_the_sloping_floor(roll, pitch, yaw):
    # the floor z = -s (40 - x) west of the shore: the beam p + r d meets it at
    # r = (p_z + s (40 - p_x)) / (s d_x - d_z) (closed form for the plane)
    s, p = 0.1, np.array([20.0, 3.0, -0.4])
    q = quat_from_euler(roll, pitch, yaw)
    d = -rotation_matrix(q)[:, 2]
    expected = (p[2] + s * (40.0 - p[0])) / (s * d[0] - d[2])
    assert slant_range(p, q, 30.0, _beach(s)) == pytest.approx(expected, abs=1e-8)
    # offshore, where the slope reaches the ocean's 30 m: the level floor
    far = np.array([-500.0, 0.0, -0.4])
    assert slant_range(far, q, 30.0, _beach(s)) == pytest.approx(slant_range(far, q, 30.0))


def test_on_the_beach_it_reads_no_water_and_a_flat_floor_needs_no_search():
    q = quat_from_euler(0.0, 0.0, 0.0)
    assert slant_range(np.array([45.0, 0.0, -0.4]), q, 30.0, _beach(0.1)) == 0.0
    # 1 m off: 0.1 m of water under a transducer 0.4 m down: aground, 0
    assert slant_range(np.array([39.0, 0.0, -0.4]), q, 30.0, _beach(0.1)) == 0.0
    assert slant_range(np.array([30.0, 0.0, -0.4]), q, 30.0, _beach(0.1)) == pytest.approx(0.6)
