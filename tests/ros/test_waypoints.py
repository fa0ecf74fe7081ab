"""examples/waypoints.py closes the loop on the Otter-like catamaran from its sensors only.

Real time: the guidance reacts to sensor messages as an autonomy stack would. The path is
judged on ground truth (the bag's /otter/odom) in simulation time.
"""

import math
import re
import subprocess
import sys
from itertools import pairwise
from pathlib import Path

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.scenario import load_scenario
from boat_dynamics.physics.sensors import geodetic_to_enu

ROOT = Path(__file__).resolve().parents[2]
LEGS = np.array([[15.0, 0.0], [15.0, 15.0], [0.0, 15.0]])


def _distance_to_path(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    """(N,) m, each point's distance to the polyline ``path`` (K, 2)."""
    out = np.full(points.shape[0], np.inf)
    for a, b in pairwise(path):
        ab = b - a
        s = np.clip((points - a) @ ab / (ab @ ab), 0.0, 1.0)
        out = np.minimum(out, np.hypot(*(points - a - s[:, None] * ab).T))
    return out


def test_the_waypoint_example_follows_its_legs_from_gnss_and_imu(boatsim, tmp_path):
    from rosbags.highlevel import AnyReader

    scenario = load_scenario(ROOT / "scenarios" / "otter.yaml")
    bag = tmp_path / "bag"
    sim = boatsim("run", "scenarios/otter.yaml", "--record", str(bag))
    guide = subprocess.run([sys.executable, "examples/waypoints.py", "--ns", "otter",
                            "--timeout", "90"], cwd=ROOT, capture_output=True, text=True,
                           timeout=180)
    assert sim.stop() == 0
    log = guide.stdout + guide.stderr
    assert guide.returncode == 0, log
    assert "reached all 3 waypoints" in log
    elapsed = float(re.search(r"reached all 3 waypoints in ([0-9.]+) s", log).group(1))
    lat, lon, alt = (float(v) for v in re.search(
        r"origin ([-0-9.]+), ([-0-9.]+), ([-0-9.]+)", log).groups())
    # the guidance's frame: east-north at its origin (a mean of fixes), as the world sees it
    origin = geodetic_to_enu(scenario.simulation.datum, math.radians(lat), math.radians(lon),
                             alt)[:2]
    antenna = scenario.boats[0].sensors[1].position
    track = []
    with AnyReader([bag]) as reader:
        for conn, _, raw in reader.messages(
                [c for c in reader.connections if c.topic == "/otter/odom"]):
            pose = reader.deserialize(raw, conn.msgtype).pose.pose
            q = np.array([pose.orientation.x, pose.orientation.y, pose.orientation.z,
                          pose.orientation.w])
            p = np.array([pose.position.x, pose.position.y, pose.position.z])
            track.append((p + rotation_matrix(q) @ antenna)[:2])
    track = np.array(track)
    goals = origin + LEGS
    # the guidance stops once less than 2 m of the last leg remain (by its GNSS): the track
    # up to its closest approach to the last waypoint is the path it steered
    closest = int(np.argmin(np.hypot(*(track - goals[-1]).T)))
    underway = track[:closest + 1]
    error = _distance_to_path(underway, np.vstack([underway[0], goals]))
    rms = math.sqrt(float(np.mean(error**2)))
    result = (f"{elapsed:.1f} s, closest to the last waypoint "
              f"{np.hypot(*(track[closest] - goals[-1])):.2f} m, path error max "
              f"{error.max():.2f} m, RMS {rms:.2f} m")
    print(f"waypoints: {result}")
    # measured: 37-39 s, 2.5-2.8 m largest (the overshoot of the first corner), RMS
    # 1.2-1.3 m, with the GNSS's 0.6 m noise and 0.3 m correlated error. With both cores
    # busy the guidance, a process reacting in real time, worked through queues of
    # old sensor readings: 83 s, then twice timed out at 90 s. It now takes the latest
    # reading only: 36.9-39.0 s loaded, 2.7-3.0 m largest, RMS 1.2-1.4 m (three runs). The
    # V-pontoon Otter with its coefficients: 37.1-37.3 s, 2.09 m, RMS 0.99-1.04 m.
    assert np.hypot(*(track[closest] - goals[-1])) < 4.0, result
    assert elapsed < 60.0, result
    assert error.max() < 4.0, result
    assert rms < 2.0, result
