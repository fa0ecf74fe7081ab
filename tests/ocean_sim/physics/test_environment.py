"""The current and the wind of the environment: velocities and the NORSOK gusts."""

import math

import numpy as np
import pytest

from ocean_sim.physics.environment import (
    MAX_CURRENT_SPEED,
    MAX_GUST_COMPONENTS,
    MAX_WIND_SPEED,
    NORSOK_RANGE,
    Environment,
    InvalidEnvironmentError,
    Wind,
    norsok_spectrum,
)


def test_current_and_mean_wind_point_where_they_go():
    env = Environment(0.5, math.radians(90.0), Wind.make(10.0, math.radians(180.0)))
    np.testing.assert_allclose(env.current, [0.0, 0.5, 0.0], atol=1e-15)
    np.testing.assert_allclose(env.wind.velocity(12.3), [-10.0, 0.0, 0.0], atol=1e-12)
    assert Environment().is_calm and not env.is_calm


def test_norsok_spectrum_closed_form_values():
    # NORSOK N-003 (2007) eq. 6.4 at 10 m: S(f) = 320 (U/10)^2 / (1 + x^n)^(5/3n),
    # x = 172 f (U/10)^-0.75; at U = 10 m/s and f = 0.01 Hz: x = 1.72
    n = 0.468
    assert norsok_spectrum(np.array([0.01]), 10.0)[0] == pytest.approx(
        320.0 / (1 + 1.72**n) ** (5 / (3 * n)), rel=1e-12)
    assert norsok_spectrum(np.array([0.01]), 20.0)[0] > norsok_spectrum(np.array([0.01]),
                                                                         10.0)[0]


def test_gusts_have_the_spectrums_variance_and_the_mean_speed():
    # u(t) = sum sqrt(2 S df) cos(...): over a long record its mean is U and its variance the
    # spectrum's integral over the NORSOK range (trapezoid on a fine log grid)
    wind = Wind.make(12.0, 0.3, "norsok", components=200, seed=4)
    t = np.arange(0.0, 60_000.0, 0.5)
    u = wind.speed + np.cos(np.outer(t, wind.frequencies) + wind.phases) @ wind.amplitudes
    f = np.geomspace(*NORSOK_RANGE, 20001)
    variance = np.trapezoid(norsok_spectrum(f, 12.0), f)
    assert u.mean() == pytest.approx(12.0, abs=0.05 * math.sqrt(variance))
    assert u.var() == pytest.approx(variance, rel=0.05)
    assert math.sqrt(variance) / 12.0 == pytest.approx(0.12, abs=0.04)  # ~12 % turbulence
    same = Wind.make(12.0, 0.3, "norsok", components=200, seed=4)
    assert same.speed_at(123.4) == wind.speed_at(123.4)
    assert Wind.make(12.0, 0.3, "norsok", components=200, seed=5).speed_at(123.4) != (
        wind.speed_at(123.4))
    assert Wind.make(12.0, 0.3).speed_at(123.4) == 12.0  # no gusts


@pytest.mark.parametrize(("make", "key"), [
    (lambda: Wind.make(10.0, 0.0, "norsok", 4_000_000_000), "wind.gust_components"),
    (lambda: Wind.make(10.0, 0.0, "norsok", 0), "wind.gust_components"),
    (lambda: Wind.make(10.0, 0.0, "norsok", True), "wind.gust_components"),
    (lambda: Wind.make(10.0, 0.0, "harris"), "wind.gusts"),
    (lambda: Wind.make(101.0, 0.0), "wind.speed"),
    (lambda: Wind.make(math.nan, 0.0), "wind.speed"),
    (lambda: Wind.make(5.0, math.inf), "wind.direction"),
    (lambda: Environment(20.5, 0.0), "current.speed"),
    (lambda: Environment(-1.0, 0.0), "current.speed"),
    (lambda: Environment(1.0, math.nan), "current.direction"),
])
def test_an_environment_out_of_its_bounds_is_refused_before_anything_is_drawn(make, key):
    # the bounds of the scenario and of the ocean node's parameters hold for every reader; a
    # /ocean/environment of 4e9 gust components once allocated 29.8 GiB and killed the node
    with pytest.raises(InvalidEnvironmentError) as err:
        make()
    assert err.value.key == key


def test_the_bounds_themselves_are_allowed():
    wind = Wind.make(MAX_WIND_SPEED, 0.0, "norsok", MAX_GUST_COMPONENTS)
    assert wind.frequencies.size == MAX_GUST_COMPONENTS
    assert Environment(MAX_CURRENT_SPEED, 0.0, wind).current_speed == 20.0
