"""Which subscribers of /boatsim/lockstep a replay takes for a lockstep simulation, and
which of them it waits for on /boatsim/lockstep_ready before the first command."""

import pytest

from boat_dynamics.tools.replay import follows_lockstep, parse_ready, unannounced
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


def test_a_ready_message_names_the_node_then_its_topics():
    assert parse_ready("boat_dynamics_shard_1 /b/cmd_rudder /b/cmd_thrust") == (
        "boat_dynamics_shard_1", {"/b/cmd_rudder", "/b/cmd_thrust"})
    assert parse_ready("boat_dynamics") == ("boat_dynamics", set())


def test_the_replayer_waits_for_every_dynamics_subscriber_of_each_topic():
    subscribers = {"/a/cmd_thrust": {"boat_dynamics_shard_0", "rosbag2_recorder"},
                   "/b/cmd_thrust": {"boat_dynamics_shard_1"},
                   "/b/cmd_rudder": {"boat_dynamics_shard_1", "probe"}}
    assert unannounced(subscribers, {}) == [
        ("boat_dynamics_shard_0", "/a/cmd_thrust"), ("boat_dynamics_shard_1", "/b/cmd_rudder"),
        ("boat_dynamics_shard_1", "/b/cmd_thrust")]  # not the recorder, not the probe
    ready = {"boat_dynamics_shard_0": {"/a/cmd_thrust"},
             "boat_dynamics_shard_1": {"/b/cmd_thrust"}}
    assert unannounced(subscribers, ready) == [("boat_dynamics_shard_1", "/b/cmd_rudder")]
    ready["boat_dynamics_shard_1"].add("/b/cmd_rudder")
    assert unannounced(subscribers, ready) == []
    # a node's announcement of another topic does not stand for this one
    assert unannounced({"/cmd_thrust": {"boat_dynamics"}},
                       {"boat_dynamics": {"/cmd_rudder"}}) == [("boat_dynamics", "/cmd_thrust")]
