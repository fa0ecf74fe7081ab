"""The GNSS model: WGS-84 conversion against closed forms; fix noise statistics."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.sensors import (
    Datum,
    GnssNoise,
    GnssSpec,
    enu_to_geodetic,
    geodetic_to_enu,
    gnss_start,
    measure_gnss,
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
