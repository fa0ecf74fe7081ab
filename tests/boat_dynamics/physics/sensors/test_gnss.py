"""The GNSS model: WGS-84 conversion against closed forms; fix noise statistics; heading."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_from_euler
from boat_dynamics.physics.sensors import (
    Datum,
    GnssNoise,
    GnssSpec,
    enu_to_geodetic,
    geodetic_to_enu,
    gnss_start,
    measure_gnss,
    measure_heading,
    stream_key,
)

A, F = 6378137.0, 1 / 298.257223563  # WGS-84 (NIMA TR8350.2)
E2 = F * (2 - F)


def test_small_offsets_follow_the_ellipsoids_radii_of_curvature():
    # north by dn: dlat = dn / M, east by de: dlon = de / (N cos lat), with the meridian and
    # prime-vertical radii M = a (1 - e^2) / w^3, N = a / w, w = sqrt(1 - e^2 sin^2 lat)
    datum = Datum(math.radians(45.0), math.radians(-4.0), 0.0)
    w = math.sqrt(1 - E2 * math.sin(datum.latitude) ** 2)
    m, n = A * (1 - E2) / w**3, A / w
    lat, lon, alt = enu_to_geodetic(datum, np.array([10.0, 20.0, 0.0]))
    assert lat - datum.latitude == pytest.approx(20.0 / m, rel=1e-5)
    assert lon - datum.longitude == pytest.approx(10.0 / (n * math.cos(datum.latitude)),
                                                  rel=1e-5)
    assert alt == pytest.approx((10.0**2 / n + 20.0**2 / m) / 2, abs=1e-4)  # earth curvature


def test_geodetic_and_enu_convert_back_and_forth():
    datum = Datum(math.radians(-33.7), math.radians(150.7), 12.0)
    p = np.array([-1234.5, 678.9, 3.2])
    np.testing.assert_allclose(geodetic_to_enu(datum, *enu_to_geodetic(datum, p)), p,
                               atol=1e-6)


def _fixes(noise, n, rate=5.0, seed=11):
    spec = GnssSpec(rate_hz=rate, noise=noise)
    datum = Datum()
    key = stream_key(seed, 0, 1)
    state = gnss_start(spec, key)
    truth = np.array([100.0, -50.0, 1.0])
    errors, vel = [], []
    for _ in range(n):
        reading, state = measure_gnss(spec, key, state, datum, truth, np.array([1.0, 2, 0]))
        errors.append(geodetic_to_enu(datum, reading.latitude, reading.longitude,
                                      reading.altitude) - truth)
        vel.append(reading.velocity - [1.0, 2, 0])
    return np.array(errors), np.array(vel), reading


def test_a_fix_converts_back_to_the_true_position_within_the_configured_sigma():
    noise = GnssNoise(horizontal_sigma=1.2, vertical_sigma=2.5, bias_sigma=0.0,
                      bias_correlation_time=60.0, velocity_sigma=0.1)
    errors, vel, reading = _fixes(noise, 8000)
    sigma = np.array([1.2, 1.2, 2.5])
    np.testing.assert_allclose(errors.std(axis=0), sigma, rtol=0.05)
    assert np.all(np.abs(errors.mean(axis=0)) < 0.05 * sigma)
    np.testing.assert_allclose(vel.std(axis=0), 0.1, rtol=0.05)
    np.testing.assert_allclose(np.diag(reading.position_covariance), sigma**2)


def test_the_correlated_error_is_slow_and_of_the_configured_sigma():
    noise = GnssNoise(horizontal_sigma=0.0, vertical_sigma=0.0, bias_sigma=0.8,
                      bias_correlation_time=10.0, velocity_sigma=0.0)
    errors, _, reading = _fixes(noise, 20000, rate=1.0)
    np.testing.assert_allclose(errors.std(axis=0), [0.8, 0.8, 1.6], rtol=0.1)
    lag = 10  # one correlation time at 1 Hz
    corr = np.corrcoef(errors[:-lag, 0], errors[lag:, 0])[0, 1]
    assert corr == pytest.approx(math.exp(-1.0), abs=0.05)
    np.testing.assert_allclose(np.diag(reading.position_covariance), [0.64, 0.64, 2.56])


def test_the_same_seed_gives_the_same_fixes():
    a, _, _ = _fixes(GnssNoise(), 20, seed=5)
    b, _, _ = _fixes(GnssNoise(), 20, seed=5)
    np.testing.assert_array_equal(a, b)


def test_a_receiver_has_no_fix_in_its_outages_only():
    from boat_dynamics.physics.sensors import GnssSpec, has_fix

    spec = GnssSpec(outages=((1.0, 2.5), (10.0, math.inf)))
    assert [has_fix(spec, t) for t in (0.0, 0.99, 1.0, 2.0, 2.5, 9.99, 10.0, 1e6)] == [
        True, True, False, False, True, True, False, False]
    assert has_fix(GnssSpec(), 5.0)  # no outages: always a fix


def _dual(baseline, sigma_deg=0.0):
    return GnssSpec(noise=GnssNoise(heading_sigma=math.radians(sigma_deg)),
                    heading_baseline=None if baseline is None else np.array(baseline, float))


@pytest.mark.parametrize("yaw_deg", [-175.0, -60.0, 0.0, 33.0, 179.5])
@pytest.mark.parametrize("baseline", [[1.0, 0.0, 0.0], [-0.3, 0.8, 0.2], [0.0, -1.5, 0.0]])
def test_a_level_boat_s_baseline_gives_its_yaw_whatever_the_mounting(yaw_deg, baseline):
    # psi = atan2(w_y, w_x) - atan2(b_y, b_x), w = R b: the boat's yaw when level
    yaw = measure_heading(_dual(baseline), stream_key(0, "a", "g"), 3,
                          quat_from_euler(0.0, 0.0, math.radians(yaw_deg)))
    assert math.remainder(yaw - math.radians(yaw_deg), 2 * math.pi) == pytest.approx(0.0,
                                                                                    abs=1e-12)
    assert -math.pi <= yaw <= math.pi


def test_a_fore_and_aft_baseline_ignores_roll_and_a_tilted_oblique_one_turns():
    key = stream_key(0, "a", "g")
    q = quat_from_euler(0.4, 0.0, 1.0)
    assert measure_heading(_dual([1.0, 0.0, 0.0]), key, 0, q) == pytest.approx(1.0, abs=1e-12)
    # rolled by r then pitched by p (R = Ry(p) Rx(r)), a baseline (1, 1, 0) goes to
    # (cos p + sin p sin r, cos r, .): its heading turns from pi / 4 to atan2 of those
    r, p = 0.3, 0.2
    expected = (math.atan2(math.cos(r), math.cos(p) + math.sin(p) * math.sin(r))
                - math.pi / 4)
    assert measure_heading(_dual([1.0, 1.0, 0.0]), key, 0, quat_from_euler(r, p, 0.0)) == (
        pytest.approx(expected, abs=1e-12))


def test_no_baseline_or_one_too_steep_gives_no_heading():
    key, level = stream_key(0, "a", "g"), quat_from_euler(0.0, 0.0, 0.0)
    assert measure_heading(_dual(None), key, 0, level) is None
    assert measure_heading(_dual([0.05, 0.0, 1.0]), key, 0, level) is None  # 2.9 deg off vertical
    # a boat on its beam ends: an athwartship baseline points up
    assert measure_heading(_dual([0.0, 1.0, 0.0]), key, 0,
                           quat_from_euler(math.pi / 2, 0.0, 0.0)) is None


def test_heading_noise_has_its_sigma_and_leaves_the_fixes_as_they_were():
    sigma, n = 0.5, 20000
    spec, key = _dual([1.0, 0.0, 0.0], sigma), stream_key(4, "alpha", "gnss")
    q = quat_from_euler(0.0, 0.0, 0.7)
    errors = np.array([measure_heading(spec, key, k, q) - 0.7 for k in range(n)])
    s = math.radians(sigma)
    assert abs(errors.mean()) < 4 * s / math.sqrt(n)
    assert errors.std() == pytest.approx(s, rel=4 / math.sqrt(2 * n))
    # the fixes of a receiver with a heading are those of one without (draws apart)
    plain = GnssSpec()
    a, b = gnss_start(spec, key), gnss_start(plain, key)
    for _ in range(5):
        fa, a = measure_gnss(spec, key, a, Datum(), np.zeros(3), np.zeros(3))
        fb, b = measure_gnss(plain, key, b, Datum(), np.zeros(3), np.zeros(3))
        assert (fa.latitude, fa.longitude, fa.altitude) == (fb.latitude, fb.longitude,
                                                            fb.altitude)


def _jumps(spec, n):
    """(starts, fixes in a jump per jump, offsets (S, 2), durations (S,)) over ``n`` fixes."""
    from boat_dynamics.physics.sensors.gnss import GnssState, multipath_jump

    key = stream_key(5, "boat", "gnss")
    state = GnssState(1, np.zeros(3))
    offsets, durations, lengths = [], [], []
    for k in range(1, n + 1):
        jump, left = multipath_jump(spec, key, GnssState(k, state.bias, state.jump,
                                                         state.jump_left))
        if left > 0.0 and state.jump_left - 1.0 / spec.rate_hz <= 0.0:  # a new one
            offsets.append(jump)
            durations.append(left)
            lengths.append(0)
        if left > 0.0:
            lengths[-1] += 1
        state = GnssState(k + 1, state.bias, jump, left)
    return len(offsets), np.array(lengths[:-1]), np.array(offsets), np.array(durations)


def test_multipath_jumps_come_at_their_rate_last_their_duration_and_are_their_size():
    # 1 Hz fixes, 0.1 jump/s while none, 5 s each, 8 m: 30,000 fixes. Per fix a jump starts
    # with p = 1 - exp(-0.1) when none is under way, and covers ceil(D / 1 s) fixes, D
    # exponential of mean 5 s: E[fixes] = 1 / (1 - exp(-1/5)); between two, (1 - p) / p
    # fixes without. The count's variance is below a Poisson count's (the cycle's squared
    # coefficient of variation is 0.55): 4 sqrt(expected) is over 4 sigma.
    from boat_dynamics.physics.sensors.gnss import Multipath

    spec = GnssSpec(rate_hz=1.0, multipath=Multipath(rate_hz=0.1, sigma=8.0, duration=5.0))
    n = 30_000
    count, lengths, offsets, durations = _jumps(spec, n)
    p, covered = -math.expm1(-0.1), 1.0 / -math.expm1(-0.2)
    expected = n / (covered + (1 - p) / p)
    assert abs(count - expected) < 4 * math.sqrt(expected), (count, expected)
    # fixes a jump: geometric of variance q / (1 - q)^2, q = exp(-0.2)
    sd = math.sqrt(math.exp(-0.2)) / -math.expm1(-0.2)
    assert abs(lengths.mean() - covered) < 4 * sd / math.sqrt(len(lengths))
    assert abs(durations.mean() - 5.0) < 4 * 5.0 / math.sqrt(count)  # exponential
    # east and north N(0, 8^2): the sample sigma within 4 of its sigma / sqrt(2 n)
    assert abs(offsets.std() - 8.0) < 4 * 8.0 / math.sqrt(2 * offsets.size)
    assert np.all(np.abs(offsets.mean(axis=0)) < 4 * 8.0 / math.sqrt(count))
    # without multipath, or at rate 0: never
    assert _jumps(GnssSpec(rate_hz=1.0), 200)[0] == 0
    assert _jumps(GnssSpec(rate_hz=1.0, multipath=Multipath(rate_hz=0.0)), 200)[0] == 0


def test_a_jump_moves_the_fix_the_receiver_does_not_know_and_its_noise_is_the_same():
    from boat_dynamics.physics.sensors.gnss import Multipath

    datum, key = Datum(), stream_key(2, "boat", "gnss")
    plain = GnssSpec(rate_hz=5.0)
    jumpy = GnssSpec(rate_hz=5.0, multipath=Multipath(rate_hz=100.0, sigma=10.0,
                                                      duration=0.5))
    a, b = gnss_start(plain, key), gnss_start(jumpy, key)
    moved = []
    for _ in range(6):
        ra, a = measure_gnss(plain, key, a, datum, np.zeros(3), np.zeros(3))
        rb, b = measure_gnss(jumpy, key, b, datum, np.zeros(3), np.zeros(3))
        d = (geodetic_to_enu(datum, rb.latitude, rb.longitude, rb.altitude)
             - geodetic_to_enu(datum, ra.latitude, ra.longitude, ra.altitude))
        np.testing.assert_allclose(d, [*b.jump, 0.0], atol=1e-6)  # the jump, nothing else
        np.testing.assert_array_equal(rb.position_covariance, ra.position_covariance)
        np.testing.assert_array_equal(rb.velocity, ra.velocity)
        moved.append(b.jump.copy())
    assert np.linalg.norm(moved[0]) > 0.1  # p = 1 - exp(-20): it jumps at once
    # 0.5 s at 5 Hz: a jump covers ceil(D / 0.2 s) fixes, then another starts at once
    assert any(not np.array_equal(moved[k], moved[k + 1]) for k in range(5))


def test_a_scenarios_multipath_is_read_and_bad_values_refused():
    from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
    from boat_dynamics.physics.sensors.gnss import Multipath

    def gnss(**keys):
        return parse_scenario({"boats": [{"sensors": [{"type": "gnss", **keys}]}]}
                              ).boats[0].sensors[0]

    assert gnss().multipath is None
    assert gnss(multipath={"sigma": 20}).multipath == Multipath(0.01, 20.0, 10.0)
    for bad, key in (({"rate_hz": -1}, "rate_hz"), ({"sigma": "big"}, "sigma"),
                     ({"duration": 0}, "duration"), ({"size": 3}, "size")):
        with pytest.raises(ScenarioError) as err:
            gnss(multipath=bad)
        assert err.value.key == f"boats[0].sensors[0].multipath.{key}"
    with pytest.raises(ScenarioError, match="only for a gnss"):
        parse_scenario({"boats": [{"sensors": [{"type": "imu", "multipath": {}}]}]})
