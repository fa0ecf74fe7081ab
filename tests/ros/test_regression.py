"""record, compare, plot and teleop: the regression-testing tools, end to end."""

import math
import os
import pty
import signal
import struct
import subprocess
import sys
import termios
import time

import numpy as np
import pytest
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from std_msgs.msg import Float64
from support import cli_run

from boat_dynamics.tools.bags import compare_bags, read_bag, read_bag_topics

SCRIPTED = """
ocean: {components: [{amplitude: 0.3, wavelength: 25.0, steepness: 0.5}]}
boats: [{commands: [{t: 0, thrust: 1.0, rudder: 0.0}, {t: 2, thrust: 1.0, rudder: 0.3}]}]
"""


@pytest.fixture(scope="module")
def two_runs(tmp_path_factory):
    d = tmp_path_factory.mktemp("runs")
    (d / "s.yaml").write_text(SCRIPTED)
    for name in ("a", "b"):
        out = cli_run("run", str(d / "s.yaml"), "--fast", "--duration", "4", "--record",
                   str(d / name))
        assert out.returncode == 0, out.stderr
    return d


def _perturbed_copy(src, dst, topic="/odom", index=50, dx=0.01):
    """Copy one topic of a bag, moving message ``index`` by dx in x."""
    store = get_typestore(Stores.ROS2_JAZZY)
    with AnyReader([src]) as reader, Writer(dst, version=9,
                                           storage_plugin=StoragePlugin.MCAP) as writer:
        conn_in = next(c for c in reader.connections if c.topic == topic)
        conn_out = writer.add_connection(topic, conn_in.msgtype, typestore=store)
        for i, (_, stamp, raw) in enumerate(reader.messages(connections=[conn_in])):
            msg = reader.deserialize(raw, conn_in.msgtype)
            if i == index:
                msg.pose.pose.position.x += dx
                when = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
            writer.write(conn_out, stamp, store.serialize_cdr(msg, conn_in.msgtype))
    return when


def test_same_scenario_same_commands_give_identical_bags(two_runs):
    result = compare_bags(two_runs / "a", two_runs / "b")
    assert result.ok, result.report()
    topics = {t.topic for t in result.topics}
    assert {"/odom", "/wrench/total", "/ocean/wave_field", "/diagnostics"} <= topics
    assert "/rosout" not in topics
    odom = next(t for t in result.topics if t.topic == "/odom")
    assert odom.matched == 201 and all(f.max_abs == 0.0 for f in odom.fields)
    assert cli_run("compare", str(two_runs / "a"), str(two_runs / "b")).returncode == 0


def test_compare_detects_a_perturbation_and_names_the_field(two_runs, tmp_path):
    when = _perturbed_copy(two_runs / "a", tmp_path / "p")
    result = compare_bags(two_runs / "a", tmp_path / "p", topics=["/odom"])
    assert not result.ok
    worst = result.topics[0].fields[0]
    assert worst.field == "pose.pose.position.x"
    assert worst.max_abs == pytest.approx(0.01, rel=1e-9)
    assert worst.stamp_ns / 1e9 == pytest.approx(when)
    out = cli_run("compare", str(two_runs / "a"), str(tmp_path / "p"), "--topics", "/odom")
    assert out.returncode == 1
    assert "pose.pose.position.x: max |a - b| = 0.01 at t = " in out.stdout
    ok = cli_run("compare", str(two_runs / "a"), str(tmp_path / "p"), "--topics", "/odom",
              "--tol", "*.position.*=0.02")
    assert ok.returncode == 0, ok.stdout


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["compare", "/nonexistent/bag", "{a}"], "no such bag"),
        (["compare", "{a}", "{a}", "--topics", "/nope"], "topic(s) not in the bag: /nope"),
        (["compare", "{corrupt}", "{a}"], "not a readable rosbag2 bag"),
        (["compare", "{a}", "{a}", "--tol", "x=abc"], "expected FIELD=VALUE"),
        (["plot", "/nonexistent/bag"], "no such bag"),
    ],
)
def test_bad_inputs_exit_2_with_one_line(two_runs, tmp_path, args, fragment):
    corrupt = tmp_path / "corrupt"
    corrupt.mkdir()
    (corrupt / "metadata.yaml").write_text("this: [is not a bag\n")
    args = [a.format(a=two_runs / "a", corrupt=corrupt) for a in args]
    out = cli_run(*args)
    assert out.returncode == 2
    assert fragment in out.stderr and "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1


def test_plot_writes_a_png_of_the_expected_size(two_runs, tmp_path):
    target = tmp_path / "run.png"
    out = cli_run("plot", str(two_runs / "a"), "-o", str(target))
    assert out.returncode == 0, out.stderr
    data = target.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
    width, height = struct.unpack(">II", data[16:24])
    assert (width, height) == (1200, 1500)  # 4 x 2 panels for the one boat


def test_standalone_record_picks_up_topics_including_latched_ones(boatsim, tmp_path):
    bag = tmp_path / "rec"
    rec = boatsim("record", "/odom", "/ocean/wave_field", "-o", str(bag), name="record")
    time.sleep(2.0)
    sim = boatsim("run", "--duration", "6")
    assert sim.wait(timeout=60) == 0
    time.sleep(1.0)
    assert rec.stop(signal.SIGINT) == 0
    out = rec.output()
    assert "wrote" in out and "Traceback" not in out
    with AnyReader([bag]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        odom = [c for c in reader.connections if c.topic == "/odom"]
        stamps = [reader.deserialize(raw, "nav_msgs/msg/Odometry").header.stamp
                  for _, _, raw in reader.messages(connections=odom)]
        field = [c for c in reader.connections if c.topic == "/ocean/wave_field"]
        zero = next(reader.deserialize(raw, c.msgtype).header.stamp  # simulation time 0
                    for c, _, raw in reader.messages(connections=field))
    assert set(counts) == {"/odom", "/ocean/wave_field"}
    assert counts["/ocean/wave_field"] == 1  # latched: published before the recorder joined
    # what is published before DDS has matched the new publisher cannot be recorded (about a
    # second here, 2.3 s with both cores busy: 186 of 301); from the first message on, nothing
    # is lost: 50 Hz without a gap, to the run's last odom at t = 6 s
    t = [s.sec + s.nanosec * 1e-9 for s in stamps]
    assert len(t) >= 100  # of 301: at least the last 2 s
    assert float(np.diff(t).max()) == pytest.approx(0.02, abs=1e-6)
    assert t[-1] - t[0] == pytest.approx(0.02 * (len(t) - 1), abs=1e-6)
    assert t[-1] - (zero.sec + zero.nanosec * 1e-9) == pytest.approx(6.0, abs=1e-6)


def test_a_stopped_recorder_keeps_every_message_it_had_received(boatsim, probe, tmp_path):
    from rclpy.duration import Duration
    from rclpy.qos import QoSProfile, ReliabilityPolicy

    bag = tmp_path / "burst"
    rec = boatsim("record", "/burst", "-o", str(bag), name="record")
    pub = probe.node.create_publisher(
        Float64, "/burst", QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE))
    probe.spin_until(lambda: pub.get_subscription_count() > 0, 30.0, "the recorder")
    for i in range(1000):  # the recorder's depth: a full queue is acknowledged at once
        pub.publish(Float64(data=float(i)))
    # acknowledged: each is in the recorder's DDS queue; a stop right now must not lose one
    # (before, the recorder ended its loop with the burst still queued: it kept 98-315)
    assert pub.wait_for_all_acked(Duration(seconds=30))
    assert rec.stop(signal.SIGINT) == 0
    assert "wrote 1000 messages" in rec.output(), rec.output()
    values = [m.data for _, m in read_bag(bag, ["/burst"])["/burst"]]
    assert values == [float(i) for i in range(1000)]


def test_teleop_through_a_pty_sends_commands_and_restores_the_terminal(probe):
    thrusts, rudders = [], []
    probe.node.create_subscription(Float64, "/cmd_thrust", lambda m: thrusts.append(m.data), 10)
    probe.node.create_subscription(Float64, "/cmd_rudder", lambda m: rudders.append(m.data), 10)
    master, slave = pty.openpty()
    before = termios.tcgetattr(slave)
    proc = subprocess.Popen([sys.executable, "-m", "boat_dynamics", "teleop"], stdin=slave,
                            stdout=slave, stderr=slave, env=os.environ.copy(), close_fds=True)
    try:
        probe.spin_until(lambda: thrusts, 30.0, "teleop's first /cmd_thrust")
        os.write(master, b"www")
        probe.spin_until(lambda: thrusts and thrusts[-1] == pytest.approx(0.3), 10.0, "0.3")
        os.write(master, b"\x1b[D\x1b[D")  # left arrow twice: 0.1 rad to port
        probe.spin_until(lambda: rudders and rudders[-1] == pytest.approx(0.1), 10.0, "0.1")
        os.write(master, b"s")
        probe.spin_until(lambda: thrusts[-1] == pytest.approx(0.2), 10.0, "0.2")
        os.write(master, b" ")
        probe.spin_until(lambda: thrusts[-1] == 0.0 and rudders[-1] == 0.0, 10.0, "stop")
        os.write(master, b"q")
        assert proc.wait(timeout=15) == 0
        assert termios.tcgetattr(slave) == before
        screen = os.read(master, 65536).decode(errors="ignore")
        assert "throttle +0.30" in screen or "throttle" in screen
    finally:
        if proc.poll() is None:
            proc.kill()
        os.close(master)
        os.close(slave)


def _command_bag(path):
    """A bag with commands only: thrust and rudder at chosen simulation times."""
    store = get_typestore(Stores.ROS2_JAZZY)
    plan = [(0.0, "/cmd_thrust", 1.0), (0.0, "/cmd_rudder", 0.0), (0.8, "/cmd_thrust", 1.0),
            (1.0, "/cmd_rudder", 0.3), (1.6, "/cmd_thrust", 1.0), (2.37, "/cmd_thrust", -0.5),
            (2.4, "/cmd_rudder", -0.2), (3.1, "/cmd_thrust", 0.8)]
    Float64Msg = store.types["std_msgs/msg/Float64"]
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conns = {t: writer.add_connection(t, "std_msgs/msg/Float64", typestore=store)
                 for t in ("/cmd_thrust", "/cmd_rudder")}
        for t, topic, value in plan:
            writer.write(conns[topic], round(t * 1e9),
                         store.serialize_cdr(Float64Msg(data=value), "std_msgs/msg/Float64"))
    return plan


def test_two_lockstep_replays_give_identical_outputs(boatsim, tmp_path):
    plan = _command_bag(tmp_path / "commands")
    runs = []
    for name in ("a", "b"):
        sim = boatsim("run", "--fast", "--lockstep", "--duration", "4", "--record",
                      str(tmp_path / name), name=f"sim_{name}")
        out = cli_run("replay", str(tmp_path / "commands"), timeout=60)
        assert out.returncode == 0, out.stderr
        assert sim.wait(timeout=60) == 0
        runs.append(tmp_path / name)
    result = compare_bags(*runs)
    assert result.ok, result.report()
    by_topic = {t.topic: t for t in result.topics}
    assert by_topic["/cmd_thrust"].matched == 5 and by_topic["/cmd_rudder"].matched == 3
    # each command took effect at the first step at or after its time: the thrust of 2.37 s
    # shows in the wrench at 2.4 s (the next 10 Hz sample after the 2.37 s step boundary)
    with AnyReader([runs[0]]) as reader:
        conns = [c for c in reader.connections if c.topic in ("/cmd_thrust", "/wrench/thrust")]
        seen = {"/cmd_thrust": [], "/wrench/thrust": []}
        for conn, stamp, raw in reader.messages(connections=conns):
            seen[conn.topic].append((stamp, reader.deserialize(raw, conn.msgtype)))
    stamps = [s / 1e9 for s, _ in seen["/cmd_thrust"]]
    assert stamps == pytest.approx([t for t, topic, _ in plan if topic == "/cmd_thrust"],
                                   abs=1e-9)
    # the default boat's outboard turns with the rudder command: the thrust's signed size
    thrust_at = {round(s / 1e9, 3): math.copysign(math.hypot(m.wrench.force.x, m.wrench.force.y),
                                                  m.wrench.force.x)
                 for s, m in seen["/wrench/thrust"]}
    assert thrust_at[2.3] == pytest.approx(2000.0) and thrust_at[2.4] == pytest.approx(-1000.0)


def test_a_replay_against_a_real_time_run_follows_the_wall_clock(boatsim, probe, tmp_path):
    # a real-time run has no /boatsim/lockstep subscription: after a short wait for one the
    # replayer publishes on the wall clock, and the run receives every command. A node that
    # only listens to /boatsim/lockstep (here named as `ros2 bag record -a`'s) is no lockstep
    # simulation: the replayer took it for one and waited --timeout for its /clock, then failed.
    from std_msgs.msg import Float64MultiArray

    from boat_msgs_py import names
    from boat_msgs_py.qos import COMMAND_QOS

    probe.other_node("rosbag2_recorder").create_subscription(
        Float64MultiArray, names.LOCKSTEP, lambda m: None, COMMAND_QOS)
    _command_bag(tmp_path / "commands")
    sim = boatsim("run", "--record", str(tmp_path / "live"))
    out = cli_run("replay", str(tmp_path / "commands"), "--timeout", "30", timeout=60)
    assert out.returncode == 0, out.stderr
    assert "(wall clock x1)" in out.stderr and "replayed 8 commands" in out.stderr
    assert sim.stop() == 0
    with AnyReader([tmp_path / "live"]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections
                  if c.topic in ("/cmd_thrust", "/cmd_rudder")}
    assert counts == {"/cmd_thrust": 5, "/cmd_rudder": 3}


def _hold_at_grants(probe, replay, grants, clock, each_round=lambda: None) -> str:
    """A stand-in lockstep simulation: /clock at the last grant's time until the replayer
    exits (``each_round`` called every 20 ms); returns the replayer's stderr."""
    from rosgraph_msgs.msg import Clock

    from boat_msgs_py.convert import seconds_to_time

    t = 0.0
    while replay.poll() is None:  # the simulation holds at each grant's time
        each_round()
        if grants and grants[-1][0] < 1e17:
            t = max(t, grants[-1][0])
        clock.publish(Clock(clock=seconds_to_time(t)))
        probe.spin_for(0.02)
    return replay.stderr.read()


def test_a_lockstep_simulation_whose_clock_comes_late_is_replayed_in_lockstep(probe, tmp_path):
    # A stand-in for a loaded machine's `run --fast --lockstep`: it follows /boatsim/lockstep
    # at once but publishes /clock only after 3 s (wall). The replayer used to give /clock 2 s,
    # then went by the wall clock while the simulation waited at t = 0 for ever.
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import Float64MultiArray

    from boat_msgs_py import names
    from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS

    _command_bag(tmp_path / "commands")
    node, grants, received = probe.node, [], []
    # the replayer follows only boatsim's own nodes' lockstep subscriptions: named as one
    probe.other_node(names.DYNAMICS_NODE).create_subscription(
        Float64MultiArray, names.LOCKSTEP, lambda m: grants.append(tuple(m.data)), COMMAND_QOS)
    for topic in ("/cmd_thrust", "/cmd_rudder"):
        node.create_subscription(Float64, topic, received.append, COMMAND_QOS)
    clock = node.create_publisher(Clock, names.CLOCK, CLOCK_QOS)
    replay = subprocess.Popen([sys.executable, "-m", "boat_dynamics", "replay",
                               str(tmp_path / "commands")], stderr=subprocess.PIPE, text=True)
    try:
        probe.spin_until(lambda: node.count_publishers(names.LOCKSTEP) > 0, 30.0,
                         "the replayer")
        probe.spin_for(3.0)  # from when the replayer is there
        err = _hold_at_grants(probe, replay, grants, clock)
    finally:
        if replay.poll() is None:
            replay.kill()
    assert replay.returncode == 0, err
    assert "(lockstep with /clock)" in err and "replayed 8 commands" in err
    probe.spin_until(lambda: len(received) == 8, 10.0, "the 8 commands")


def test_a_replay_sends_no_command_before_the_simulation_has_matched_its_publishers(
        probe, tmp_path):
    # A stand-in lockstep simulation that matches the replayer late: it announces on
    # /boatsim/lockstep_ready only after 3 s (wall) and misses every grant until then. Before,
    # the replayer sent the t = 0 commands and its first grant once, as soon as it had seen
    # the subscriptions and /clock; a simulation that had not matched its publishers yet lost
    # them and waited at t = 0 for ever (with both cores busy, 1 loaded suite run in 3).
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import Float64MultiArray, String

    from boat_msgs_py import names
    from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS

    _command_bag(tmp_path / "commands")
    sim = probe.other_node(names.DYNAMICS_NODE)
    matched, grants, received, early = [False], [], [], []

    def on_command(msg):
        (received if matched[0] else early).append(msg.data)

    sim.create_subscription(Float64MultiArray, names.LOCKSTEP,
                            lambda m: matched[0] and grants.append(tuple(m.data)), COMMAND_QOS)
    for topic in ("/cmd_thrust", "/cmd_rudder"):
        sim.create_subscription(Float64, topic, on_command, COMMAND_QOS)
    clock = sim.create_publisher(Clock, names.CLOCK, CLOCK_QOS)
    ready = sim.create_publisher(String, names.LOCKSTEP_READY, COMMAND_QOS)
    replay = subprocess.Popen([sys.executable, "-m", "boat_dynamics", "replay",
                               str(tmp_path / "commands")], stderr=subprocess.PIPE, text=True)
    try:
        probe.spin_until(lambda: sim.count_publishers(names.LOCKSTEP) > 0, 30.0, "the replayer")
        start = time.monotonic()

        def match_late():
            matched[0] = matched[0] or time.monotonic() - start > 3.0
            if matched[0]:
                ready.publish(String(data=f"{names.DYNAMICS_NODE} /cmd_rudder /cmd_thrust"))

        err = _hold_at_grants(probe, replay, grants, clock, match_late)
    finally:
        if replay.poll() is None:
            replay.kill()
    assert replay.returncode == 0, err
    assert early == [], "commands sent before the simulation said it had matched them"
    probe.spin_until(lambda: len(received) == 8, 10.0, "the 8 commands")
    assert "replayed 8 commands" in err


def test_a_lockstep_run_says_which_replayer_topics_it_has_matched(boatsim, probe, tmp_path):
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import Float64MultiArray, String

    from boat_msgs_py import names
    from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS

    words = []
    probe.node.create_subscription(String, names.LOCKSTEP_READY,
                                   lambda m: words.append(m.data), COMMAND_QOS)
    replayer = probe.other_node(names.REPLAY_NODE)
    replayer.create_publisher(Float64, "/cmd_thrust", COMMAND_QOS)
    probe.node.create_publisher(Float64, "/cmd_rudder", COMMAND_QOS)  # not the replayer's
    sim = boatsim("run", "--fast", "--lockstep", "--record", str(tmp_path / "bag"))
    probe.spin_until(lambda: words, 60.0, names.LOCKSTEP_READY)
    assert set(words) == {f"{names.DYNAMICS_NODE} /cmd_thrust"}
    # a grant of 30 s: the run's recorder looks for new topics while it steps (every second
    # of wall time), then the run holds at t = 30 s and says its word again
    clock = []
    probe.node.create_subscription(Clock, names.CLOCK, lambda m: clock.append(m.clock.sec),
                                   CLOCK_QOS)
    grant = replayer.create_publisher(Float64MultiArray, names.LOCKSTEP, COMMAND_QOS)
    grant.publish(Float64MultiArray(data=[30.0, 0.0]))
    probe.spin_until(lambda: clock and clock[-1] >= 30, 120.0, "the simulation at t = 30 s")
    count = len(words)
    probe.spin_until(lambda: len(words) > count + 3, 30.0, "the word said at t = 30 s")
    assert sim.stop() == 0
    # said on the wall clock, it is protocol: not recorded (two identical runs would differ)
    topics = read_bag_topics(tmp_path / "bag")
    assert names.LOCKSTEP_READY not in topics, topics


def test_replay_without_a_simulation_or_commands_exits_2(tmp_path):
    _command_bag(tmp_path / "commands")
    out = cli_run("replay", str(tmp_path / "commands"), "--timeout", "1")
    assert out.returncode == 2 and "waiting for a simulation" in out.stderr
    assert "Traceback" not in out.stderr
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(tmp_path / "empty", version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        writer.add_connection("/odom", "nav_msgs/msg/Odometry", typestore=store)
    out = cli_run("replay", str(tmp_path / "empty"))
    assert out.returncode == 2 and "no command topics" in out.stderr


def test_run_record_loses_nothing_with_ten_boats(tmp_path):
    boats = "\n".join(f"  - {{name: b{i}, initial_pose: {{position: [{12 * i}.0, 0.0, 0.0]}}}}"
                      for i in range(10))
    (tmp_path / "fleet.yaml").write_text(f"boats:\n{boats}\n")
    out = cli_run("run", str(tmp_path / "fleet.yaml"), "--fast", "--duration", "2", "--record",
               str(tmp_path / "bag"), timeout=180)
    assert out.returncode == 0, out.stderr
    with AnyReader([tmp_path / "bag"]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
    # 200 steps: every 2nd at 50 Hz plus step 0, every 10th at 10 Hz plus step 0
    for i in range(10):
        for topic in ("odom", "pose", "twist"):
            assert counts[f"/b{i}/{topic}"] == 101
        for source in ("buoyancy", "damping", "drag", "thrust", "rudder", "total"):
            assert counts[f"/b{i}/wrench/{source}"] == 21
    assert counts["/clock"] == 201 and counts["/diagnostics"] == 21


def test_undecodable_messages_exit_2_with_one_line(two_runs, tmp_path):
    from rosbags.typesys import get_types_from_msg

    bad = tmp_path / "bad"
    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg("float64 a\nint32 b", "foo_msgs/msg/Bar"))
    with Writer(bad, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/odom", "foo_msgs/msg/Bar", typestore=store)
        writer.write(conn, 0, b"\x00\x01\x00")  # 3 bytes: not a float64 + int32
    short = tmp_path / "short"  # an Odometry connection whose message is 3 bytes
    with Writer(short, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/odom", "nav_msgs/msg/Odometry", typestore=store)
        writer.write(conn, 0, b"\x00\x01\x00")
    for args, fragment in (
            (["compare", str(bad), str(two_runs / "a"), "--topics", "/odom"],
             "cannot decode /odom [foo_msgs/msg/Bar]"),
            (["plot", str(bad)], "no */odom topic of type nav_msgs/msg/Odometry (/odom is "
                                 "foo_msgs/msg/Bar)"),
            (["plot", str(short)], "cannot decode /odom [nav_msgs/msg/Odometry]")):
        out = cli_run(*args)
        assert out.returncode == 2, out.stderr
        assert fragment in out.stderr
        assert len(out.stderr.strip().splitlines()) == 1 and "Traceback" not in out.stderr


SENSORS = """
ocean: {components: [{amplitude: 0.3, wavelength: 25.0, steepness: 0.5}]}
boats:
  - commands: [{t: 0, thrust: 1.0, rudder: 0.2}]
    sensors: [{type: imu}, {type: gnss}, {type: odometry}]
"""


def test_two_identical_runs_give_byte_identical_bags(tmp_path):
    # every type the simulation publishes, templates and rclpy-serialized messages alike;
    # /rosout is stamped by the wall clock, so it is left out
    (tmp_path / "s.yaml").write_text(SENSORS)
    for run in ("x", "y"):
        out = cli_run("run", str(tmp_path / "s.yaml"), "--fast", "--duration", "2", "--record",
                   str(tmp_path / run / "bag"), "--exclude-topics", "/rosout")
        assert out.returncode == 0, out.stderr
    with AnyReader([tmp_path / "x" / "bag"]) as reader:
        topics = {c.topic for c in reader.connections}
    assert {"/odom", "/tf", "/tf_static", "/diagnostics", "/ocean/surface", "/imu/data",
            "/gnss/fix", "/gnss/vel"} <= topics, topics
    assert "/rosout" not in topics
    a = (tmp_path / "x" / "bag" / "bag.mcap").read_bytes()
    b = (tmp_path / "y" / "bag" / "bag.mcap").read_bytes()
    same = a == b  # not `assert a == b`: pytest's diff of two 100 kB byte strings takes minutes
    assert same, f"{len(a)} and {len(b)} bytes; " + _first_difference(tmp_path / "x" / "bag",
                                                                      tmp_path / "y" / "bag")


def test_a_runs_recorder_leaves_out_parameter_declarations_and_keeps_values_set():
    # the surface server's process declares use_sim_time as it starts, at a wall-clock moment:
    # recorded, it made two identical runs' bags differ (its event at 0.10 s in one, none in
    # the other; reproduced 2 in 12 runs with both cores loaded)
    from rcl_interfaces.msg import Parameter, ParameterEvent
    from rclpy.serialization import serialize_message

    from boat_dynamics.tools.recording import declares_only

    def event(**lists):
        return serialize_message(ParameterEvent(node="/ocean_surface", **lists))

    p = Parameter(name="use_sim_time")
    assert declares_only(event(new_parameters=[p]))
    assert not declares_only(event(changed_parameters=[p]))
    assert not declares_only(event(new_parameters=[p], changed_parameters=[p]))
    assert not declares_only(event(deleted_parameters=[p]))
    assert not declares_only(event())


def _first_difference(x, y) -> str:
    """Where two bags first differ: the topic, the message's index and stamps, or the order."""
    def messages(bag):
        with AnyReader([bag]) as reader:
            return [(c.topic, t, raw) for c, t, raw in reader.messages()]

    a, b = messages(x), messages(y)
    for i, (p, q) in enumerate(zip(a, b, strict=False)):
        if p != q:
            return (f"message {i} differs: {p[0]} at {p[1]} ns ({len(p[2])} bytes) against "
                    f"{q[0]} at {q[1]} ns ({len(q[2])} bytes)")
    return f"{len(a)} and {len(b)} messages, equal as far as both go (the files' framing differs)"


def test_a_killed_run_loses_at_most_its_last_second_after_reindex(boatsim, probe, tmp_path):
    from rosgraph_msgs.msg import Clock

    bag = tmp_path / "bag"
    sim = boatsim("run", "--fast", "--record", str(bag))
    seen = []
    probe.node.create_subscription(Clock, "/clock", seen.append, 10)
    probe.spin_until(lambda: seen and seen[-1].clock.sec >= 12, 120.0, "12 s of /clock")
    t_seen = seen[-1].clock.sec + seen[-1].clock.nanosec * 1e-9
    sim.stop(signal.SIGKILL)
    assert not (bag / "metadata.yaml").exists()
    refused = cli_run("plot", str(bag), "-o", str(tmp_path / "p.png"))
    assert refused.returncode == 2 and f"boatsim reindex {bag}" in refused.stderr

    out = cli_run("reindex", str(bag))

    assert out.returncode == 0, out.stderr
    with AnyReader([bag]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        clock = [c for c in reader.connections if c.topic == "/clock"]
        stamps = [t for _, t, _ in reader.messages(connections=clock)]
    assert stamps == sorted(stamps) and stamps[0] == 0
    assert stamps[-1] / 1e9 > t_seen - 1.0, (stamps[-1] / 1e9, t_seen)
    assert abs(counts["/odom"] - counts["/clock"] / 2) <= 2  # odom at 50 Hz, clock at 100
    assert cli_run("plot", str(bag), "-o", str(tmp_path / "p.png")).returncode == 0


def test_a_full_disk_stops_the_recording_and_the_run_goes_on(tmp_path):
    """A file-size limit (RLIMIT_FSIZE, EFBIG) stands in for a full disk: before, two
    tracebacks and the run died; now one error line, the run reaches its end, exit 1."""
    import resource

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (256 * 1024, 256 * 1024))

    bag = tmp_path / "bag"
    out = subprocess.run([sys.executable, "-m", "boat_dynamics", "run", "--fast", "--duration",
                          "30", "--record", str(bag)], capture_output=True, text=True,
                         timeout=300, preexec_fn=small_files)
    assert out.returncode == 1, out.stderr
    assert "Traceback" not in out.stderr
    assert out.stderr.count("recording stopped at bag time") == 2  # the log, the last word
    assert "the simulation goes on" in out.stderr
    assert "t    30.00 s" in out.stderr  # the status line: it ran to its end
    assert cli_run("reindex", str(bag)).returncode == 0
    with AnyReader([bag]) as reader:
        clock = [c for c in reader.connections if c.topic == "/clock"]
        stamps = [t for _, t, _ in reader.messages(connections=clock)]
    assert stamps == [k * 10_000_000 for k in range(len(stamps))] and 0 < len(stamps) < 3000
