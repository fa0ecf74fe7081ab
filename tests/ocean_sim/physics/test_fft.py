"""Tessendorf's FFT tile (ocean_sim/physics/fft.py) against the direct sum of its components."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ocean_sim.physics.fft import (
    MAX_GRID_POINTS,
    PIERSON_MOSKOWITZ_PHILLIPS,
    TileSpec,
    build_tile,
    grid_points,
    grid_surface,
    lattice,
    spectral_density,
    tile_amplitudes,
    tile_sea,
    tile_steepness,
)
from ocean_sim.physics.spectra import pierson_moskowitz_peak_period
from ocean_sim.physics.waves import (
    InvalidSeaStateError,
    TileGrid,
    WaveComponent,
    WaveField,
    displace,
    sample_surface,
)

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
    ("wind_speed", math.nan), ("spreading", -1.0), ("depth", 0.0),
    ("suppression_length", -0.5), ("suppression_length", 201.0),
    ("suppression_length", math.nan)])
def test_a_bad_tile_is_refused_naming_the_key(name, value):
    with pytest.raises(InvalidSeaStateError, match=f"fft.{name} = "):
        TileSpec(**{name: value})


@pytest.mark.parametrize("m", [32, 75, 5], ids=["the tile's grid", "finer", "coarser"])
def test_the_grid_surface_is_the_direct_sum_at_its_nodes_tiled_over_any_area(m):
    # JONSWAP, depth 12 m, choppiness 0.9: every field (height, displacement, slopes) counts;
    # at M < N the waves alias onto the nodes, and the nodes are still exact
    sea, t, size = tile_sea(_PHILLIPS), 321.0, _PHILLIPS.size
    cells = np.stack(np.meshgrid(np.arange(-70, 90, 3), np.arange(-3 * m, 4 * m, 7),
                                 indexing="ij"), -1).reshape(-1, 2)
    positions, normals = grid_surface(sea, t, cells, m)
    rest = cells * (size / m)
    np.testing.assert_allclose(positions, displace(sea, rest, t), rtol=0, atol=1e-9)
    s = sample_surface(sea, positions[:, :2], t)  # the query finds the nodes again
    np.testing.assert_allclose(s.rest_xy, rest, rtol=0, atol=1e-6)
    assert np.abs(s.heights - positions[:, 2]).max() < 1e-3
    np.testing.assert_allclose(s.normals, normals, rtol=0, atol=1e-6)
    shifted, _ = grid_surface(sea, t, cells + [m, -2 * m], m, normals=False)  # periodic
    np.testing.assert_allclose(shifted, positions + [size, -2 * size, 0.0], rtol=0, atol=1e-9)


def test_the_grid_surface_of_a_tile_is_its_build_tile():
    spec, t = _JONSWAP, 55.0
    cells = np.stack(np.meshgrid(np.arange(16), np.arange(16), indexing="ij"), -1)
    positions, normals = grid_surface(tile_sea(spec), t, cells.reshape(-1, 2), 16)
    tile = build_tile(spec, t)
    np.testing.assert_allclose(positions, tile.positions.reshape(-1, 3), rtol=0, atol=1e-9)
    np.testing.assert_allclose(normals, tile.normals.reshape(-1, 3), rtol=0, atol=1e-12)


def test_the_grid_is_as_fine_as_asked_within_its_budget():
    assert grid_points(TileGrid(200.0, 32), 1.0) == 200  # spacing 1 m
    assert grid_points(TileGrid(150.7, 32), 1.0) == 151  # 0.998 m
    assert grid_points(TileGrid(200.0, 32), 200.0 / MAX_GRID_POINTS) == MAX_GRID_POINTS
    assert grid_points(TileGrid(200.0, 32), 0.99 * 200.0 / MAX_GRID_POINTS) is None


def test_a_tile_sea_carries_its_tile_and_its_lattice_is_checked():
    sea = tile_sea(_JONSWAP)
    assert sea.tile == TileGrid(150.0, 16)
    assert sea.filtered(20.0).tile == sea.tile and sea != WaveField(sea.components, sea.gravity,
                                                                    sea.depth)
    assert len(sea.components) == 15 * 15 - 1  # every lattice wave but k = 0 and Nyquist's
    off = WaveComponent(0.1, 150.0 / 2.5, 0.0)  # n = 2.5: between lattice points
    with pytest.raises(InvalidSeaStateError, match=r"components\[224\] = .*must lie on the "
                       r"tile's lattice: wavevector 2 pi \(n, m\) / 150 m with integers "
                       r"\|n\|, \|m\| < 8"):
        WaveField((*sea.components, off), tile=sea.tile)
    beyond = WaveComponent(0.01, 150.0 / 8, 0.0)  # n = 8: the Nyquist line, not a wave of N 16
    with pytest.raises(InvalidSeaStateError, match=r"components\[0\]"):
        WaveField((beyond,), tile=TileGrid(150.0, 16))
    assert WaveField((beyond,), tile=TileGrid(150.0, 18)).tile.resolution == 18
    with pytest.raises(InvalidSeaStateError, match=r"components\[0\]"):  # at k = 0
        WaveField((beyond,), tile=TileGrid(1e-9, 16))
    for bad, key in ((TileGrid(0.0, 16), "tile.size"), (TileGrid(math.inf, 16), "tile.size"),
                     (TileGrid(150.0, 15), "tile.resolution"),
                     (TileGrid(150.0, 2), "tile.resolution")):
        with pytest.raises(InvalidSeaStateError, match=f"{key} = "):
            WaveField((), tile=bad)


def test_small_wave_suppression_is_tessendorfs_exp_minus_k2_l2():
    # eq. 24: P(k) exp(-k^2 l^2), the same draws: h0 is times exp(-k^2 l^2 / 2) exactly
    spec = TileSpec(size=100.0, resolution=64, seed=7, wind_speed=6.0)
    ell = 4.0  # the tile's shortest waves are 3.125 m (2.2 m on the diagonal)
    plain = tile_amplitudes(spec)
    damped = tile_amplitudes(TileSpec(**{**spec.__dict__, "suppression_length": ell}))
    kx, ky = lattice(spec)
    k2 = kx * kx + ky * ky
    np.testing.assert_allclose(damped, plain * np.exp(-k2 * ell**2 / 2.0), rtol=1e-12, atol=0)
    # the waves shorter than l keep under exp(-4 pi^2) = 7e-18 of their variance, those 10 l
    # long and longer over exp(-(2 pi / 10)^2) = 67 %
    wavelength = 2.0 * np.pi / np.sqrt(np.where(k2 > 0.0, k2, 1.0))
    short, long = (k2 > 0.0) & (wavelength < ell), (k2 > 0.0) & (wavelength >= 10.0 * ell)
    assert short.sum() > 1000 and long.sum() >= 20
    assert np.sum(np.abs(damped[short]) ** 2) < 7.2e-18 * np.sum(np.abs(plain[short]) ** 2)
    assert np.all(np.abs(damped[long]) ** 2 >= 0.67 * np.abs(plain[long]) ** 2)
    # and the tile's heights: its spectrum's share below l is gone
    sea = tile_sea(TileSpec(**{**spec.__dict__, "suppression_length": ell}))
    below = sum(c.amplitude**2 for c in sea.components if c.wavelength < ell)
    assert below < 1e-17 * sum(c.amplitude**2 for c in tile_sea(spec).components
                               if c.wavelength < ell)
