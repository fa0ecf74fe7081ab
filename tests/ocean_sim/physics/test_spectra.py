"""Generated sea states: H_s, seeds, spreading, Beaufort presets, refusals."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ocean_sim.physics.spectra import (
    BEAUFORT_SIGNIFICANT_HEIGHT,
    SpectrumSpec,
    beaufort_sea,
    generate_sea,
    jonswap,
    pierson_moskowitz_peak_period,
    wavenumber,
)
from ocean_sim.physics.waves import InvalidSeaStateError, angular_frequency


def hs_of(sea):
    """4 sqrt(m0), m0 = sum a^2 / 2."""
    return 4.0 * math.sqrt(float(np.sum(sea.arrays.a**2)) / 2.0)


@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from(["jonswap", "pierson_moskowitz"]), hs=st.floats(0.1, 15.0),
       tp=st.floats(2.0, 20.0), n=st.integers(4, 128), gamma=st.floats(1.0, 7.0),
       depth=st.one_of(st.just(math.inf), st.floats(5.0, 200.0)))
def test_significant_height_is_recovered_within_5_percent(kind, hs, tp, n, gamma, depth):
    sea = generate_sea(SpectrumSpec(kind, hs, tp, 0.0, 10.0, n, gamma), seed=1, depth=depth)
    assert hs_of(sea) == pytest.approx(hs, rel=0.05)
    assert len(sea.components) == n
    assert sea.steepness_sum <= 0.5 + 1e-9  # the steepness budget


def test_continuous_spectrum_integrates_to_hs():
    w = np.linspace(0.01, 30.0, 200_000)
    for gamma in (1.0, 3.3):
        m0 = np.trapezoid(jonswap(w, 2.5, 9.0, gamma), w)
        assert 4 * math.sqrt(m0) == pytest.approx(2.5, rel=0.02)  # DNV's A_gamma is approximate


def test_peak_of_the_spectrum_is_at_the_peak_period():
    w = np.linspace(0.2, 3.0, 100_000)
    s = jonswap(w, 2.0, 8.0, 3.3)
    assert w[np.argmax(s)] == pytest.approx(2 * math.pi / 8.0, rel=1e-3)


@pytest.mark.parametrize("depth", [math.inf, 100.0, 10.0, 2.0])
def test_wavenumber_inverts_the_dispersion_relation(depth):
    omega = np.linspace(0.2, 5.0, 50)
    k = wavenumber(omega, 9.81, depth)
    assert np.allclose(angular_frequency(k, 9.81, depth), omega, rtol=1e-12)


def test_same_seed_same_sea_different_seed_different_phases():
    spec = SpectrumSpec("jonswap", 2.0, 8.0, 0.5, 10.0, 24)
    a, b, c = generate_sea(spec, seed=7), generate_sea(spec, seed=7), generate_sea(spec, seed=8)
    assert a == b
    pa, pc = np.array([x.phase for x in a.components]), np.array([x.phase for x in c.components])
    assert np.all(pa != pc)
    assert np.array_equal(a.arrays.a, c.arrays.a)  # the spectrum, not the seed, sets amplitudes


def test_spreading_centres_on_the_mean_direction_and_narrows_with_s():
    def spread(s):
        sea = generate_sea(SpectrumSpec("jonswap", 2.0, 8.0, 1.0, s, 1000), seed=2)
        d = np.array([x.direction for x in sea.components])
        mean = math.atan2(np.sin(d).mean(), np.cos(d).mean())
        return mean, np.sqrt(np.mean(np.remainder(d - 1.0 + np.pi, 2 * np.pi) - np.pi) ** 2)

    mean, _ = spread(10.0)
    assert mean == pytest.approx(1.0, abs=0.05)
    # circular spread of cos-2s ~ sqrt(2 / (s + 1)) rad for large s
    for s in (5.0, 20.0):
        d = np.array([x.direction for x in generate_sea(
            SpectrumSpec("jonswap", 2.0, 8.0, 1.0, s, 1000), seed=2).components])
        rms = math.sqrt(np.mean((d - 1.0) ** 2))
        assert rms == pytest.approx(math.sqrt(2.0 / (s + 1.0)), rel=0.15)
    long_crested = generate_sea(SpectrumSpec("jonswap", 2.0, 8.0, 1.0, None, 10), seed=2)
    assert {x.direction for x in long_crested.components} == {1.0}


def test_beaufort_presets():
    assert len(BEAUFORT_SIGNIFICANT_HEIGHT) == 13
    assert list(BEAUFORT_SIGNIFICANT_HEIGHT) == sorted(BEAUFORT_SIGNIFICANT_HEIGHT)
    assert beaufort_sea(0).is_flat
    for force in (3, 6, 9, 12):
        sea = beaufort_sea(force, components=64)
        assert hs_of(sea) == pytest.approx(BEAUFORT_SIGNIFICANT_HEIGHT[force], rel=0.05)
    # fully developed sea: T_p = 2 pi / 0.877 sqrt(H_s / (0.21 g)); about 8.7 s at H_s = 3 m
    assert pierson_moskowitz_peak_period(3.0) == pytest.approx(8.65, abs=0.01)
    with pytest.raises(InvalidSeaStateError, match=r"spectrum.beaufort = 13"):
        beaufort_sea(13)


@pytest.mark.parametrize(
    ("spec", "key"),
    [
        (SpectrumSpec(type="phillips"), "spectrum.type"),
        (SpectrumSpec(significant_height=math.nan), "spectrum.significant_height"),
        (SpectrumSpec(peak_period=0.0), "spectrum.peak_period"),
        (SpectrumSpec(gamma=0.5), "spectrum.gamma"),
        (SpectrumSpec(spreading=-1.0), "spectrum.spreading"),
        (SpectrumSpec(components=0), "spectrum.components"),
        (SpectrumSpec(steepness=1.5), "spectrum.steepness"),
    ],
)
def test_refused_spectra_name_the_key(spec, key):
    with pytest.raises(InvalidSeaStateError) as info:
        generate_sea(spec)
    assert info.value.key == key
