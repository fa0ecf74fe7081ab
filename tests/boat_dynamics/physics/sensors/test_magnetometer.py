"""The magnetometer: the Earth's field against closed forms, hard and soft iron, noise."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_from_euler
from boat_dynamics.physics.sensors import (
    EarthField,
    MagnetometerSpec,
    measure_magnetometer,
    stream_key,
)

QUIET = MagnetometerSpec(sigma=0.0)


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def test_the_field_in_enu_from_declination_inclination_and_intensity():
    # north X = F cos I cos D, east Y = F cos I sin D, down Z = F sin I; ENU = (Y, X, -Z)
    f = 50e-6
    np.testing.assert_allclose(EarthField(0.0, 0.0, f).enu(), [0.0, f, 0.0], atol=1e-20)
    np.testing.assert_allclose(EarthField(0.0, math.pi / 2, f).enu(), [0.0, 0.0, -f],
                               atol=1e-20)
    d, i = math.radians(-12.0), math.radians(-35.0)  # south of the magnetic equator: up
    b = EarthField(d, i, f).enu()
    np.testing.assert_allclose(b, [f * math.cos(i) * math.sin(d), f * math.cos(i) * math.cos(d),
                                   -f * math.sin(i)], rtol=1e-12)
    assert b[0] < 0.0 and b[2] > 0.0 and np.linalg.norm(b) == pytest.approx(f, rel=1e-12)
    # the default: WMM2025 at 45 N, 4 W for 2026.0, X 23,217 nT, Y 125 nT, Z 40,682 nT
    np.testing.assert_allclose(EarthField().enu() * 1e9, [125.0, 23217.0, -40682.0], atol=30)


@pytest.mark.parametrize("yaw_deg", [-170.0, -90.0, -30.0, 0.0, 45.0, 120.0, 179.0])
def test_a_level_boat_recovers_its_heading_from_the_field(yaw_deg):
    # psi = pi/2 - D - atan2(m_y, m_x) (yaw counter-clockwise from east, FLU body)
    earth = EarthField(math.radians(7.5), math.radians(62.0), 48e-6)
    reading = measure_magnetometer(QUIET, stream_key(0, "a", "m"), 0, earth,
                                   quat_from_euler(0.0, 0.0, math.radians(yaw_deg)))
    m = reading.field
    psi = math.pi / 2 - earth.declination - math.atan2(m[1], m[0])
    error = math.remainder(psi - math.radians(yaw_deg), 2 * math.pi)
    assert abs(error) < 1e-12
    # level: the vertical axis reads the field's vertical part, -F sin I (body z up)
    assert m[2] == pytest.approx(-48e-6 * math.sin(math.radians(62.0)), rel=1e-12)
    # a compass heading, clockwise from true north, is 90 deg - yaw: atan2(m_y, m_x) + D in
    # FLU axes (the textbook's atan2(-m_y, m_x) is in FRD axes, y to starboard)
    heading = math.degrees(math.atan2(m[1], m[0]) + earth.declination) % 360.0
    assert heading == pytest.approx((90.0 - yaw_deg) % 360.0, abs=1e-9)


def test_hard_and_soft_iron_are_applied_to_the_field_in_the_sensor_axes():
    earth = EarthField(math.radians(-3.0), math.radians(55.0), 49e-6)
    roll, pitch, yaw = 0.2, -0.15, 2.1
    hard = np.array([3e-6, -1.5e-6, 0.8e-6])
    soft = np.array([[1.05, 0.02, -0.01], [0.02, 0.97, 0.03], [-0.01, 0.03, 1.1]])
    spec = MagnetometerSpec(sigma=0.0, hard_iron=hard, soft_iron=soft)
    q = quat_from_euler(roll, pitch, yaw)
    reading = measure_magnetometer(spec, stream_key(0, "a", "m"), 5, earth, q)
    # body to world R = Rz(yaw) Ry(pitch) Rx(roll) (REP-103), so the body reads R^T b_w
    body = (_rz(yaw) @ _ry(pitch) @ _rx(roll)).T @ earth.enu()
    np.testing.assert_allclose(reading.field, soft @ body + hard, rtol=0, atol=1e-18)
    ideal = measure_magnetometer(QUIET, stream_key(0, "a", "m"), 5, earth, q).field
    np.testing.assert_allclose(ideal, body, rtol=0, atol=1e-18)
    # a calibration inverts them: W^-1 (m - h) is the field again
    np.testing.assert_allclose(np.linalg.solve(soft, reading.field - hard), body, atol=1e-18)


def test_white_noise_has_the_configured_sigma_zero_mean_and_no_correlation():
    sigma, n = 2e-7, 20000
    spec = MagnetometerSpec(sigma=sigma)
    key, q, earth = stream_key(11, "alpha", "mag"), quat_from_euler(0.1, 0.2, 0.3), EarthField()
    truth = measure_magnetometer(QUIET, key, 0, earth, q).field
    errors = np.array([measure_magnetometer(spec, key, k, earth, q).field - truth
                       for k in range(n)])
    # the mean within 4 standard errors (sigma / sqrt(n)); the covariance sigma^2 I: its
    # diagonal within 4 standard errors (sqrt(2 / n) relative: 4 %), its off-diagonal
    # correlations within 4 / sqrt(n) (0.028)
    assert np.all(np.abs(errors.mean(axis=0)) < 4 * sigma / math.sqrt(n))
    cov = np.cov(errors.T)
    np.testing.assert_allclose(np.diag(cov), sigma ** 2, rtol=4 * math.sqrt(2 / n))
    corr = np.corrcoef(errors.T)
    assert np.abs(corr[~np.eye(3, dtype=bool)]).max() < 4 / math.sqrt(n)
    reading = measure_magnetometer(spec, key, 0, earth, q)
    np.testing.assert_array_equal(reading.covariance, np.eye(3) * sigma ** 2)


def test_the_same_stream_and_sample_give_the_same_reading():
    spec, earth, q = MagnetometerSpec(), EarthField(), quat_from_euler(0.0, 0.0, 1.0)
    a = measure_magnetometer(spec, stream_key(1, "a", "m"), 7, earth, q).field
    np.testing.assert_array_equal(a, measure_magnetometer(spec, stream_key(1, "a", "m"), 7,
                                                          earth, q).field)
    assert not np.array_equal(a, measure_magnetometer(spec, stream_key(1, "a", "m"), 8, earth,
                                                      q).field)
    assert not np.array_equal(a, measure_magnetometer(spec, stream_key(2, "a", "m"), 7, earth,
                                                      q).field)
