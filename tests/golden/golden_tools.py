"""Recording golden runs: a scenario driven by a command plan replayed in lockstep.

Shared by tests/ros/test_golden.py and regold.py. A run starts `boatsim run --fast
--lockstep --record`, replays the plan's commands with `boatsim replay`, and keeps only the
command and odometry topics of the bag (small enough to commit).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import yaml
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

HERE = Path(__file__).resolve().parent


def specs() -> dict:
    """The golden specs (tests/golden/specs.yaml)."""
    return yaml.safe_load((HERE / "specs.yaml").read_text())


def write_commands(plan: list, path: Path) -> None:
    """A bag of std_msgs/Float64 commands at their simulation times."""
    store = get_typestore(Stores.ROS2_JAZZY)
    msg_type = "std_msgs/msg/Float64"
    cls = store.types[msg_type]
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conns = {}
        for t, topic, value in plan:
            if topic not in conns:
                conns[topic] = writer.add_connection(topic, msg_type, typestore=store)
            writer.write(conns[topic], round(t * 1e9),
                         store.serialize_cdr(cls(data=float(value)), msg_type))


def _keep(src: Path, dst: Path) -> None:
    """Copy the command and odometry topics of a bag."""
    with AnyReader([src]) as reader, Writer(dst, version=9,
                                           storage_plugin=StoragePlugin.MCAP) as writer:
        keep = [c for c in reader.connections
                if c.topic.endswith(("/odom", "/cmd_thrust", "/cmd_rudder"))]
        out = {}
        for conn in keep:
            out[conn.topic] = writer.add_connection(conn.topic, conn.msgtype,
                                                    typestore=reader.typestore)
        for conn, stamp, raw in reader.messages(connections=keep):
            writer.write(out[conn.topic], stamp, raw)


def record_run(name: str, out: Path, work: Path, timeout: float = 120.0) -> None:
    """Record golden run ``name`` into ``out`` (a new directory), using ``work`` as scratch."""
    spec = specs()[name]
    work.mkdir(parents=True, exist_ok=True)
    commands, full = work / f"{name}.commands", work / f"{name}.full"
    for p in (commands, full):
        shutil.rmtree(p, ignore_errors=True)
    write_commands(spec["commands"], commands)
    cli = [sys.executable, "-m", "boat_dynamics"]
    sim = subprocess.Popen([*cli, "run", str(HERE / spec["scenario"]), "--fast", "--lockstep",
                            "--duration", str(spec["duration"]), "--record", str(full)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                           env=os.environ.copy())
    try:
        replay = subprocess.run([*cli, "replay", str(commands)], capture_output=True,
                                text=True, timeout=timeout, env=os.environ.copy())
        if replay.returncode != 0:
            raise RuntimeError(f"replay of {name} failed: {replay.stderr.strip()}")
        _, err = sim.communicate(timeout=timeout)
        if sim.returncode != 0:
            raise RuntimeError(f"simulation of {name} failed: {err.strip()[-2000:]}")
    finally:
        if sim.poll() is None:
            sim.kill()
            sim.wait()
    _keep(full, out)
