"""Gerstner wave field against its closed forms."""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from ocean_sim.physics.waves import (
    InvalidSeaStateError,
    WaveComponent,
    WaveField,
    angular_frequency,
    displace,
    find_rest_positions,
    sample_surface,
    slope_orbit_velocity,
    stokes_drift,
    surface_height,
)

STEEP_SEA = WaveField(
    (
        WaveComponent(0.8, 30.0, 0.2, 1.0, 0.3),
        WaveComponent(0.4, 11.0, 1.3, 0.9, 1.1),
        WaveComponent(0.15, 6.0, -0.7, 1.0, 2.5),
        WaveComponent(0.05, 3.0, 2.9, 0.8, 0.0),
    ),
    depth=20.0,
)


def test_steep_sea_is_admissible_and_steep():
    assert 0.6 < STEEP_SEA.steepness_sum <= 1.0


def _height_by_formula(sea, xy, t):
    """Height at world xy by brute force: dense displaced grid, refined by bisection-free search.

    Independent of the Newton inversion: scipy-free fixed-point iteration run to machine
    precision with a small relaxation factor.
    """
    p0 = np.array(xy, dtype=float).reshape(-1, 2).copy()
    for _ in range(2000):
        d = displace(sea, p0, t)
        p0 = p0 - 0.5 * (d[:, :2] - xy)
    return displace(sea, p0, t)


def test_height_matches_formula_below_1mm_on_steep_multicomponent_sea():
    rng = np.random.default_rng(1)
    xy = rng.uniform(-60, 60, size=(400, 2))
    t = 17.3
    heights = surface_height(STEEP_SEA, xy, t)
    reference = _height_by_formula(STEEP_SEA, xy, t)
    assert np.abs(reference[:, :2] - xy).max() < 1e-9  # the reference did converge
    assert np.abs(heights - reference[:, 2]).max() < 1e-3
    # and the inversion lands the displaced rest position on the query point
    p0 = find_rest_positions(STEEP_SEA, xy, t)
    assert np.abs(displace(STEEP_SEA, p0, t)[:, :2] - xy).max() < 1e-6


def test_normals_equal_finite_differences_of_displaced_surface():
    rng = np.random.default_rng(2)
    p0 = rng.uniform(-40, 40, size=(200, 2))
    t = 4.2
    h = 1e-5
    tx = (displace(STEEP_SEA, p0 + [h, 0], t) - displace(STEEP_SEA, p0 - [h, 0], t)) / (2 * h)
    ty = (displace(STEEP_SEA, p0 + [0, h], t) - displace(STEEP_SEA, p0 - [0, h], t)) / (2 * h)
    fd = np.cross(tx, ty)
    fd /= np.linalg.norm(fd, axis=1, keepdims=True)
    xy = displace(STEEP_SEA, p0, t)[:, :2]
    normals = sample_surface(STEEP_SEA, xy, t).normals
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0)
    assert np.abs(normals - fd).max() < 1e-6


def test_velocity_equals_time_derivative_of_particle_position():
    rng = np.random.default_rng(3)
    p0 = rng.uniform(-40, 40, size=(50, 2))
    t, h = 9.0, 1e-5
    fd = (displace(STEEP_SEA, p0, t + h) - displace(STEEP_SEA, p0, t - h)) / (2 * h)
    xy = displace(STEEP_SEA, p0, t)[:, :2]
    surf = sample_surface(STEEP_SEA, xy, t)
    assert np.abs(surf.velocities - fd).max() < 1e-6
    fd2 = (displace(STEEP_SEA, p0, t + h)[:, 2] - 2 * displace(STEEP_SEA, p0, t)[:, 2]
           + displace(STEEP_SEA, p0, t - h)[:, 2]) / h**2
    assert np.abs(surf.accelerations[:, 2] - fd2).max() < 1e-3


@pytest.mark.parametrize("depth", [math.inf, 50.0, 5.0, 1.0])
def test_dispersion_relation(depth):
    wavelength = 20.0
    k = 2 * math.pi / wavelength
    omega = float(angular_frequency(k, 9.81, depth))
    expected = math.sqrt(9.81 * k * (1.0 if math.isinf(depth) else math.tanh(k * depth)))
    assert omega == pytest.approx(expected, rel=1e-12)
    # the wave crest moves at the phase speed omega / k
    sea = WaveField((WaveComponent(0.1, wavelength, 0.0, 0.0, 0.0),), depth=depth)
    c = omega / k
    for t in (0.0, 3.0):
        crest_x = c * t
        assert surface_height(sea, [[crest_x, 0.0]], t)[0] == pytest.approx(0.1, abs=1e-12)


def test_trochoid_particles_move_on_circles_of_radius_a():
    a = 0.5
    sea = WaveField((WaveComponent(a, 2 * math.pi * a, 0.7, 1.0, 0.0),))  # k a = 1: Q k a = 1
    p0 = np.array([[3.0, -2.0]])
    ts = np.linspace(0, 10, 200)
    pts = np.array([displace(sea, p0, t)[0] for t in ts])
    d = np.array([math.cos(0.7), math.sin(0.7)])
    horizontal = (pts[:, :2] - p0) @ d
    assert np.allclose(horizontal**2 + pts[:, 2] ** 2, a * a, atol=1e-12)


def test_flat_sea():
    surf = sample_surface(WaveField(), np.array([[1.0, 2.0], [-3.0, 4.0]]), 5.0)
    assert np.all(surf.heights == 0.0)
    assert np.all(surf.normals == [0.0, 0.0, 1.0])
    assert np.all(surf.velocities == 0.0)


@pytest.mark.parametrize(
    ("kwargs", "key"),
    [
        ({"components": (WaveComponent(-0.1, 10.0),)}, "components[0].amplitude"),
        ({"components": (WaveComponent(0.1, 0.0),)}, "components[0].wavelength"),
        ({"components": (WaveComponent(0.1, 10.0, steepness=1.5),)}, "components[0].steepness"),
        ({"components": (WaveComponent(0.1, math.nan),)}, "components[0].wavelength"),
        ({"components": (WaveComponent(0.1, 10.0), WaveComponent(math.inf, 5.0))},
         "components[1].amplitude"),
        ({"components": (WaveComponent(2.0, 10.0, steepness=1.0),)}, "components"),
        ({"gravity": 0.0}, "gravity"),
        ({"depth": -1.0}, "depth"),
    ],
)
def test_refused_sea_states_name_the_key(kwargs, key):
    with pytest.raises(InvalidSeaStateError) as info:
        WaveField(**kwargs)
    assert info.value.key == key
    assert key in str(info.value)


@st.composite
def admissible_seas(draw, max_ak=math.inf):
    n = draw(st.integers(1, 6))
    budget = draw(st.floats(0.05, 1.0))
    comps = []
    weights = [draw(st.floats(0.1, 1.0)) for _ in range(n)]
    for w in weights:
        lam = draw(st.floats(2.0, 200.0))
        q = draw(st.floats(0.0, 1.0))
        k = 2 * math.pi / lam
        a_max = budget * w / sum(weights) / max(q * k, 1e-9)
        a = min(draw(st.floats(0.0, 1.0)) * a_max, 5.0, max_ak / k)
        comps.append(WaveComponent(a, lam, draw(st.floats(-math.pi, math.pi)), q,
                                   draw(st.floats(0, 2 * math.pi))))
    depth = draw(st.one_of(st.just(math.inf), st.floats(0.5, 500.0)))
    return WaveField(tuple(comps), depth=depth)


@settings(max_examples=200, deadline=None)
@given(sea=admissible_seas(), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16))
# a cusp (Q k a = 1): a point starting next to it was left 0.46 mm off after 60 fixed-point
# steps (found by a loaded CI-like run); a damped Newton step now gets it to 1e-7 m
@example(sea=WaveField((WaveComponent(0.3183098861837907, 2.0, 0.345703125, 1.0, 0.5),)),
         t=0.0, seed=1)
@example(sea=WaveField((WaveComponent(1.0 / math.pi, 2.0, 0.345703125, 1.0, 0.5),)),
         t=1.3, seed=0)
def test_inversion_residual_below_1mm_for_admissible_seas(sea, t, seed):
    xy = np.random.default_rng(seed).uniform(-500, 500, size=(64, 2))
    p0 = find_rest_positions(sea, xy, t)
    residual = np.abs(displace(sea, p0, t)[:, :2] - xy).max()
    assert residual < 1e-6  # the documented tolerance is 1e-7 m; 1 mm is the requirement


@settings(max_examples=60, deadline=None)
@given(sea=admissible_seas(max_ak=0.45), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16))
@example(sea=WaveField((WaveComponent(0.1432394487827058, 2.0, 0.0, 1.0, 1.0),)), t=1.5, seed=0)
def test_float32_queries_agree_with_float64_to_a_tenth_of_a_millimetre(sea, t, seed):
    # physically possible waves: a k <= 0.45 (Stokes limit H / lambda = 1/7); each point's
    # phase is reduced modulo 2 pi in float64 before the cast, so far from the origin too
    xy = np.random.default_rng(seed).uniform(-300, 300, size=(64, 2)) + 5000.0
    a = sample_surface(sea, xy, t)
    b = sample_surface(sea, xy, t, precision="float32")
    assert np.abs(a.heights - b.heights).max() < 1e-4
    # normals turn fastest at a steep crest: curvature k (k a) / (1 - Q k a)^2, 4.7 /m for
    # a = 0.143 m, lambda = 2 m, Q = 1 (found by hypothesis: 1.4e-4 rad there). 5e-4 rad is 0.03 deg
    assert np.abs(a.normals - b.normals).max() < 5e-4
    assert np.abs(displace(sea, b.rest_xy, t)[:, :2] - xy).max() < 1e-4


@settings(max_examples=60, deadline=None)
@given(sea=admissible_seas(max_ak=0.45), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16),
       precision=st.sampled_from(["float32", "float64"]))
def test_a_points_answer_does_not_depend_on_the_other_points_asked_with_it(sea, t, seed,
                                                                          precision):
    # what lets a fleet split over shards (or a boat stepped alone) get the same numbers, to
    # the last bits of the final sums: BLAS rounds a row's sums over the components by its
    # place in the batch on some CPUs (OpenBLAS's AVX2 sgemm: 3e-8 m in a float32 height on an
    # AMD EPYC). Phases taken about the batch's centre differed by up to 1e-4 m in
    # float32 here.
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-2000, 2000, size=(int(rng.integers(2, 200)), 2))
    part = np.sort(rng.choice(len(xy), size=int(rng.integers(1, len(xy))), replace=False))
    whole = sample_surface(sea, xy, t, precision=precision)
    alone = sample_surface(sea, xy[part], t, precision=precision)
    last_bits = 1e-6 if precision == "float32" else 1e-12
    for field in ("heights", "normals", "velocities", "rest_xy"):
        difference = np.abs(getattr(whole, field)[part] - getattr(alone, field)).max()
        assert difference <= last_bits, (field, difference)


def test_a_point_too_far_for_float32_spoils_only_its_own_answer():
    xy = np.array([[1.0, 2.0], [1e308, 0.0], [-30.0, 4.0]])
    with np.errstate(over="ignore", invalid="ignore"):  # no exception either
        got = sample_surface(STEEP_SEA, xy, 3.0, precision="float32")
    fine = sample_surface(STEEP_SEA, xy[[0, 2]], 3.0, precision="float32")
    assert np.array_equal(got.heights[[0, 2]], fine.heights)
    assert not np.isfinite(got.heights[1])


def test_ignore_horizontal_displacement_uses_the_query_point_as_rest_position():
    rng = np.random.default_rng(5)
    xy = rng.uniform(-50, 50, size=(100, 2))
    approx = sample_surface(STEEP_SEA, xy, 3.0, invert=False)
    assert np.array_equal(approx.rest_xy, xy)
    assert np.allclose(approx.heights, displace(STEEP_SEA, xy, 3.0)[:, 2], atol=1e-12)
    exact = sample_surface(STEEP_SEA, xy, 3.0)
    assert np.abs(approx.heights - exact.heights).max() > 0.05  # it is an approximation


def test_min_wavelength_leaves_out_short_components():
    long_only = WaveField(STEEP_SEA.components[:2], depth=STEEP_SEA.depth)
    xy = np.random.default_rng(6).uniform(-50, 50, size=(50, 2))
    a = sample_surface(STEEP_SEA, xy, 2.0, min_wavelength=10.0)
    b = sample_surface(long_only, xy, 2.0)
    assert np.array_equal(a.heights, b.heights)
    assert STEEP_SEA.filtered(10.0) is STEEP_SEA.filtered(10.0)  # cached
    assert STEEP_SEA.filtered(0.0) is STEEP_SEA


def test_stokes_drift_closed_form():
    a, lam = 0.5, 30.0
    k = 2 * math.pi / lam
    w = math.sqrt(9.81 * k)
    deep = WaveField((WaveComponent(a, lam, math.pi / 2, 0.5, 0.0),))
    assert np.allclose(stokes_drift(deep), [0.0, w * k * a * a], atol=1e-15)
    assert stokes_drift(deep, 2.0)[1] == pytest.approx(w * k * a * a * math.exp(-4 * k))
    # finite depth: omega k a^2 cosh(2kh) / (2 sinh^2(kh)), larger than deep water at the surface
    h = 5.0
    shallow = WaveField((WaveComponent(a, lam, 0.0, 0.5, 0.0),), depth=h)
    ws = math.sqrt(9.81 * k * math.tanh(k * h))
    expected = ws * k * a * a * math.cosh(2 * k * h) / (2 * math.sinh(k * h) ** 2)
    assert stokes_drift(shallow)[0] == pytest.approx(expected, rel=1e-12)
    assert stokes_drift(WaveField()).tolist() == [0.0, 0.0]


def test_slope_orbit_velocity_is_the_time_integral_of_the_slope_push():
    # du/dt at a fixed particle = -g grad_p0 z(p0, t): the push of the slope (first order),
    # on a finite-depth sea with omega^2 = g k tanh(k h)
    p0 = np.random.default_rng(8).uniform(-40, 40, size=(20, 2))
    t, h = 3.7, 1e-4
    du_dt = (slope_orbit_velocity(STEEP_SEA, p0, t + h)
             - slope_orbit_velocity(STEEP_SEA, p0, t - h)) / (2 * h)

    def z(p):
        return displace(STEEP_SEA, p, t)[:, 2]

    grad = np.stack([(z(p0 + [h, 0.0]) - z(p0 - [h, 0.0])) / (2 * h),
                     (z(p0 + [0.0, h]) - z(p0 - [0.0, h])) / (2 * h)], axis=1)
    np.testing.assert_allclose(du_dt, -STEEP_SEA.gravity * grad, atol=2e-6)
    assert np.abs(du_dt).max() > 1.0  # a real push
    # deep water, Q = 1: the Gerstner particle's own velocity; Q = 0.5: twice it
    for q in (1.0, 0.5):
        deep = WaveField((WaveComponent(0.5, 30.0, 0.7, q, 0.2),))
        sample = sample_surface(deep, p0, t)
        np.testing.assert_allclose(slope_orbit_velocity(deep, sample.rest_xy, t),
                                   sample.velocities[:, :2] / q, atol=1e-12)
    assert slope_orbit_velocity(WaveField(), p0, t).tolist() == np.zeros((20, 2)).tolist()


def test_unknown_precision_is_refused():
    with pytest.raises(ValueError, match="precision 'float16' is not allowed"):
        sample_surface(STEEP_SEA, [[0.0, 0.0]], 0.0, precision="float16")


def test_pressure_head_is_hydrostatic_in_still_water_and_zero_on_any_surface():
    from ocean_sim.physics.waves import pressure_head

    z = np.array([-3.0, -0.5, 0.0])
    assert np.array_equal(pressure_head(WaveField(), np.zeros((3, 2)), np.zeros(3), z, 1.0), -z)
    rng = np.random.default_rng(5)
    xy = rng.uniform(-30, 30, (200, 2))
    for depth in (math.inf, 8.0):
        sea = WaveField((WaveComponent(0.5, 20.0, 0.3, 0.9, 0.2),
                         WaveComponent(0.2, 7.0, -1.2, 0.6, 1.0)), depth=depth)
        s = sample_surface(sea, xy, 3.7)
        at_surface = pressure_head(sea, s.rest_xy, s.heights, s.heights, 3.7)
        assert np.abs(at_surface).max() < 1e-12  # Wheeler stretching: p = 0 on the surface
        below = pressure_head(sea, s.rest_xy, s.heights, s.heights - rng.uniform(0, 5, 200), 3.7)
        assert below.min() > 0.0  # the water pushes wherever it is


@pytest.mark.parametrize("depth", [math.inf, 3.0, 1e4])
def test_pressure_head_decays_with_depth_as_linear_theory(depth):
    # a small sine wave: p / (rho g) = -z + a cos(theta) E(z), E = e^{kz} deep,
    # cosh k(z + h) / cosh kh in finite depth (Dean & Dalrymple eq. 4.23)
    from ocean_sim.physics.waves import pressure_head

    a, lam = 1e-4, 5.0
    k = 2 * math.pi / lam
    sea = WaveField((WaveComponent(a, lam, 0.0, 0.0, 0.4),), depth=depth)
    x = np.linspace(0, lam, 7)
    xy = np.stack([x, np.zeros_like(x)], axis=1)
    s = sample_surface(sea, xy, 0.9)
    theta = k * x - angular_frequency(k, 9.81, depth) * 0.9 + 0.4
    for z in (-0.3, -1.0, -2.5):
        head = pressure_head(sea, s.rest_xy, s.heights, np.full(7, z), 0.9)
        decay = (math.exp(k * z) if depth > 1e3  # deep (cosh k h overflows a float)
                 else math.cosh(k * (z + depth)) / math.cosh(k * depth))
        # stretching moves the decay by eta = O(a): a relative error of O(k a)
        np.testing.assert_allclose(head + z, a * np.cos(theta) * decay, rtol=0, atol=a * k * a)
        assert np.all(np.isfinite(head))


def test_a_sea_of_more_than_max_components_is_refused():
    # whoever gives it (scenario, parameters, an /ocean/wave_field from any node): 20,000
    # components were accepted and slowed every query 20-fold
    from ocean_sim.physics.waves import MAX_COMPONENTS

    one = WaveComponent(0.01, 50.0, 0.0, 0.0, 0.0)
    assert len(WaveField((one,) * MAX_COMPONENTS).components) == MAX_COMPONENTS
    with pytest.raises(InvalidSeaStateError, match="at most 4096") as err:  # a 64^2 tile
        WaveField((one,) * (MAX_COMPONENTS + 1))
    assert err.value.key == "components"
