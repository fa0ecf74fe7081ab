"""The scanner: its rays' pattern, ranges against closed forms, roll, the sea, its noise."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_multiply, rotation_matrix
from boat_dynamics.physics.sensors.lidar import LidarSpec, lidar_directions, measure_lidar
from boat_dynamics.physics.sensors.noise import stream_key
from boat_dynamics.physics.world.obstacles import Prism, World

WALL = World((Prism.make("wall", [[10.0, -50.0], [11.0, -50.0], [11.0, 50.0], [10.0, 50.0]],
                         3.0),))
KEY = stream_key(0, "boat", "lidar")


def _level(yaw=0.0, roll=0.0):
    """(3, 3) body to world of a boat at ``roll`` then ``yaw`` (rad)."""
    qr = np.array([math.sin(roll / 2), 0.0, 0.0, math.cos(roll / 2)])
    qy = np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])
    return rotation_matrix(quat_multiply(qy, qr)[None])[0]


def _flat(xy):
    return np.zeros(xy.shape[0])


def test_a_full_circle_has_no_repeated_ray_and_a_sector_ends_on_its_edges():
    full = LidarSpec(samples=8)
    np.testing.assert_allclose(full.azimuths, -math.pi + math.pi / 4 * np.arange(8))
    sector = LidarSpec(samples=5, horizontal_fov=math.radians(90))
    np.testing.assert_allclose(sector.azimuths, np.radians([-45, -22.5, 0, 22.5, 45]))
    d = lidar_directions(LidarSpec(samples=4, rings=3, vertical_fov=math.radians(30)))
    assert d.shape == (12, 3)
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0)
    np.testing.assert_allclose(np.degrees(np.arcsin(d[::4, 2])), [-15, 0, 15])


def test_a_level_scanner_reads_a_wall_at_its_distance_over_the_cosine():
    spec = LidarSpec(samples=5, horizontal_fov=math.radians(60), range_sigma=0.0,
                     position=np.array([0.0, 0.0, 1.0]))
    r = measure_lidar(spec, KEY, 0, _level(), np.zeros(3), WALL, None, _flat)
    np.testing.assert_allclose(r, 10.0 / np.cos(spec.azimuths), rtol=1e-12)
    turned = measure_lidar(spec, KEY, 0, _level(yaw=math.pi), np.zeros(3), WALL, None, _flat)
    assert np.all(np.isinf(turned))  # facing away: open water, level rays never reach it


def test_a_rolled_boat_sweeps_the_sea_and_over_the_wall():
    # Rolled 20 deg to starboard: the scanner's ray to starboard (-90 deg) points 20 deg down
    # and meets flat water at h / sin 20 (h: the sensor's height, rolled with the hull); the
    # ray ahead still meets the wall at 10 m.
    spec = LidarSpec(samples=4, range_sigma=0.0, position=np.array([0.0, 0.0, 2.0]))
    rot = _level(roll=math.radians(20))
    r = measure_lidar(spec, KEY, 0, rot, np.zeros(3), WALL, None, _flat)
    # azimuths -180, -90, 0, 90 deg
    h = 2.0 * math.cos(math.radians(20))
    assert math.isinf(r[1])  # the sea returns nothing by default
    assert r[2] == pytest.approx(10.0, rel=1e-9)
    clutter = LidarSpec(samples=4, range_sigma=0.0, position=np.array([0.0, 0.0, 2.0]),
                        sea="clutter", clutter_probability=1.0)
    r = measure_lidar(clutter, KEY, 0, rot, np.zeros(3), WALL, None, _flat)
    assert r[1] == pytest.approx(h / math.sin(math.radians(20)), rel=1e-9)


def test_its_noise_is_white_of_its_sigma_and_the_same_for_a_seed():
    spec = LidarSpec(samples=720, horizontal_fov=math.radians(10), range_sigma=0.05)
    scans = np.array([measure_lidar(spec, KEY, k, _level(), np.zeros(3), WALL, None, _flat)
                      for k in range(20)])
    errors = scans - 10.0 / np.cos(spec.azimuths)
    assert abs(errors.mean()) < 4 * 0.05 / math.sqrt(errors.size)  # 14,400 draws
    assert errors.std() == pytest.approx(0.05, rel=0.03)
    again = measure_lidar(spec, KEY, 3, _level(), np.zeros(3), WALL, None, _flat)
    np.testing.assert_array_equal(again, scans[3])


def test_out_of_its_ranges_it_reads_nothing():
    near = LidarSpec(samples=3, horizontal_fov=0.2, range_sigma=0.0, min_range=10.5)
    assert np.all(np.isinf(measure_lidar(near, KEY, 0, _level(), np.zeros(3), WALL, None,
                                         _flat)[1:2]))
    far = LidarSpec(samples=3, horizontal_fov=0.2, range_sigma=0.0, max_range=9.0)
    assert np.all(np.isinf(measure_lidar(far, KEY, 0, _level(), np.zeros(3), WALL, None,
                                         _flat)))


def test_a_scenarios_lidar_is_read_with_its_keys_and_bad_ones_refused():
    from boat_dynamics.physics.scenario import ScenarioError, parse_scenario

    spec, = parse_scenario({"boats": [{"sensors": [{
        "type": "lidar", "rings": 8, "samples": 720, "horizontal_fov_deg": 270,
        "vertical_fov_deg": 20, "max_range": 50, "sea": "clutter",
        "clutter_probability": 0.1, "noise": {"range_sigma": 0.03}}]}]}).boats[0].sensors
    assert isinstance(spec, LidarSpec)
    assert (spec.rings, spec.samples, spec.sea, spec.max_range) == (8, 720, "clutter", 50.0)
    assert spec.horizontal_fov == pytest.approx(math.radians(270))
    assert spec.vertical_fov == pytest.approx(math.radians(20))
    for bad, key in (({"rings": 0}, "rings"), ({"samples": 1000, "rings": 256}, "samples"),
                     ({"sea": "foam"}, "sea"), ({"min_range": 5, "max_range": 2}, "max_range"),
                     ({"horizontal_fov_deg": 400}, "horizontal_fov_deg")):
        with pytest.raises(ScenarioError) as err:
            parse_scenario({"boats": [{"sensors": [{"type": "lidar", **bad}]}]})
        assert err.value.key == f"boats[0].sensors[0].{key}"
    with pytest.raises(ScenarioError, match="only for a lidar"):
        parse_scenario({"boats": [{"sensors": [{"type": "imu", "rings": 4}]}]})
