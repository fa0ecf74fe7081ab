"""Sample-point buoyancy options of the seed notes."""

import math

import numpy as np
import pytest
from ready_scenarios import ready

from boat_dynamics.physics.body.hull import BoxHull
from boat_dynamics.physics.core.boat import BoatInputs, initial_state, reference_pose, step
from boat_dynamics.physics.force_models.buoyancy import SamplePointBuoyancy, sample_point_buoyancy
from boat_dynamics.physics.scenario import ScenarioError
from ocean_sim.physics.waves import WaveField

RHO, G = 1025.0, 9.81
POINTS = BoxHull(4.0, 2.0, 1.0).bottom_grid(2, 2)
COM = np.zeros(3)
EYE = np.eye(3)


def model(**kw):
    return SamplePointBuoyancy(points=POINTS, volume=8.0, max_depth=1.0, **kw)


def total_up(m, depths, **kw):
    return sample_point_buoyancy(m, np.asarray(depths, float), EYE, COM, RHO, G, **kw).force


def test_linear_curve_is_archimedes_and_clamps_at_full_depth():
    full = RHO * G * 8.0
    assert total_up(model(), [0.5] * 4)[2] == pytest.approx(0.5 * full)
    assert total_up(model(), [7.0] * 4)[2] == pytest.approx(full)  # depth clamp
    assert total_up(model(), [-1.0] * 4)[2] == 0.0


def test_exponential_curve_saturates():
    m = model(curve="exponential", alpha=3.0)
    full = RHO * G * 8.0
    assert total_up(m, [1.0] * 4)[2] == pytest.approx(full)
    half = total_up(m, [0.5] * 4)[2] / full
    assert half == pytest.approx((1 - math.exp(-1.5)) / (1 - math.exp(-3.0)))
    assert half > 0.5  # more than linear near the surface, bounded at depth


def test_force_along_the_surface_normal():
    n = np.array([math.sin(0.3), 0.0, math.cos(0.3)])
    f = total_up(model(direction="normal"), [0.5] * 4, normals=np.tile(n, (4, 1)))
    assert f / np.linalg.norm(f) == pytest.approx(n)
    assert np.linalg.norm(f) == pytest.approx(0.5 * RHO * G * 8.0)


def test_depth_scale_and_force_clamp():
    base = total_up(model(), [0.25] * 4)[2]
    assert total_up(model(depth_scale=True), [0.25] * 4)[2] == pytest.approx(0.25 * base)
    clamped = total_up(model(force_clamp=0.5), [0.9] * 4)[2]
    assert clamped == pytest.approx(0.5 * RHO * G * 8.0)


def test_point_damping_is_proportional_to_mass_and_opposes_motion():
    v = np.tile([0.0, 0.0, 2.0], (4, 1))
    light = total_up(model(point_damping=1.5), [0.5] * 4, point_velocities=v, mass=1000.0)
    heavy = total_up(model(point_damping=1.5), [0.5] * 4, point_velocities=v, mass=2000.0)
    archimedes = 0.5 * RHO * G * 8.0
    assert archimedes - light[2] == pytest.approx(1.5 * 1000.0 * 2.0)
    assert archimedes - heavy[2] == pytest.approx(2 * (archimedes - light[2]))
    dry = total_up(model(point_damping=1.5), [-0.5] * 4, point_velocities=v, mass=1000.0)
    assert dry[2] == 0.0  # only submerged points damp


def test_boat_layout_floats_at_the_archimedes_draft():
    sc = ready({"boats": [{"mass": 2460.0, "buoyancy": {"model": "sample_points",
                                                                 "layout": "boat"}}]})
    p = sc.boats[0].params
    pts = p.buoyancy.points
    assert pts.shape == (7, 3)
    assert sorted(pts[:, 1].round(9)) == sorted((-pts[:, 1]).round(9))  # symmetric
    s = initial_state(p, [0.0, 0.0, 0.3])
    for _ in range(3000):
        s = step(p, s, BoatInputs(), WaveField(), 0.01)
    draft = 0.5 - reference_pose(p, s)[0][2]
    assert draft == pytest.approx(2460.0 / (1025.0 * 8.0), abs=1e-3)


def test_custom_points_and_refusals():
    pts = [[1.5, 0.8, -0.5], [1.5, -0.8, -0.5], [-1.5, 0.8, -0.5], [-1.5, -0.8, -0.5]]
    sc = ready({"boats": [{"buoyancy": {"model": "sample_points", "layout": "custom",
                                                 "points": pts, "curve": "exponential"}}]})
    assert sc.boats[0].params.buoyancy.points.tolist() == pts
    with pytest.raises(ScenarioError, match=r"buoyancy.points"):
        ready({"boats": [{"buoyancy": {"model": "sample_points", "layout": "custom",
                                                "points": [[1, 2]]}}]})
    with pytest.raises(ScenarioError, match=r"buoyancy.curve: 'cubic'"):
        ready({"boats": [{"buoyancy": {"model": "sample_points", "curve": "cubic"}}]})
    with pytest.raises(ScenarioError, match=r"buoyancy.layout: 'boat' .*only for model"):
        ready({"boats": [{"buoyancy": {"layout": "boat"}}]})


def test_a_sphere_cap_has_the_closed_form_volume_and_centroid():
    # Against direct integration over the cap's height of the disc areas pi (r^2 - (z - r)^2)
    # (z from the sphere's lowest point), for a unit-diameter sphere.
    from boat_dynamics.physics.force_models.buoyancy import sphere_cap

    r = 0.5
    for x in (0.0, 0.1, 0.37, 0.5, 0.8, 1.0):
        z = np.linspace(0.0, x, 20_001)
        area = np.pi * (r * r - (z - r) ** 2)
        volume = np.trapezoid(area, z) if x > 0 else 0.0
        fraction, rise = sphere_cap(np.array([x]))
        assert fraction[0] == pytest.approx(volume / (4 / 3 * np.pi * r**3), abs=1e-8)
        if x > 0:
            assert rise[0] == pytest.approx(np.trapezoid(area * z, z) / volume, abs=1e-7)
    assert sphere_cap(np.array([0.5]))[1][0] == pytest.approx(5 / 16)  # hemisphere: 5 r / 8


@pytest.mark.parametrize("ratio", [0.1, 0.3, 0.5, 0.8])
def test_a_single_sphere_floats_at_the_exact_draft(ratio):
    # One sphere (Assassin's Creed's buoyancy spheres, curve: sphere) of diameter 1 m under a
    # box, loaded to `ratio` of its displacement: its draft h = x D solves
    # x^2 (3 - 2 x) = ratio (bisection here, independent of the model's code).
    diameter = 1.0
    mass = ratio * 1025.0 * math.pi * diameter**3 / 6.0
    sc = ready({"boats": [{"mass": mass, "hull": {"length": 1.0, "beam": 1.0, "height": 1.0},
                           "buoyancy": {"model": "sample_points", "layout": "custom",
                                        "points": [[0.0, 0.0, -0.5]], "curve": "sphere",
                                        "max_depth": diameter}}]})
    p = sc.boats[0].params
    lo, hi = 0.0, 1.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid * mid * (3 - 2 * mid) < ratio else (lo, mid)
    draft = 0.5 - p.control.height_offset  # the sphere's bottom is 0.5 m below the reference
    assert draft == pytest.approx(lo * diameter, abs=1e-6)
    s = initial_state(p, [0.0, 0.0, 0.2])
    for _ in range(4000):
        s = step(p, s, BoatInputs(), WaveField(), 0.01)
    assert 0.5 - reference_pose(p, s)[0][2] == pytest.approx(lo * diameter, abs=1e-3)


def test_spheres_default_to_the_hulls_volume_and_lift_at_their_cap_centroid():
    # Four spheres a side (the notes' "4+ per side"): by default together the hull's volume;
    # a box loaded to half of it floats with each sphere half under (x = 1/2), level.
    sc = ready({"boats": [{"density": 512.5, "buoyancy": {
        "model": "sample_points", "grid": [4, 2], "curve": "sphere"}}]})
    b = sc.boats[0].params.buoyancy
    diameter = (6 * 8.0 / (math.pi * 8)) ** (1 / 3)
    assert b.max_depth == pytest.approx(diameter)
    assert b.volume == pytest.approx(8.0)
    draft = -0.5 - sc.boats[0].params.control.height_offset + 1.0  # bottom at -0.5 m
    assert draft == pytest.approx(0.5 * diameter, abs=1e-6)
    # the torque of a depth difference between the sides comes from the cap centroids
    depths = np.array([0.3, 0.3, 0.3, 0.3, 0.6, 0.6, 0.6, 0.6])
    m = SamplePointBuoyancy(points=b.points, volume=b.volume, max_depth=b.max_depth,
                            curve="sphere")
    w = sample_point_buoyancy(m, depths, EYE, COM, RHO, G)
    from boat_dynamics.physics.force_models.buoyancy import sphere_cap

    f, rise = sphere_cap(depths / b.max_depth)
    share = RHO * G * b.volume / 8
    arms = b.points.copy()
    arms[:, 2] += rise * b.max_depth
    expected = np.cross(arms, np.column_stack([0 * f, 0 * f, share * f])).sum(axis=0)
    assert w.force[2] == pytest.approx(share * f.sum())
    assert w.torque == pytest.approx(expected)
