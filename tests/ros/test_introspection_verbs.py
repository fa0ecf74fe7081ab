"""`boatsim topic|node|param`: the `ros2` verbs a PyPI install lacks, against a running sim."""

import pytest
import yaml
from std_msgs.msg import Float64

from boat_dynamics.cli import main


class _Result:
    def __init__(self, returncode: int, stdout: str, stderr: str) -> None:
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


@pytest.fixture
def cli(capsys):
    """Run a verb in this process (no interpreter start-up: the suite's time budget).

    Graph listings get 3 s of discovery: the loaded test machine finds participants seconds
    apart (the default 1 s missed one in 5 `node list` calls with both cores busy); verbs
    that wait for their topic, node or service on their own get the least.
    """

    def run(*args):
        capsys.readouterr()
        listing = args[:2] in (("topic", "list"), ("topic", "info"), ("node", "list"))
        code = main([*args, "--spin-time", "3" if listing else "0.2"])
        out = capsys.readouterr()
        return _Result(code, out.out, out.err)

    return run


@pytest.fixture
def sim(boatsim, probe):
    from nav_msgs.msg import Odometry

    run = boatsim("run", "scenarios/multi_boat.yaml")  # real time: /odom at 50 Hz
    seen = []
    probe.node.create_subscription(Odometry, "/alpha/odom", seen.append, 10)
    probe.spin_until(lambda: len(seen) > 2, 60.0, "/alpha/odom")
    yield run
    assert run.stop() == 0


def test_the_verbs_against_one_running_simulation(sim, probe, cli):
    # one simulation for every verb (its start-up is most of the cost): the topic verbs first
    # (`topic info` counts /alpha/cmd_thrust's publishers before `topic pub` makes one), the
    # parameters last (`param set` changes cmd_timeout)
    _topic_list_info_echo_and_hz(cli)
    _topic_pub_drives_a_boat(probe, cli)
    _node_list_and_params(cli)


def _topic_list_info_echo_and_hz(cli):
    listed = cli("topic", "list", "-t").stdout.splitlines()
    assert "/alpha/odom [nav_msgs/msg/Odometry]" in listed
    assert "/ocean/wave_field [boat_msgs/msg/WaveField]" in listed
    assert not [t for t in listed if t.startswith("/_")]
    # the count of the same graph (a topic may come or go between two calls: /tf, a probe's)
    assert abs(int(cli("topic", "list", "-c").stdout) - len(listed)) <= 2
    info = cli("topic", "info", "/alpha/cmd_thrust").stdout.splitlines()
    assert info == ["Type: std_msgs/msg/Float64", "Publisher count: 0", "Subscription count: 1"]
    verbose = cli("topic", "info", "/alpha/odom", "-v").stdout
    assert "Node name: boat_dynamics" in verbose and "Reliability: RELIABLE" in verbose
    echo = cli("topic", "echo", "/alpha/odom", "--once", "--timeout", "30")
    assert echo.returncode == 0, echo.stderr
    doc = yaml.safe_load(echo.stdout.split("---")[0])
    assert doc["child_frame_id"] == "alpha/base_link" and len(doc["pose"]["covariance"]) == 36
    # transient-local: a late subscriber gets it (if it waits for the publisher's endpoint)
    latched_echo = cli("topic", "echo", "/ocean/wave_field", "--once", "--timeout", "30")
    assert latched_echo.returncode == 0, latched_echo.stderr
    latched = yaml.safe_load(latched_echo.stdout.split("---")[0])
    assert len(latched["components"]) == 16
    hz = cli("topic", "hz", "/alpha/odom", "--timeout", "3").stdout
    assert "average rate: " in hz and "window: " in hz
    missing = cli("topic", "info", "/nosuch")
    assert missing.returncode == 1 and "Unknown topic '/nosuch'" in missing.stderr


def _topic_pub_drives_a_boat(probe, cli):
    got = []
    probe.node.create_subscription(Float64, "/alpha/cmd_thrust", got.append, 10)
    out = cli("topic", "pub", "/alpha/cmd_thrust", "std_msgs/msg/Float64", "{data: 0.7}",
               "--times", "3", "-r", "10", "-w", "2")  # the boat's and the probe's
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("Waiting for at least 2 matching subscription(s)...\n"
                                 "publisher: beginning loop\n")
    assert "publishing #3: std_msgs.msg.Float64(data=0.7)" in out.stdout
    probe.spin_until(lambda: len(got) >= 3, 10.0, "three published commands")
    assert {m.data for m in got} == {0.7}
    bad = cli("topic", "pub", "/alpha/cmd_thrust", "std_msgs/msg/Float64", "{dta: 1}", "-1")
    assert bad.returncode == 1 and "dta: Float64 has no such field" in bad.stderr


def _node_list_and_params(cli):
    nodes = cli("node", "list").stdout.splitlines()
    assert {"/boat_dynamics", "/ocean", "/ocean_surface"} <= set(nodes)

    def param(*args):
        # 20 s for the answers: with both cores busy `param get` once had none within 5 s
        out = cli("param", *args, "--timeout", "20")
        assert out.returncode == 0, out.stderr
        return out.stdout

    assert "cmd_timeout" in param("list", "/boat_dynamics")
    assert param("get", "/boat_dynamics", "cmd_timeout").strip() == "Double value is: 1.0"
    assert param("set", "/boat_dynamics", "cmd_timeout", "2").strip() == (
        "Set parameter successful")  # a whole number for a double: taken as 2.0
    for name, value, why in (("cmd_timeout", "-5", "out of range"),
                             ("publish_rate_hz", "20.0", "read-only")):
        refused = cli("param", "set", "/boat_dynamics", name, value, "--timeout", "20")
        assert refused.returncode == 1, refused  # ros2 param set exits 0: a script can't tell
        assert refused.stderr.startswith("boatsim param set: error: Setting parameter failed: ")
        assert why in refused.stderr, refused.stderr
    dump = yaml.safe_load(param("dump", "/boat_dynamics"))
    params = dump["/boat_dynamics"]["ros__parameters"]
    assert params["cmd_timeout"] == 2.0 and params["charlie.control_mode"] == "constrained"
    gone = cli("param", "get", "/nosuch_node", "x")
    assert gone.returncode == 1 and "Node not found: /nosuch_node" in gone.stderr
