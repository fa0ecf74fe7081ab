"""The compiled surface query against its numpy oracle, and its sin / cos; the kernels' cache.

``sample_surface(..., precision="float64")`` runs the compiled kernel
(:mod:`ocean_sim.physics.surface_kernel`); ``waves._sample_numpy`` is the numpy
implementation it replaced for float64, kept as the oracle.
"""

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_waves import admissible_seas

from ocean_sim.physics import waves
from ocean_sim.physics.surface_kernel import sincos
from ocean_sim.physics.waves import WaveComponent, WaveField, displace, sample_surface

FIELDS = ("heights", "normals", "velocities", "accelerations", "rest_xy")


def _points(seed: int, n: int = 64, offset: float = 0.0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-300, 300, size=(n, 2)) + offset


@settings(max_examples=120, deadline=None)
@given(sea=admissible_seas(max_ak=0.45), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16),
       offset=st.sampled_from([0.0, 5000.0]), budget=st.floats(0.05, 0.9))
@example(sea=WaveField((WaveComponent(0.3, 25.0, 0.0, 0.5), WaveComponent(0.15, 12.0, 0.4, 0.5),
                        WaveComponent(0.08, 6.0, -0.3, 0.5))), t=3.0, seed=0, offset=0.0,
         budget=0.9)
def test_the_compiled_query_equals_numpys_where_the_inversion_is_well_posed(sea, t, seed, offset,
                                                                         budget):
    # physically possible waves (a k <= 0.45, the Stokes limit; a 5 m wave 2 m long has
    # slopes of 16, which make its normals 16 times as sensitive to the phase's last bit), and
    # sum Q k a <= 0.9: det J >= 0.01, so rounding is not amplified by the inversion; there
    # every field agrees to 1e-12 of its largest value in the batch (at least 1: m, m/s,
    # m/s^2). A phase of 1e3 rad holds 1e-13 rad (an ulp), summed in another order by each;
    # 5 km out (1e4 rad, 2e-12 rad) within 1e-9, what the compiled core promises
    if sea.steepness_sum > budget:
        scale = budget / sea.steepness_sum
        sea = WaveField(tuple(WaveComponent(c.amplitude * scale, c.wavelength, c.direction,
                                            c.steepness, c.phase) for c in sea.components),
                        depth=sea.depth)
    xy = _points(seed, offset=offset)
    got = sample_surface(sea, xy, t, precision="float64")
    want = waves._sample_numpy(sea, xy, t, "float64", True)
    tol = 1e-12 if offset == 0.0 else 1e-9
    for name in FIELDS:
        a, b = getattr(got, name), getattr(want, name)
        assert np.abs(a - b).max() <= tol * max(1.0, np.abs(b).max()), name


@settings(max_examples=120, deadline=None)
@given(sea=admissible_seas(), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16))
@example(sea=WaveField((WaveComponent(1.0 / math.pi, 2.0, 0.345703125, 1.0, 0.5),)),
         t=1.3, seed=0)  # a cusp, sum Q k a = 1: the halved Newton steps
def test_the_compiled_inversion_finds_the_rest_positions_up_to_the_cusp(sea, t, seed):
    xy = _points(seed)
    got = sample_surface(sea, xy, t, precision="float64")
    assert np.abs(displace(sea, got.rest_xy, t)[:, :2] - xy).max() < 1e-6  # tolerance 1e-7
    assert np.allclose(np.linalg.norm(got.normals, axis=1), 1.0, atol=1e-12)


def test_no_inversion_no_horizontal_motion_no_points_and_a_nan_point():
    sea = WaveField((WaveComponent(0.3, 25.0, 0.2, 0.6), WaveComponent(0.1, 7.0, -1.0, 0.4)))
    xy = _points(3, 16)
    for invert in (True, False):
        got = sample_surface(sea, xy, 7.0, invert=invert, precision="float64")
        want = waves._sample_numpy(sea, xy, 7.0, "float64", invert)
        for name in FIELDS:
            assert np.allclose(getattr(got, name), getattr(want, name), rtol=0, atol=1e-12)
    sine = WaveField((WaveComponent(0.3, 25.0, 0.2, 0.0),))  # Q = 0: no inversion needed
    assert np.array_equal(sample_surface(sine, xy, 1.0, precision="float64").rest_xy, xy)
    assert sample_surface(sea, np.zeros((0, 2)), 1.0, precision="float64").heights.shape == (0,)
    bad = xy.copy()
    bad[5] = np.nan
    got = sample_surface(sea, bad, 7.0, precision="float64")
    keep = np.arange(16) != 5
    assert np.isnan(got.heights[5]) and np.all(np.isfinite(got.heights[keep]))
    assert np.allclose(got.heights[keep],
                       sample_surface(sea, xy, 7.0, precision="float64").heights[keep],
                       rtol=0, atol=0)  # a point's result does not depend on the others


@pytest.mark.parametrize("scale", [1.0, 100.0, 1e5])
def test_the_polynomial_sin_and_cos_are_within_2_ulp_of_libm(scale):
    x = np.random.default_rng(int(scale)).uniform(-scale, scale, 200_000)
    x[:4] = [0.0, math.pi / 4, -math.pi / 2, 3 * math.pi / 4]
    s, c = sincos(x)
    for got, want in ((s, np.sin(x)), (c, np.cos(x))):
        assert np.all(np.abs(got - want) <= 2 * np.spacing(np.maximum(np.abs(want), 0.5)))


def _start(env: dict, tmp_path) -> subprocess.CompletedProcess:
    # The module's smallest kernel: it is cached as surface_f64 is (jit.kernel); compiling
    # surface_f64 took 24 s of the test's 26 s on a busy machine, sincos 3 s of 5
    code = ("import warnings, numpy as np; warnings.simplefilter('always')\n"
            "from ocean_sim.physics import jit\n"
            "from ocean_sim.physics.surface_kernel import sincos\n"
            "sincos(np.zeros(1))\n"
            "print(jit.cache_dir(), sum(sincos.stats.cache_hits.values()))")
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          timeout=600, cwd=tmp_path)


def test_a_cache_directory_that_cannot_be_written_falls_back_to_one_every_process_finds(
        tmp_path):
    # numba would otherwise compile again in every process (a read-only install keeps its
    # cache beside the source); here the first process compiles and the second loads. The
    # home is a file, so that even root cannot make the directory (a mode would not stop it)
    home = tmp_path / "home"
    home.write_text("")
    temp = tmp_path / "tmp"
    temp.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(XDG_CACHE_HOME=str(home), TMPDIR=str(temp), OPENBLAS_NUM_THREADS="1")
    first, second = _start(env, tmp_path), _start(env, tmp_path)
    fallback = temp / f"boatsim-numba-{os.getuid()}"
    for run in (first, second):
        assert run.returncode == 0, run.stderr
        assert f"{home / 'boatsim' / 'numba'} cannot be written; using {fallback}" in run.stderr
    assert first.stdout.split() == [str(fallback), "0"]  # compiled
    assert second.stdout.split() == [str(fallback), "1"]  # loaded from the cache


def test_numba_cache_dir_is_honoured(tmp_path):
    code = ("import numba; from ocean_sim.physics import jit\n"
            "print(jit.cache_dir(), numba.config.CACHE_DIR)")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "mine"))
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [str(tmp_path / "mine")] * 2 and not run.stderr


@settings(max_examples=10, deadline=None)
@given(sea=admissible_seas(), t=st.floats(0.0, 1e3), seed=st.integers(0, 2**16))
def test_a_point_is_answered_alike_in_any_block_and_any_batch(sea, t, seed):
    """The query goes in blocks of points (surface_kernel._BLOCK phases): a point's answer,
    to the last bit, is the one it gets asked alone, wherever the blocks cut the batch."""
    from ocean_sim.physics.surface_kernel import _BLOCK

    n = 2 * _BLOCK // max(len(sea.components), 1) + 37  # three blocks, the last one short
    xy = _points(seed, n)
    batch = sample_surface(sea, xy, t, precision="float64")
    for i in np.random.default_rng(seed).choice(n, size=12, replace=False):
        alone = sample_surface(sea, xy[i:i + 1], t, precision="float64")
        for name in FIELDS:
            np.testing.assert_array_equal(getattr(batch, name)[i], getattr(alone, name)[0],
                                          err_msg=name)
