"""Tessendorf's FFT tile (ocean_sim/physics/fft.py) against the direct sum of its components."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ocean_sim.physics.fft import (
    PIERSON_MOSKOWITZ_PHILLIPS,
    TileSpec,
    build_tile,
    spectral_density,
    tile_amplitudes,
    tile_sea,
    tile_steepness,
)
from ocean_sim.physics.spectra import pierson_moskowitz_peak_period
from ocean_sim.physics.waves import InvalidSeaStateError, displace, sample_surface

_PHILLIPS = TileSpec(size=120.0, resolution=32, seed=4, wind_speed=7.0, direction=0.4,
                     choppiness=1.0)
_JONSWAP = TileSpec(size=150.0, resolution=16, seed=2, spectrum="jonswap",
                    significant_height=1.5, peak_period=7.0, spreading=4.0, direction=-1.0,
                    choppiness=0.9, depth=12.0)


def _rest_grid(spec: TileSpec) -> np.ndarray:
    x0 = np.arange(spec.resolution) * spec.size / spec.resolution
    gx, gy = np.meshgrid(x0, x0, indexing="ij")
    return np.stack([gx.ravel(), gy.ravel()], axis=1)


@pytest.mark.parametrize("spec", [_PHILLIPS, _JONSWAP], ids=["phillips", "jonswap"])
def test_the_fft_grid_is_the_direct_sum_of_the_tiles_components(spec):
    n, t = spec.resolution, 1234.5
    tile, sea = build_tile(spec, t), tile_sea(spec)
    positions = tile.positions.reshape(-1, 3)
    np.testing.assert_allclose(positions, displace(sea, _rest_grid(spec), t), rtol=0, atol=1e-9)
    # the query at the displaced points finds the grid's rest points, heights and normals
    s = sample_surface(sea, positions[:, :2], t)
    np.testing.assert_allclose(s.rest_xy, _rest_grid(spec), rtol=0, atol=1e-6)
    np.testing.assert_allclose(s.heights, positions[:, 2], rtol=0, atol=1e-6)
    np.testing.assert_allclose(s.normals, tile.normals.reshape(-1, 3), rtol=0, atol=1e-6)
    assert tile.jacobian.shape == (n, n) and tile.jacobian.min() > 0.0


def test_the_query_at_random_points_is_within_a_millimetre_of_the_direct_sum():
    sea, t = tile_sea(_PHILLIPS), 77.0
    xy = np.random.default_rng(8).uniform(-300.0, 300.0, (400, 2))
    s = sample_surface(sea, xy, t)
    direct = displace(sea, s.rest_xy, t)  # the components summed at the rest points found
    assert np.abs(direct[:, :2] - xy).max() < 1e-6
    assert np.abs(direct[:, 2] - s.heights).max() < 1e-3
    assert np.ptp(s.heights) > 0.5  # a sea, not a flat tile (H_s 1.05 m)


def test_choppy_displacement_is_the_gerstner_steepness_of_every_component():
    sea = tile_sea(_PHILLIPS)
    q = tile_steepness(_PHILLIPS, tile_amplitudes(_PHILLIPS))
    assert 0.0 < q < 1.0
    assert {c.steepness for c in sea.components} == {q}
    assert sea.steepness_sum == pytest.approx(1.0, rel=1e-12)  # choppiness 1: the budget
    flat = TileSpec(**{**_PHILLIPS.__dict__, "choppiness": 0.0})
    tile = build_tile(flat, 3.0)  # no choppiness: points move only up and down
    np.testing.assert_allclose(tile.positions[..., :2].reshape(-1, 2), _rest_grid(flat),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(tile.positions[..., 2], build_tile(_PHILLIPS, 3.0).positions[
        ..., 2], rtol=0, atol=1e-12)


def test_a_component_travels_toward_its_wavevector():
    sea = tile_sea(_JONSWAP)
    a = sea.arrays.a
    mean = np.angle(np.sum(a**2 * (sea.arrays.dx + 1j * sea.arrays.dy)))  # energy-weighted
    assert abs(math.remainder(mean - _JONSWAP.direction, math.tau)) < 0.3
    # the crest of the biggest wave moves by c t along its direction
    i = int(np.argmax(a))
    c = sea.arrays.omega[i] / sea.arrays.k[i]
    d = np.array([sea.arrays.dx[i], sea.arrays.dy[i]])
    theta0 = sea.arrays.phi[i]
    p = (-theta0 / sea.arrays.k[i] + c * 5.0) * d
    assert math.cos(float(p @ sea.arrays.kd[:, i]) - sea.arrays.omega[i] * 5.0 + theta0) == \
        pytest.approx(1.0, abs=1e-9)


def test_the_same_seed_gives_the_same_sea_and_another_seed_another():
    a, b = tile_amplitudes(_JONSWAP), tile_amplitudes(TileSpec(**_JONSWAP.__dict__))
    assert np.array_equal(a, b)
    other = tile_amplitudes(TileSpec(**{**_JONSWAP.__dict__, "seed": 3}))
    assert np.abs(other - a).max() > 0.1 * np.abs(a).max()


def test_the_tile_repeats_every_size():
    sea, t, size = tile_sea(_JONSWAP), 9.0, _JONSWAP.size
    xy = np.random.default_rng(1).uniform(0.0, size, (50, 2))
    here = sample_surface(sea, xy, t)
    there = sample_surface(sea, xy + [size, -2.0 * size], t)
    np.testing.assert_allclose(there.heights, here.heights, rtol=0, atol=1e-9)
    np.testing.assert_allclose(there.normals, here.normals, rtol=0, atol=1e-9)


def _variance(spec: TileSpec, k_max: float) -> float:
    """Integral of F over the wavevector plane on a polar grid, m^2."""
    k = np.linspace(1e-4, k_max, 2000)[:, None]
    theta = np.linspace(-math.pi, math.pi, 361)[None, :]
    f = spectral_density(spec, k * np.cos(theta), k * np.sin(theta)) * k
    return float(np.trapezoid(np.trapezoid(f, theta[0], axis=1), k[:, 0]))


def test_the_jonswap_spectrum_integrates_to_hs_squared_over_16():
    for depth in (math.inf, 15.0):
        spec = TileSpec(spectrum="jonswap", significant_height=2.0, peak_period=8.0,
                        spreading=6.0, depth=depth)
        assert _variance(spec, 3.0) == pytest.approx(2.0**2 / 16.0, rel=0.005)


def test_the_phillips_spectrum_is_the_fully_developed_sea_of_its_wind():
    u, g = 10.0, 9.81
    spec = TileSpec(wind_speed=u, phillips_constant=PIERSON_MOSKOWITZ_PHILLIPS)
    hs = 0.21 * u**2 / g  # Pierson & Moskowitz (1964)
    # below k_max: pi A L_w^2 / 2 exp(-1 / (k_max L_w)^2), 99.0 % at k_max = 10 / L_w
    assert _variance(spec, 10.0 * g / u**2) == pytest.approx(hs**2 / 16.0 * math.exp(-0.01),
                                                             rel=0.002)
    assert pierson_moskowitz_peak_period(hs, g) > 0.0


def test_the_tiles_variance_is_the_spectrums_on_average():
    # <|h0|^2> = P(k): over seeds, the tile's variance sum a^2 / 2 (= its grid's mean h^2,
    # Parseval) is the lattice sum of F (2 pi / L)^2; one seed's scatters by 18 % (400 seeds),
    # the mean of 32 by 3 %
    spec = TileSpec(size=400.0, resolution=32, spectrum="jonswap", significant_height=2.0,
                    peak_period=8.0)
    dk = 2.0 * math.pi / spec.size
    k1 = dk * np.fft.fftfreq(spec.resolution, 1.0 / spec.resolution)
    f = spectral_density(spec, *np.meshgrid(k1, k1, indexing="ij"))
    f[spec.resolution // 2, :] = f[:, spec.resolution // 2] = 0.0  # no Nyquist waves
    expected = float(f.sum()) * dk**2
    # a lattice of 4 steps to the peak, cut at 2 peak wavenumbers: 4 % under H_s^2 / 16
    assert expected == pytest.approx(2.0**2 / 16.0, rel=0.1)
    seen = [np.mean(build_tile(TileSpec(**{**spec.__dict__, "seed": s}), 0.0)
                    .positions[..., 2] ** 2) for s in range(32)]
    assert np.mean(seen) == pytest.approx(expected, rel=0.1)


@pytest.mark.parametrize(("name", "value"), [
    ("resolution", 7), ("resolution", 2), ("resolution", 66), ("resolution", 32.0),
    ("spectrum", "pm"), ("seed", -1), ("size", 0.0), ("choppiness", 1.5),
    ("wind_speed", math.nan), ("spreading", -1.0), ("depth", 0.0)])
def test_a_bad_tile_is_refused_naming_the_key(name, value):
    with pytest.raises(InvalidSeaStateError, match=f"fft.{name} = "):
        TileSpec(**{name: value})
