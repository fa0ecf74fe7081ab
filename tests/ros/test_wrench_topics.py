"""`simulation.wrench_topics: on_subscription`: a boat's wrench topics appear when subscribed.

Real time, not --fast: the probe must find the graph and subscribe while the run goes on.
Windows are counted in messages (simulation time), never in wall time.
"""

import numpy as np
import yaml
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry

from boat_msgs_py.convert import time_to_seconds


def _scenario(tmp_path, **simulation):
    path = tmp_path / "two.yaml"
    path.write_text(yaml.safe_dump({"simulation": simulation, "boats": [
        {"name": "alpha"}, {"name": "bravo", "initial_pose": {"position": [20.0, 0.0, 0.0]}}]}))
    return path


def _topics(probe):
    return {name for name, _ in probe.node.get_topic_names_and_types()}


def test_wrench_topics_on_subscription_are_made_when_someone_subscribes(boatsim, probe,
                                                                         tmp_path):
    sim = boatsim("run", str(_scenario(tmp_path, wrench_topics="on_subscription")))
    odom = []
    probe.node.create_subscription(Odometry, "/alpha/odom", odom.append, 10)
    probe.spin_until(lambda: len(odom) > 10, 60.0, "/alpha/odom")
    before = _topics(probe)
    assert {"/alpha/odom", "/alpha/pose", "/bravo/twist"} <= before
    assert not [t for t in before if "/wrench/" in t]  # 18 endpoints not made
    total = []
    probe.node.create_subscription(WrenchStamped, "/alpha/wrench/total", total.append, 10)
    probe.spin_until(lambda: len(total) >= 5, 60.0, "/alpha/wrench/total once subscribed")
    stamps = np.array([time_to_seconds(w.header.stamp) for w in total])
    # diagnostics_rate_hz 10: every stamp on the 0.1 s grid (a probe stalled on a busy machine
    # may miss one), most 0.1 s apart
    steps = np.diff(stamps) / 0.1
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-5)
    assert (np.round(steps) >= 1).all() and np.median(np.round(steps)) == 1
    assert total[-1].header.frame_id == "alpha/base_link"
    after = {t for t in _topics(probe) if "/wrench/" in t}
    assert after == {"/alpha/wrench/total"}  # only what someone asked for
    assert sim.stop() == 0
    assert "wrench/<source> topics are advertised when someone subscribes" in sim.output()


def test_a_recording_holds_every_wrench_all_the_same(boatsim, tmp_path):
    from boat_dynamics.tools.bags import read_bag

    bag = tmp_path / "bag"
    sim = boatsim("run", str(_scenario(tmp_path, wrench_topics="on_subscription")), "--fast",
                  "--duration", "1", "--record", str(bag))
    assert sim.wait(timeout=90) == 0, sim.output()
    topics = [f"/{b}/wrench/{s}" for b in ("alpha", "bravo")
              for s in ("buoyancy", "damping", "drag", "thrust", "rudder", "diffraction",
                        "slamming", "wind", "total")]
    msgs = read_bag(bag, topics)
    assert {t: len(msgs[t]) for t in topics} == {t: 11 for t in topics}  # 0 .. 1 s at 10 Hz


def test_a_towed_boat_publishes_its_carriage_force(boatsim, tmp_path):
    # alpha on a carriage at 1.5 m/s in calm water, bravo free: alpha's wrench/carriage (body
    # frame, about the centre of mass) is the force the physics computes (pipeline.step's
    # towing, the same scenario stepped here alone, to rounding), ahead and across nothing;
    # a boat not towed has no such topic.
    from boat_dynamics.physics.body.rigid_body import rotation_matrix
    from boat_dynamics.physics.core import pipeline
    from boat_dynamics.physics.core.model import BoatInputs
    from boat_dynamics.physics.core.system import FleetInputs
    from boat_dynamics.physics.force_models.carriage import body_wrench
    from boat_dynamics.physics.scenario import load_scenario
    from boat_dynamics.tools.bags import read_bag, read_bag_topics

    path = tmp_path / "towed.yaml"
    path.write_text(yaml.safe_dump({"ocean": {"components": []}, "boats": [
        {"name": "alpha", "carriage": {"speed": 1.5}},
        {"name": "bravo", "initial_pose": {"position": [20.0, 0.0, 0.0]}}]}))
    bag = tmp_path / "bag"
    sim = boatsim("run", str(path), "--fast", "--duration", "3", "--record", str(bag))
    assert sim.wait(timeout=90) == 0, sim.output()
    msgs = read_bag(bag, ["/alpha/wrench/carriage"])["/alpha/wrench/carriage"]
    assert "/bravo/wrench/carriage" not in read_bag_topics(bag)
    stamps = np.array([time_to_seconds(m.header.stamp) for _, m in msgs])
    np.testing.assert_allclose(stamps, 0.1 * np.arange(1, 31), atol=1e-9)  # from the 1st step
    assert msgs[-1][1].header.frame_id == "alpha/base_link"

    scenario = load_scenario(path)
    system, state = pipeline.start(scenario.boats[:1], scenario.sea)
    inputs = FleetInputs.stack([BoatInputs()])
    for _ in range(300):
        step = pipeline.step(system, state, inputs, scenario.sea, 0.01)
        state = step.state
    want = body_wrench(system.params[0].carriage, rotation_matrix(state.orientation[0]),
                       step.towing[0])
    w = msgs[-1][1].wrench
    got = np.array([w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z])
    np.testing.assert_allclose(got, want, rtol=1e-6, atol=1e-6)
    assert got[0] > 50.0 and abs(got[1]) < 1e-3 * got[0]  # N: the resistance, ahead
