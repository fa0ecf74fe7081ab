"""`simulation.fleet_state: true`: every boat's odometry in one boat_msgs/FleetState message.

Recorded runs in --fast mode, read back: counted in messages (simulation time).
"""

import pytest
import yaml

from boat_dynamics.tools.bags import read_bag

BOATS = ("alpha", "bravo", "charlie")


def _scenario(tmp_path):
    path = tmp_path / "three.yaml"
    path.write_text(yaml.safe_dump({"simulation": {"fleet_state": True}, "boats": [
        {"name": name, "initial_pose": {"position": [15.0 * i, 0.0, 0.0], "yaw_deg": 30 * i},
         "commands": [{"t": 0.0, "thrust": 0.5 * i, "rudder": 0.1}]}
        for i, name in enumerate(BOATS)]}))
    return path


def _pose_twist(odom):
    p, q = odom.pose.pose.position, odom.pose.pose.orientation
    v, w = odom.twist.twist.linear, odom.twist.twist.angular
    return (p.x, p.y, p.z, q.x, q.y, q.z, q.w), (v.x, v.y, v.z, w.x, w.y, w.z)


@pytest.mark.parametrize("processes", [[], ["--shards", "2"]], ids=["one process", "2 shards"])
def test_the_fleet_message_is_every_boats_odometry_at_its_stamp(boatsim, tmp_path, processes):
    bag = tmp_path / "bag"
    sim = boatsim("run", str(_scenario(tmp_path)), "--fast", "--duration", "1", "--record",
                  str(bag), *processes)
    assert sim.wait(timeout=120) == 0, sim.output()
    topics = ["/boatsim/fleet_state", *(f"/{b}/odom" for b in BOATS)]
    msgs = read_bag(bag, topics)
    odom = {(b, stamp): m for b in BOATS for stamp, m in msgs[f"/{b}/odom"]}
    seen: dict[int, list[str]] = {}
    for stamp, fleet in msgs["/boatsim/fleet_state"]:
        assert fleet.header.frame_id == "world"
        assert len(fleet.names) == len(fleet.poses) == len(fleet.twists) >= 1
        seen.setdefault(stamp, []).extend(fleet.names)
        for name, pose, twist in zip(fleet.names, fleet.poses, fleet.twists, strict=True):
            p, q, v, w = pose.position, pose.orientation, twist.linear, twist.angular
            assert ((p.x, p.y, p.z, q.x, q.y, q.z, q.w), (v.x, v.y, v.z, w.x, w.y, w.z)) == (
                _pose_twist(odom[(name, stamp)]))  # bit for bit
    assert len(seen) == 51  # 0 .. 1 s at 50 Hz
    assert all(sorted(names) == list(BOATS) for names in seen.values())  # each boat once
    shares = {len(f.names) for _, f in msgs["/boatsim/fleet_state"]}
    assert shares == ({3} if not processes else {1, 2})  # a shard publishes its own boats
