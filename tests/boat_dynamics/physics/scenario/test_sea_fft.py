"""The scenario's ``ocean.model: fft`` and its ``ocean.fft`` block."""

from __future__ import annotations

import math

import pytest

from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
from ocean_sim.physics.fft import TileSpec, tile_sea


def _sea(ocean: dict, **simulation):
    return parse_scenario({"simulation": simulation, "ocean": ocean,
                           "boats": [{"name": "b"}]}).sea


def test_an_fft_ocean_is_its_tiles_components():
    sea = _sea({"model": "fft", "depth": 30.0,
                "fft": {"size": 150.0, "resolution": 16, "spectrum": "jonswap",
                        "significant_height": 1.5, "peak_period": 7.0, "direction_deg": 90.0,
                        "choppiness": 0.7}}, seed=5)
    spec = TileSpec(size=150.0, resolution=16, seed=5, spectrum="jonswap",
                    significant_height=1.5, peak_period=7.0, direction=math.pi / 2,
                    choppiness=0.7, depth=30.0)
    assert sea == tile_sea(spec)  # the seed is simulation.seed unless ocean.fft.seed
    assert _sea({"model": "fft", "fft": {"seed": 5}}) == _sea({"model": "fft"}, seed=5)
    assert _sea({"model": "fft", "fft": {"seed": 4}}) != _sea({"model": "fft"}, seed=5)


def test_small_wave_suppression_is_the_tiles():
    sea = _sea({"model": "fft", "fft": {"size": 80.0, "resolution": 16,
                                        "suppression_length": 3.0}}, seed=2)
    assert sea == tile_sea(TileSpec(size=80.0, resolution=16, seed=2, suppression_length=3.0))
    assert sea != _sea({"model": "fft", "fft": {"size": 80.0, "resolution": 16}}, seed=2)


def test_the_default_model_is_the_gerstner_sum():
    comps = [{"amplitude": 0.3, "wavelength": 25.0}]
    assert _sea({"components": comps}) == _sea({"model": "gerstner", "components": comps})


@pytest.mark.parametrize(("ocean", "key", "allowed"), [
    ({"model": "ffx"}, "ocean.model", "must be one of: gerstner, fft"),
    ({"model": "fft", "spectrum": {}}, "ocean.spectrum", "not with ocean.model fft"),
    ({"model": "fft", "components": []}, "ocean.components", "not with ocean.model fft"),
    ({"fft": {"size": 100.0}}, "ocean.fft", "only with ocean.model: fft"),
    ({"model": "fft", "fft": {"sise": 1}}, "ocean.fft.sise", "unknown key"),
    ({"model": "fft", "fft": {"resolution": 31}}, "ocean.fft.resolution", "even integer"),
    ({"model": "fft", "fft": {"resolution": 128}}, "ocean.fft.resolution", r"\[4, 64\]"),
    ({"model": "fft", "fft": {"seed": -2}}, "ocean.fft.seed", "integer >= 0"),
    ({"model": "fft", "fft": {"spectrum": "pm"}}, "ocean.fft.spectrum", "phillips, jonswap"),
    ({"model": "fft", "fft": {"gamma": 2.0}}, "ocean.fft.gamma", "only with spectrum: jonswap"),
    ({"model": "fft", "fft": {"spectrum": "jonswap", "wind_speed": 3.0}},
     "ocean.fft.wind_speed", "only with spectrum: phillips"),
    ({"model": "fft", "fft": {"choppiness": 1.2}}, "ocean.fft.choppiness", r"\[0, 1\]"),
    ({"model": "fft", "fft": {"size": -1.0}}, "ocean.fft.size", r"\(0, 1e\+06\]"),
    ({"model": "fft", "fft": {"suppression_length": -0.1}}, "ocean.fft.suppression_length",
     r"\[0, 1e\+06\] m"),
    ({"model": "fft", "fft": {"suppression_length": "2 m"}}, "ocean.fft.suppression_length",
     "must be a number"),
    ({"model": "fft", "fft": {"size": 50.0, "suppression_length": 60.0}},
     "ocean.fft.suppression_length", r"must be a number in \[0, 50\] m \(the tile's size\)"),
])
def test_a_bad_fft_ocean_is_refused_naming_key_value_and_what_is_allowed(ocean, key, allowed):
    with pytest.raises(ScenarioError, match=allowed) as err:
        _sea(ocean)
    assert err.value.key == key
