"""Messages any node on the domain may publish cannot kill or slow the simulation.

The dynamics node's subscribers check what they receive within the bounds of the parameters
that set the same things (ocean_sim.physics.environment, ocean_sim.physics.waves): a message
out of them is refused, the first of a topic logged with its reason, every one counted on
/diagnostics as ``messages_refused``; the run goes on with the previous sea and environment.
Counted in messages, never in wall time.
"""

import math

from boat_msgs.msg import Environment as EnvironmentMsg
from boat_msgs.msg import WaveComponent as WaveComponentMsg
from boat_msgs.msg import WaveField as WaveFieldMsg
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Odometry

from boat_msgs_py.qos import ENVIRONMENT_QOS, WAVE_FIELD_QOS


def test_hostile_environment_and_wave_field_messages_are_refused_and_counted(boatsim, probe):
    sim = boatsim("run", "--fast")
    odoms, refused = [], []
    probe.node.create_subscription(Odometry, "/odom", odoms.append, 100)

    def on_diagnostics(msg):
        refused.extend(kv.value for kv in msg.status[0].values if kv.key == "messages_refused")

    probe.node.create_subscription(DiagnosticArray, "/diagnostics", on_diagnostics, 10)
    probe.spin_until(lambda: len(odoms) > 5, 60.0, "/odom")
    environment = probe.node.create_publisher(EnvironmentMsg, "/ocean/environment",
                                              ENVIRONMENT_QOS)
    field = probe.node.create_publisher(WaveFieldMsg, "/ocean/wave_field", WAVE_FIELD_QOS)
    one = WaveComponentMsg(amplitude=0.01, wavelength=50.0, direction=0.0, steepness=0.0,
                           phase=0.0)
    def counted():
        return int(refused[-1]) if refused else 0

    for k in range(3):  # 4e9 gust components once allocated 29.8 GiB and killed the node
        environment.publish(EnvironmentMsg(wind_speed=10.0, gusts="norsok",
                                           gust_components=4_000_000_000 - k))
        probe.spin_until(lambda k=k: counted() >= k + 1, 60.0, f"refusal {k + 1} counted")
    field.publish(WaveFieldMsg(gravity=9.81, depth=math.inf, components=[one] * 20_000))
    probe.spin_until(lambda: counted() >= 4, 60.0, "the wave field's refusal counted")
    n = len(odoms)
    probe.spin_until(lambda: len(odoms) > n + 20, 60.0, "/odom going on")
    assert all(math.isfinite(o.pose.pose.position.z) for o in odoms)
    assert sim.stop() == 0
    out = sim.output()
    # once each topic, with the key and the value; later refusals counted, not logged
    assert out.count("[boat_dynamics]: ignoring invalid /ocean/environment") == 1
    assert ("wind.gust_components: 4000000000 is not allowed: an integer in [1, 1000]; "
            "keeping the previous current and wind") in out
    assert out.count("[boat_dynamics]: ignoring invalid /ocean/wave_field") == 1
    assert "'20000 components' is not allowed: at most 4096; keeping the previous sea" in out


def test_a_boat_whose_state_diverges_is_stopped_and_the_run_exits_3(boatsim, tmp_path):
    # a 1 g boat on a 4 t hull's buoyancy went NaN at its 6th step, and the run exited 0
    # with NaN odometry; now it is held where it was, reported, and the other boat goes on
    import yaml

    from boat_dynamics.tools.bags import read_bag

    path = tmp_path / "light.yaml"
    path.write_text(yaml.safe_dump({"boats": [
        {"name": "feather", "mass": 0.001},
        {"name": "alpha", "initial_pose": {"position": [20.0, 0.0, 0.0]},
         "commands": [{"t": 0.0, "thrust": 1.0}]}]}))
    bag = tmp_path / "bag"
    sim = boatsim("run", str(path), "--fast", "--duration", "2", "--record", str(bag))
    assert sim.wait(timeout=120) == 3, sim.output()
    out = sim.output()
    assert out.count("boat feather: its state diverged at t = 0.010 s") == 1
    assert "exit 3: stopped, their state diverged: feather" in out
    msgs = read_bag(bag, ["/feather/odom", "/alpha/odom", "/diagnostics"])
    for topic in ("/feather/odom", "/alpha/odom"):
        assert len(msgs[topic]) == 101  # 0 .. 2 s at 50 Hz
        assert all(math.isfinite(m.pose.pose.position.z)
                   and math.isfinite(m.twist.twist.linear.x) for _, m in msgs[topic])
    alpha = [m.pose.pose.position.x for _, m in msgs["/alpha/odom"]]
    assert alpha[-1] > alpha[0] + 0.5  # under way
    feather = {round(m.pose.pose.position.z, 9) for _, m in msgs["/feather/odom"][2:]}
    assert len(feather) == 1  # held
    last = msgs["/diagnostics"][-1][1]
    status = next(s for s in last.status if s.name == "boatsim: feather")
    assert status.level == 2 and status.message.startswith("stopped: its state diverged")
    assert next(s for s in last.status if s.name == "boatsim: alpha").level != 2  # rosbags: int
