"""One simulation clock across processes: --shards, --processes and --only with --fast."""

import os
import re
import signal
import time

import pytest
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from support import cli_run

from boat_dynamics.tools.bagfile import merge
from boat_dynamics.tools.bags import compare_bags, read_bag

#: Three boats (two of the models, one scripted), making no waves for each other: boats in
#: different processes do not feel each other's made waves (DESIGN), so with them a sharded
#: run would differ from one process by design. A surface query takes each point's phase on
#: its own, so regrouping the fleet can change only how a sum over a batch's rows is rounded.
#: float64 queries (the default, compiled: each point summed on its own): at most the last
#: bits of the rest of the step (measured: 8e-17 m with numpy's float64 queries).
REGROUPED = 1e-12
#: float32 queries (numpy's): BLAS rounds the sums over the wave components by a row's place
#: in the batch on some CPUs: 1.3e-8 m/s and 4e-9 m in 3 s on an AMD EPYC (AVX2 kernels).
REGROUPED_32 = 1e-6
FLEET = """
simulation: {seed: 1}
ocean:
  spectrum: {type: jonswap, significant_height: 0.8, peak_period: 5.5, direction_deg: 20.0,
             spreading: 15.0, components: 16}
boats:
  - {name: alpha, initial_pose: {position: [0.0, 0.0, 0.0]},
     hydrodynamics: {made_waves: none}}
  - {name: bravo, hull: {type: box, length: 6.0, beam: 2.5, height: 1.2}, density: 450.0,
     center_of_mass: [0.0, 0.0, -0.25], initial_pose: {position: [0.0, 15.0, 0.0], yaw_deg: 90},
     hydrodynamics: {made_waves: none}}
  - name: charlie
    hydrodynamics: {made_waves: none}
    buoyancy: {model: sample_points, grid: [5, 3]}
    initial_pose: {position: [-15.0, -10.0, 0.0]}
    commands: [{t: 0.0, thrust: 1.0, rudder: 0.0}, {t: 1.0, thrust: 1.0, rudder: 0.35}]
"""
ODOM = ["/alpha/odom", "/bravo/odom", "/charlie/odom"]


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    d = tmp_path_factory.mktemp("fleet")
    (d / "fleet.yaml").write_text(FLEET)
    (d / "fleet32.yaml").write_text(FLEET.replace("{seed: 1}", "{seed: 1, wave_precision: "
                                                                "float32}"))
    out = cli_run("run", str(d / "fleet.yaml"), "--fast", "--duration", "3", "--record",
               str(d / "one"))
    assert out.returncode == 0, out.stderr
    return d


def _run(fleet, name, *args, scenario="fleet.yaml"):
    out = cli_run("run", str(fleet / scenario), "--fast", "--duration", "3", "--record",
               str(fleet / name), *args, timeout=180)
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr
    return out


def _odometry_agrees(a, b, tolerance):
    result = compare_bags(a, b, topics=ODOM, tolerances={"*": tolerance})
    assert result.ok, result.report()
    assert [t.matched for t in result.topics] == [151, 151, 151]  # 3 s at 50 Hz, and t = 0


def test_two_shards_give_the_odometry_of_one_process(fleet):
    out = _run(fleet, "shards2", "--shards", "2")
    assert "ocean + 2 shards" in out.stderr and "merged from 3 processes' bags" in out.stderr
    _odometry_agrees(fleet / "one", fleet / "shards2", REGROUPED)
    msgs = read_bag(fleet / "shards2")
    clock = [t for t, _ in msgs["/clock"]]  # from the clock owner only: once per step
    assert clock == [round(k * 1e7) for k in range(301)]
    assert len(msgs["/ocean/wave_field"]) == 1
    assert "/boatsim/step_done" not in msgs and "/boatsim/step_grant" not in msgs


def test_one_shard_is_bit_identical_and_float32_queries_agree_too(fleet):
    _run(fleet, "shard1", "--shards", "1")  # the same grouping: the same numbers
    _odometry_agrees(fleet / "one", fleet / "shard1", 0.0)
    _run(fleet, "one32", scenario="fleet32.yaml")
    _run(fleet, "shards32", "--shards", "2", scenario="fleet32.yaml")
    _odometry_agrees(fleet / "one32", fleet / "shards32", REGROUPED_32)


def test_a_process_per_boat_with_fast(fleet):
    out = _run(fleet, "processes", "--processes")
    assert "ocean + 3 boats" in out.stderr
    _odometry_agrees(fleet / "one", fleet / "processes", REGROUPED)


def _command_bag(path):
    store = get_typestore(Stores.ROS2_JAZZY)
    plan = [(0.0, "/alpha/cmd_thrust", 1.0), (0.0, "/bravo/cmd_thrust", 0.5),
            (0.8, "/alpha/cmd_rudder", 0.3), (1.0, "/bravo/cmd_thrust", -0.5),
            (1.37, "/bravo/cmd_rudder", -0.2), (2.0, "/alpha/cmd_thrust", 0.2)]
    msg = store.types["std_msgs/msg/Float64"]
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conns = {t: writer.add_connection(t, "std_msgs/msg/Float64", typestore=store)
                 for t in sorted({t for _, t, _ in plan})}
        for t, topic, value in plan:
            writer.write(conns[topic], round(t * 1e9),
                         store.serialize_cdr(msg(data=value), "std_msgs/msg/Float64"))
    return plan


def test_a_lockstep_replay_through_shards_matches_one_process(boatsim, fleet, tmp_path):
    plan = _command_bag(tmp_path / "commands")
    runs = {}
    for name, extra in (("one", ()), ("shards", ("--shards", "2"))):
        sim = boatsim("run", str(fleet / "fleet.yaml"), "--fast", "--lockstep", "--duration",
                      "3", "--record", str(tmp_path / name), *extra, name=name)
        out = cli_run("replay", str(tmp_path / "commands"), timeout=90)
        assert out.returncode == 0, out.stderr
        assert sim.wait(timeout=90) == 0, sim.output()
        runs[name] = tmp_path / name
    _odometry_agrees(runs["one"], runs["shards"], REGROUPED)
    topics = sorted({t for _, t, _ in plan})
    result = compare_bags(runs["one"], runs["shards"], topics=topics, tolerances={"*": 0.0})
    assert result.ok, result.report()  # each command recorded at the same simulation time
    stamps = read_bag(runs["shards"], ["/bravo/cmd_rudder"])["/bravo/cmd_rudder"]
    assert [t for t, _ in stamps] == [1_370_000_000]  # held at 1.37 s until it arrived


def test_processes_started_apart_join_the_barrier(boatsim, fleet, tmp_path):
    common = (str(fleet / "fleet.yaml"), "--fast", "--duration", "3")
    second = boatsim("run", *common, "--only", "shard", "1/2", "--record",
                     str(tmp_path / "s1"), name="s1")
    ocean = boatsim("run", *common, "--shards", "2", "--only", "ocean", "--record",
                    str(tmp_path / "ocean"), name="ocean")
    first = boatsim("run", *common, "--only", "shard", "0/2", "--record",
                    str(tmp_path / "s0"), name="s0")
    for sim in (first, second, ocean):
        assert sim.wait(timeout=120) == 0, sim.output()
    merge([tmp_path / "ocean", tmp_path / "s0", tmp_path / "s1"], tmp_path / "all")
    _odometry_agrees(fleet / "one", tmp_path / "all", REGROUPED)
    assert len(read_bag(tmp_path / "ocean", ["/clock"])["/clock"]) == 301
    assert "owning the clock of 2 dynamics process(es)" in ocean.output()


def test_a_process_started_with_another_scenario_is_refused(boatsim, fleet):
    """Before: it ran (two nodes named boat_dynamics_alpha) and the clock owner waited for
    ever. Now the owner refuses it by its scenario digest, and it exits 2 saying why."""
    other = fleet / "other.yaml"
    other.write_text(FLEET.replace("density: 450.0", "density: 460.0"))
    common = ("--fast", "--duration", "3")
    ocean = boatsim("run", str(fleet / "fleet.yaml"), *common, "--shards", "2", "--only",
                    "ocean", name="ocean")
    stray = boatsim("run", str(other), *common, "--only", "shard", "1/2", name="stray")
    assert stray.wait(timeout=120) == 2, stray.output()
    assert "the clock owner refused this process: its scenario" in stray.output()
    assert "Traceback" not in stray.output()
    deadline = time.monotonic() + 30
    while "refusing dynamics process 1/2" not in ocean.output():
        assert time.monotonic() < deadline, ocean.output()
        time.sleep(0.1)
    assert ocean.proc.poll() is None  # still waiting for a shard 1/2 of its own scenario
    ocean.stop()


def _pids(sim):
    """The pids the parent printed: the ocean's, then each shard's."""
    deadline = time.monotonic() + 60
    while "every process ready" not in sim.output():
        assert time.monotonic() < deadline and sim.proc.poll() is None, sim.output()
        time.sleep(0.1)
    return [int(p) for p in re.search(r"pids ([\d ]+)", sim.output()).group(1).split()]


def test_a_dead_shard_stops_a_lockstep_run(boatsim, fleet):
    """Under --lockstep a restarted shard would lack the replayer's commands it had received."""
    sim = boatsim("run", str(fleet / "fleet.yaml"), "--fast", "--lockstep", "--shards", "2")
    *_, rest = _pids(sim)
    os.kill(rest, signal.SIGKILL)
    assert sim.wait(timeout=30) == 1
    out = sim.output()
    assert f"process shard 1/2 (pid {rest}) died: killed by SIGKILL" in out
    assert "stopping the run (under --lockstep" in out and "Traceback" not in out


#: Six scripted boats (their commands depend on simulation time only), one with an IMU.
RESUMED = "\n".join(["ocean:", "  spectrum: {significant_height: 1.0, peak_period: 6.0, "
                      "components: 16}", "boats:"] + [
    f"  - {{name: b{i}, initial_pose: {{position: [{12 * i}, 0, 0]}}, commands: [{{t: 0, "
    f"thrust: {0.3 + 0.1 * i:.1f}, rudder: 0.1}}, {{t: 4, thrust: 0.8, rudder: -0.2}}]"
    + (", sensors: [{type: imu}]" if i == 4 else "") + "}" for i in range(6)])


def test_a_killed_shard_resumes_from_its_snapshot_and_rejoins_the_barrier(boatsim, probe,
                                                                           tmp_path):
    from rosgraph_msgs.msg import Clock

    from boat_msgs_py.qos import CLOCK_QOS

    scenario = tmp_path / "six.yaml"
    scenario.write_text(RESUMED)
    # 40 s of simulation: about 3 s at this machine's 13x, so the kill falls mid-run
    run = ("run", str(scenario), "--fast", "--shards", "2", "--duration", "40", "--record")
    reference = cli_run(*run, str(tmp_path / "whole"), timeout=180)
    assert reference.returncode == 0, reference.stderr
    sim = boatsim(*run, str(tmp_path / "killed"))
    clock = []
    probe.node.create_subscription(Clock, "/clock", lambda m: clock.append(m.clock.sec), CLOCK_QOS)
    *_, rest = _pids(sim)
    probe.spin_until(lambda: clock and clock[-1] >= 2, 120, "/clock at 2 s")
    os.kill(rest, signal.SIGKILL)  # shard 1/2: boats b3, b4, b5
    assert sim.wait(timeout=180) == 1, sim.output()  # a child died: status 1, run completed
    out = sim.output()
    assert f"process shard 1/2 (pid {rest}) died: killed by SIGKILL" in out
    assert re.search(r"restarted shard 1/2 \(pid \d+\) from its snapshot at step \d+00 ", out)
    assert "resuming at t = " in out and "Traceback" not in out
    if "has not reported for 2 s" in out:  # the restart took that long (it does here: 3 s)
        assert "dynamics process 1/2 reports again" in out
    topics = [f"/b{i}/odom" for i in range(6)] + ["/b4/imu/data", "/b4/wrench/total"]
    result = compare_bags(tmp_path / "whole", tmp_path / "killed", topics=topics,
                          tolerances={"*": 0.0})  # bit for bit
    assert result.ok, result.report()
    assert {t.topic: t.matched for t in result.topics} == {
        **{t: 2001 for t in topics[:6]}, "/b4/imu/data": 4000, "/b4/wrench/total": 401}
    stamps = [t for t, _ in read_bag(tmp_path / "killed", ["/b4/odom"])["/b4/odom"]]
    assert stamps == sorted(set(stamps))  # each once: the dead part was cut at the snapshot


@pytest.mark.parametrize(("args", "message"), [
    (("--only", "ocean"), "add --fast"),
    (("--fast", "--only", "ocean"), "add --shards N"),
    (("--fast", "--only", "shard", "3/3", "x"), "expected `ocean` or `shard K/N`"),
    (("--fast", "--only", "shard", "3/3"), "K must be 0 .. N - 1"),
    (("--fast", "--only", "shard", "0/4"), "4 shards for 3 boat(s)"),
    (("--fast", "--shards", "4"), "at most one shard per boat"),
])
def test_sharding_mistakes_exit_2_saying_what_is_allowed(fleet, args, message):
    out = cli_run("run", str(fleet / "fleet.yaml"), *args, timeout=60)
    assert out.returncode == 2 and message in out.stderr, out.stderr
    assert "Traceback" not in out.stderr
