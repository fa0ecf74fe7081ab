"""The radar: targets in their range bin and bearing, its resolution, R^-4, sea clutter."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_multiply, rotation_matrix
from boat_dynamics.physics.sensors.noise import stream_key
from boat_dynamics.physics.sensors.radar import (
    RadarSpec,
    clutter_mean,
    measure_radar,
    radar_points,
    significant_height,
    spokes_due,
)
from boat_dynamics.physics.world.obstacles import Cylinder, World

KEY = stream_key(0, "boat", "radar")
#: 1 deg a spoke, the default 3.9 deg beam (a spoke sees the rays 1 deg either side), no sea
QUIET = RadarSpec(spokes=360, sea_clutter=0.0, max_range=1000.0)
TWO_WAY_1DEG = math.exp(-8.0 * math.log(2.0) * (1.0 / 3.9) ** 2)


def _pile(r, bearing_deg, radius=0.2):
    b = math.radians(bearing_deg)
    return Cylinder("pile", np.array([r * math.cos(b), r * math.sin(b)]), radius, 2.0)


def _boat(yaw_deg=0.0, roll_deg=0.0):
    """(3, 3) body to world of a boat at ``roll`` then ``yaw``."""
    roll, yaw = math.radians(roll_deg), math.radians(yaw_deg)
    qr = np.array([math.sin(roll / 2), 0.0, 0.0, math.cos(roll / 2)])
    qy = np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])
    return rotation_matrix(quat_multiply(qy, qr)[None])[0]


def _scan(spec, world, rot=None, height=0.0, first=0, count=None, antenna=3.0):
    rot = _boat() if rot is None else rot
    spec = RadarSpec(**{**spec.__dict__, "position": np.array([0.0, 0.0, antenna])})
    return measure_radar(spec, KEY, first, spec.spokes if count is None else count, rot,
                         np.zeros(3), world, None, height)


def test_a_piling_is_in_its_range_bin_at_its_bearing_one_beamwidth_wide():
    # A piling 300 m off at 30 deg (world), the boat heading 10 deg: 20 deg to port. Its
    # face is 299.8 m off, bin floor(299.8 / 12) = 24 (centre 294 m); the ray at 20 deg hits
    # it and the spokes 1 deg either side see it at the two-way gain of 1 deg off the beam.
    scan = _scan(QUIET, World((_pile(300.0, 30.0),)), rot=_boat(yaw_deg=10.0))
    np.testing.assert_allclose(np.degrees(scan.azimuth), [21.0, 20.0, 19.0], atol=1e-9)
    np.testing.assert_allclose(scan.range, 294.0)
    echo = (QUIET.detection_range / 299.8) ** 4
    np.testing.assert_allclose(scan.intensity, echo * np.array([TWO_WAY_1DEG, 1.0,
                                                                TWO_WAY_1DEG]), rtol=1e-9)


def test_its_points_are_level_at_the_bearing_whatever_the_roll():
    # rolled, the mast's head is 0.8 m to starboard: a 2 m piling, its face 298 m off
    rot = _boat(yaw_deg=10.0, roll_deg=15.0)
    scan = _scan(QUIET, World((_pile(300.0, 30.0, radius=2.0),)), rot=rot)
    assert scan.range.size == 3
    points = radar_points(scan, rot)  # sensor frame; the body's rotation puts them level
    world = points @ rot.T
    np.testing.assert_allclose(world[1], 294.0 * np.array([math.cos(math.radians(30)),
                                                           math.sin(math.radians(30)), 0.0]),
                               atol=1e-9)
    assert abs(points[1, 2]) > 10.0  # in the rolled body's axes it is not level


def test_two_targets_within_a_bin_merge_and_a_bin_apart_do_not():
    # two pilings 1 deg either side of spoke 0, both in its beam: 100.3 and 105 m are one bin
    # (96..108 m), 100.3 and 110 m two
    def ahead(far):
        scan = _scan(QUIET, World((_pile(100.5, 1.0), _pile(far + 0.2, -1.0))),
                     first=0, count=1)
        return sorted(scan.range.tolist())

    assert ahead(105.0) == [102.0]
    assert ahead(110.0) == [102.0, 114.0]


def test_the_echo_falls_as_the_fourth_power_of_the_range():
    scan = _scan(QUIET, World((_pile(200.2, 0.0), _pile(400.2, 90.0))))
    near = scan.intensity[np.isclose(scan.azimuth, 0.0)]
    far = scan.intensity[np.isclose(scan.azimuth, math.pi / 2)]
    assert near[0] / far[0] == pytest.approx(2.0 ** 4, rel=1e-12)
    # beyond the detection range nothing is seen
    short = RadarSpec(**{**QUIET.__dict__, "detection_range": 300.0})
    assert np.all(_scan(short, World((_pile(400.2, 90.0),))).range.size == 0)


def test_the_sea_clutter_model_falls_as_r3_then_r7_past_the_critical_range():
    spec = RadarSpec(sea_clutter=1.0)
    # antenna 3 m, H_s 1 m: R_c = 4 pi 3 0.25 / 0.032 = 294.5 m
    rc = 4.0 * math.pi * 3.0 * 0.25 / 0.032
    c = clutter_mean(spec, np.array([50.0, 100.0, 2 * rc, 4 * rc]), 1.0, 3.0)
    assert c[1] == pytest.approx(1.0) and c[0] / c[1] == pytest.approx(8.0)
    assert c[2] / c[3] == pytest.approx(2.0 ** 7)
    assert np.all(clutter_mean(spec, np.array([50.0]), 0.0, 3.0) == 0.0)  # flat sea
    # a cell of half the bin and half the beam: a quarter of the clutter
    small = RadarSpec(sea_clutter=1.0, range_resolution=6.0, beamwidth=math.radians(1.95))
    assert clutter_mean(small, np.array([100.0]), 1.0, 3.0)[0] == pytest.approx(0.25)


def test_clutter_detections_fall_with_range_as_the_model_says():
    # No target; 4 revolutions of 2048 spokes: in each bin the count of detections is
    # binomial(n, exp(-1 / c(R))); within 5 sigma wherever it is not ~0 or ~n
    spec = RadarSpec(sea_clutter=1.0, max_range=600.0, min_range=0.0)
    assert _scan(spec, World(), height=0.0).range.size == 0  # flat sea: no clutter
    n = 4 * spec.spokes
    scan = _scan(spec, World(), height=1.0, count=n)
    centres = (np.arange(spec.bins) + 0.5) * spec.range_resolution
    p = np.exp(-1.0 / clutter_mean(spec, centres, 1.0, 3.0))
    counts = np.array([np.sum(np.isclose(scan.range, r)) for r in centres])
    sd = np.sqrt(n * p * (1 - p))
    tested = sd > 3.0
    assert tested.sum() >= 8  # from 6 m to about 150 m
    assert np.all(np.abs(counts - n * p)[tested] < 5 * sd[tested]), (counts, n * p)
    assert np.all(np.diff(counts[tested]) < 0)  # fewer and fewer
    assert counts[centres > 300.0].sum() <= 5  # expected 1e-6 beyond the critical range
    assert significant_height(np.array([0.3, 0.4])) == pytest.approx(2.0 * math.sqrt(2) * 0.5)


def test_it_is_the_same_for_a_seed_whatever_the_batches():
    spec = RadarSpec(sea_clutter=2.0, max_range=400.0)
    world = World((_pile(150.0, -100.0),))
    whole = _scan(spec, world, height=1.5, first=2000, count=200)  # over a revolution's end
    parts = [_scan(spec, world, height=1.5, first=f, count=c)
             for f, c in ((2000, 48), (2048, 1), (2049, 151))]
    for name in ("azimuth", "range", "intensity"):
        np.testing.assert_array_equal(getattr(whole, name),
                                      np.concatenate([getattr(p, name) for p in parts]))
    other = measure_radar(RadarSpec(sea_clutter=2.0, max_range=400.0,
                                    position=np.array([0.0, 0.0, 3.0])),
                          stream_key(1, "boat", "radar"), 2000, 200, _boat(), np.zeros(3),
                          world, None, 1.5)
    assert not np.array_equal(other.range, whole.range)  # another seed's clutter


def test_the_spokes_due_are_those_swept_by_then():
    spec = RadarSpec()  # 24 rpm, 2048 spokes: 819.2 a second
    assert spokes_due(spec, 0, 0.0) == (0, 1)  # spoke 0 at t = 0
    assert spokes_due(spec, 1, 1.0) == (1, 819)
    assert spokes_due(spec, 820, 1.0) == (820, 0)
    assert spokes_due(RadarSpec(rpm=60.0, spokes=100), 0, 1.0) == (0, 101)


def test_a_scenarios_radar_is_read_with_its_keys_and_bad_ones_refused():
    from boat_dynamics.physics.scenario import ScenarioError, parse_scenario

    spec, = parse_scenario({"boats": [{"sensors": [{
        "type": "radar", "rpm": 48, "spokes": 1024, "beamwidth_deg": 5.2,
        "range_resolution": 6, "max_range": 926, "min_range": 10, "detection_range": 5000,
        "sea_clutter": 0.0}]}]}).boats[0].sensors
    assert isinstance(spec, RadarSpec)
    assert (spec.rpm, spec.spokes, spec.range_resolution, spec.max_range, spec.min_range,
            spec.detection_range, spec.sea_clutter) == (48, 1024, 6, 926, 10, 5000, 0)
    assert spec.beamwidth == pytest.approx(math.radians(5.2))
    assert spec.bins == 154
    for bad, key in (({"rpm": 0}, "rpm"), ({"spokes": 4}, "spokes"),
                     ({"beamwidth_deg": 90}, "beamwidth_deg"),
                     ({"range_resolution": -1}, "range_resolution"),
                     ({"range_resolution": 0.1, "max_range": 12000}, "range_resolution"),
                     ({"min_range": 50, "max_range": 40}, "max_range"),
                     ({"detection_range": 0}, "detection_range"),
                     ({"sea_clutter": -1}, "sea_clutter"), ({"noise": {"range_sigma": 1}},
                                                            "noise.range_sigma")):
        with pytest.raises(ScenarioError) as err:
            parse_scenario({"boats": [{"sensors": [{"type": "radar", **bad}]}]})
        assert err.value.key == f"boats[0].sensors[0].{key}"
    with pytest.raises(ScenarioError, match="only for a radar"):
        parse_scenario({"boats": [{"sensors": [{"type": "lidar", "spokes": 4}]}]})
