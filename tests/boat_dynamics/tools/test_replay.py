"""Which subscribers of /boatsim/lockstep a replay takes for a lockstep simulation."""

import pytest

from boat_dynamics.tools.replay import follows_lockstep
from boat_msgs_py import names


@pytest.mark.parametrize("node_name", [
    names.DYNAMICS_NODE,                      # one process
    f"{names.DYNAMICS_NODE}_alpha",           # --processes: a boat's own process
    f"{names.DYNAMICS_NODE}_shard_1",         # --shards
    names.CLOCK_NODE,                         # the clock owner of a run over processes
])
def test_boatsims_own_nodes_follow_lockstep(node_name):
    assert follows_lockstep(node_name)


@pytest.mark.parametrize("node_name", [
    names.RECORDER_NODE,  # boatsim record
    "rosbag2_recorder",   # ros2 bag record -a
    "probe", "", names.UNKNOWN_NODE, "my_boat_dynamics_monitor",
])
def test_listeners_do_not_follow_lockstep(node_name):
    # a real-time run replayed beside one of them goes by the wall clock, not by a /clock
    # that never comes
    assert not follows_lockstep(node_name)
