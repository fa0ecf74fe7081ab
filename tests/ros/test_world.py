"""The world over ROS 2: the obstacles drawn once (latched), a boat's contact events and push."""

import math

import numpy as np
import pytest
import yaml
from support import cli_run, rrd_entities

from boat_dynamics.tools.bags import read_bag

#: A lone boat (root namespace) at full thrust toward a pier 6 m ahead of its bow, in calm
#: water; a piling off to the side that it never touches.
PIER = {"name": "pier", "type": "polygon", "top": 1.5,
        "points": [[8.0, -10.0], [9.0, -10.0], [9.0, 10.0], [8.0, 10.0]]}
WORLD = {"simulation": {"duration": 8.0},
         "world": {"obstacles": [PIER, {"name": "pile", "type": "cylinder",
                                        "center": [0.0, 15.0], "radius": 0.4}]},
         "boats": [{"commands": [{"t": 0.0, "thrust": 1.0, "rudder": 0.0}]}]}


def test_a_boat_driven_into_a_pier_reports_the_contact_and_the_world_is_drawn(boatsim, tmp_path):
    path, bag = tmp_path / "pier.yaml", tmp_path / "bag"
    path.write_text(yaml.safe_dump(WORLD))
    sim = boatsim("run", str(path), "--fast", "--record", str(bag))
    assert sim.wait(timeout=120) == 0, sim.output()
    msgs = read_bag(bag, ["/world/markers", "/collision", "/wrench/collision", "/odom"])
    (_, markers), = msgs["/world/markers"]  # once, latched
    kinds = sorted((m.ns, m.id, m.type) for m in markers.markers)
    assert kinds == [("obstacles", 0, 11), ("obstacles", 1, 3), ("obstacles", 100_000, 4)]
    walls = next(m for m in markers.markers if m.type == 11)  # TRIANGLE_LIST: 4 walls x 6
    assert len(walls.points) == 24 and walls.header.frame_id == "world"
    assert max(p.z for p in walls.points) == 1.5
    events = [m for _, m in msgs["/collision"]]
    assert events, "no contact event"
    first = events[0]
    assert (first.other, first.touching, first.boat) == ("pier", True, "")
    assert first.header.frame_id == "world"
    assert first.normal.x == pytest.approx(-1.0) and first.approach_speed > 0.5
    assert 8.0 <= first.point.x < 8.2
    # a contact that begins ends before the next begins, with the same obstacle
    assert [e.touching for e in events] == [k % 2 == 0 for k in range(len(events))]
    assert {e.other for e in events} == {"pier"}
    pushes = np.array([m.wrench.force.x for _, m in msgs["/wrench/collision"]])
    assert pushes.min() < -1000.0 and np.all(pushes <= 1e-9)  # back, never forward
    # the boat stays out of the pier: its reference point (the hull's middle) 2 m behind
    # the bow, never past x = 8 - 2 + 0.2
    assert max(m.pose.pose.position.x for _, m in msgs["/odom"]) < 6.2
    # and `boatsim view` draws the obstacles from the bag
    out = cli_run("view", str(bag), "--save", str(tmp_path / "v.rrd"))
    assert out.returncode == 0, out.stderr
    drawn = rrd_entities(tmp_path / "v.rrd")
    assert {"/world/obstacles/obstacles/0", "/world/obstacles/obstacles/1",
            "/world/obstacles/obstacles/100000"} <= drawn, drawn


def test_two_boats_that_meet_report_each_other(boatsim, tmp_path):
    # Bow to bow, 4 m apart, both at full thrust: each reports the other by name. Their
    # event topics made on subscription (as a large fleet's): the bag has them all the same.
    path, bag = tmp_path / "two.yaml", tmp_path / "bag"
    thrust = [{"t": 0.0, "thrust": 1.0, "rudder": 0.0}]
    path.write_text(yaml.safe_dump({
        "simulation": {"duration": 6.0, "wrench_topics": "on_subscription"},
        "boats": [{"name": "a", "commands": thrust},
                  {"name": "b", "commands": thrust,
                   "initial_pose": {"position": [8.0, 0.0, 0.0], "yaw_deg": 180.0}}]}))
    sim = boatsim("run", str(path), "--fast", "--record", str(bag))
    assert sim.wait(timeout=120) == 0, sim.output()
    msgs = read_bag(bag, ["/a/collision", "/b/collision", "/a/odom", "/b/odom"])
    a, b = ([m for _, m in msgs[f"/{n}/collision"]] for n in ("a", "b"))
    assert a and b, "no contact event"
    assert (a[0].boat, a[0].other, a[0].touching) == ("a", "b", True)
    assert (b[0].boat, b[0].other, b[0].touching) == ("b", "a", True)
    assert a[0].header.stamp == b[0].header.stamp
    assert a[0].normal.x == pytest.approx(-1.0, abs=0.05)  # a is pushed back, b forward
    assert b[0].normal.x == pytest.approx(1.0, abs=0.05)
    # their reference points (the hulls' middles, 4 m long) never closer than 3.8 m
    gap = [mb.pose.pose.position.x - ma.pose.pose.position.x
           for (_, ma), (_, mb) in zip(msgs["/a/odom"], msgs["/b/odom"], strict=False)]
    assert min(gap) > 3.8


def test_a_lidar_sees_the_pier_and_a_scanner_and_a_radar_the_other_boat(boatsim, tmp_path):
    # A 3-D lidar (4 rings) and a 2-D scanner 0.3 m above the hull's middle of a boat at
    # rest (its deck is at 0.5 m), its bow 6 m from the pier's face (x = 8): the scanner's
    # ray ahead reads 8 m; another boat 10 m to port, its side 9 m away, is its ray to port.
    # A radar turning once a second (1 deg spokes, 0.5 m bins) at (0.25, 0.25): the pier
    # ahead at 7.75 m, the other boat to port at 8.75 m, each in the middle of its bin.
    # A buoy (0.4 m round) 6 m to starboard: the scanner's ray that way reads 5.6 m; an AIS
    # receiver hears the other boat and not the buoy; the buoy has its odom and its line's
    # wrench/mooring, and no command topics.
    path, bag = tmp_path / "lidar.yaml", tmp_path / "bag"
    path.write_text(yaml.safe_dump({
        "simulation": {"duration": 1.0}, "ocean": {},
        "world": {"obstacles": [PIER], "buoys": [{"name": "buoy", "position": [0.0, -6.0]}]},
        "boats": [{"name": "a", "sensors": [
                      {"type": "lidar", "name": "scanner", "samples": 4,
                       "position": [0.0, 0.0, 0.3], "noise": {"range_sigma": 0.0}},
                      {"type": "lidar", "name": "lidar", "samples": 90, "rings": 4,
                       "vertical_fov_deg": 10.0, "position": [0.0, 0.0, 0.3]},
                      {"type": "radar", "rpm": 60.0, "spokes": 360, "range_resolution": 0.5,
                       "min_range": 2.0, "max_range": 50.0, "sea_clutter": 0.0,
                       "position": [0.25, 0.25, 1.0]},
                      {"type": "ais"}]},
                  {"name": "b", "initial_pose": {"position": [0.0, 10.0, 0.0]}}]}))
    sim = boatsim("run", str(path), "--fast", "--record", str(bag))
    assert sim.wait(timeout=120) == 0, sim.output()
    msgs = read_bag(bag, ["/a/scanner/scan", "/a/lidar/points", "/a/radar/points",
                          "/a/ais/reports", "/buoy/odom", "/buoy/wrench/mooring"])
    scans = [m for _, m in msgs["/a/scanner/scan"]]
    assert len(scans) == 10  # 10 Hz over 1 s (a reading needs a step before it)
    scan = scans[-1]
    assert scan.header.frame_id == "a/scanner_link"
    # azimuths -180, -90, 0, 90 deg: behind open water, to starboard the buoy; ahead the
    # pier, to port the other boat's side (1 m off its middle); the boats ride a few cm
    assert math.isinf(scan.ranges[0])
    assert scan.ranges[1] == pytest.approx(5.6, abs=0.05)
    assert scan.ranges[2] == pytest.approx(8.0, abs=0.05)
    assert scan.ranges[3] == pytest.approx(9.0, abs=0.05)
    cloud = msgs["/a/lidar/points"][-1][1]
    assert cloud.width > 10 and cloud.point_step == 12
    points = np.frombuffer(bytes(cloud.data), dtype=np.float32).reshape(-1, 3)
    ahead = points[np.abs(points[:, 1]) < 0.5]
    assert np.all(np.abs(ahead[:, 0] - 8.0) < 0.3)  # the pier's face, ahead
    # the radar: a revolution in 10 messages of 36 spokes, in its frame (x, y, z, intensity)
    clouds = [m for _, m in msgs["/a/radar/points"]]
    assert len(clouds) == 10 and clouds[0].header.frame_id == "a/radar_link"
    assert [f.name for f in clouds[0].fields] == ["x", "y", "z", "intensity"]
    radar = np.concatenate([np.frombuffer(bytes(c.data), dtype=np.float32).reshape(-1, 4)
                            for c in clouds])
    assert np.all(radar[:, 3] >= 1.0)
    ahead = radar[(np.abs(radar[:, 1]) < 0.2) & (radar[:, 0] > 0.0)]
    assert len(ahead) and np.all(np.abs(ahead[:, 0] - 7.75) < 0.1), ahead
    port = radar[(np.abs(radar[:, 0]) < 0.2) & (radar[:, 1] > 0.0)]
    assert len(port) and np.all(np.abs(port[:, 1] - 8.75) < 0.1), port
    assert not np.any((radar[:, 0] < -1.0) & (np.abs(radar[:, 1]) < 5.0))  # open water aft
    assert {m.name for _, m in msgs["/a/ais/reports"]} == {"b"}
    assert msgs["/buoy/odom"] and msgs["/buoy/wrench/mooring"]
    assert "buoy buoy: moored by a 9.7 m line to an anchor at [0.0, -6.0, -10.0] m; no " \
        "command topics" in sim.output(), sim.output()
