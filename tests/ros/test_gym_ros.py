"""/boatsim/reset and RosBoatEnv: episodes of a running lockstep simulation (issue 30, item 5).

One `boatsim run --fast --lockstep` in a regular swell with a noisy IMU: the ROS environment's
episodes repeat to the last bit for a seed, follow the in-process BoatEnv, pass Gymnasium's
checker; /clock never goes back; a reset places a boat where asked, refuses bad requests by
field and value, and is marked in the bag by the republished wave field.
"""

import itertools
import math
import warnings

import numpy as np
import pytest
from boat_msgs.srv import Reset
from geometry_msgs.msg import Pose, Quaternion, Twist
from gymnasium.utils.env_checker import check_env
from nav_msgs.msg import Odometry
from rclpy.event_handler import SubscriptionEventCallbacks
from rosbags.highlevel import AnyReader
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu

from boat_dynamics.gym import BoatEnv, Task
from boat_dynamics.gym_ros import RosBoatEnv
from boat_msgs_py import names
from boat_msgs_py.qos import RECORD_QOS

SCENARIO = """\
simulation: {rate_hz: 100, seed: 3}
ocean:
  components:
    - {amplitude: 0.3, wavelength: 25.0, direction_deg: 30.0, steepness: 0.5}
boats:
  - sensors:
      - {type: imu, name: imu, rate_hz: 10}
"""
TASK = Task(episode_time=1.0)
ACTIONS = [[1.0, 0.3]] * 5 + [[-0.5, -0.2]] * 5


def _rollout(env, seed):
    obs, _ = env.reset(seed=seed)
    out = [np.concatenate([obs, [0.0, False]])]
    for a in ACTIONS:
        obs, reward, terminated, truncated, _ = env.step(a)
        out.append(np.concatenate([obs, [reward, terminated or truncated]]))
    return np.array(out)


def _ns(stamp) -> int:
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def test_episodes_over_ros_repeat_follow_boat_env_and_reset_as_asked(boatsim, probe, tmp_path):
    path = tmp_path / "swell.yaml"
    path.write_text(SCENARIO)
    sim = boatsim("run", str(path), "--fast", "--lockstep", "--record", str(tmp_path / "bag"))
    clocks, imu, odom = [], [], []
    # deep queues: the probe spins only between episodes; it counts an episode's messages
    # only once its subscriptions have matched the simulation's publishers (a busy machine
    # matched /imu/data after the first episode: it read none of its 10 readings)
    matched: dict[str, int] = {}

    def watch(topic: str) -> SubscriptionEventCallbacks:
        return SubscriptionEventCallbacks(
            matched=lambda status: matched.__setitem__(topic, status.current_count))

    for kind, topic, keep in ((Clock, names.CLOCK, lambda m: clocks.append(_ns(m.clock))),
                              (Imu, "/imu/data", imu.append), (Odometry, "/odom", odom.append)):
        probe.node.create_subscription(kind, topic, keep, RECORD_QOS,
                                       event_callbacks=watch(topic))
    probe.spin_until(lambda: len(matched) == 3 and min(matched.values()) >= 1, 90.0,
                     "the probe's subscriptions matched the simulation's publishers")
    env = RosBoatEnv(str(path), task=TASK, node_name="learning_harness", timeout=90.0)
    try:
        readings, rollouts = [0], []
        for seed in (7, 7, 8):
            rollouts.append(_rollout(env, seed))
            probe.spin_for(0.3)
            readings.append(len(imu))
        first, again, other = rollouts
        # the same seed: the same episode to the last bit; another: another waypoint
        assert np.array_equal(first, again)
        assert not np.array_equal(first[0], other[0])
        # the in-process environment: the same trajectory (odometry's reference point turned
        # into the centre of mass and back costs rounding only)
        local = _rollout(BoatEnv(str(path), task=TASK), 7)
        np.testing.assert_allclose(first, local, rtol=0, atol=1e-9)
        assert first[5][6] > 0.1 and first[-1][-1]  # under way, and truncated after 1 s
        # sensor noise seeded by the reset: the same seed reads the same
        episodes = [imu[readings[k]:readings[k + 1]] for k in range(3)]
        gyro = [[m.angular_velocity.x for m in e] for e in episodes]
        assert len(gyro[0]) == 10 and gyro[0] == gyro[1] and gyro[0] != gyro[2]

        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            check_env(env, skip_render_check=True)
        assert all("infinity" in str(w.message) for w in caught), [str(w.message) for w in
                                                                  caught]
        _placed_and_refused(env, probe, odom, first)
    finally:
        env.close()
    probe.spin_for(0.3)
    # never back (repeated while it holds)
    assert len(clocks) > 300 and all(b >= a for a, b in itertools.pairwise(clocks))
    assert sim.stop() == 0, sim.output()
    with AnyReader([tmp_path / "bag"]) as reader:
        conns = [c for c in reader.connections if c.topic == names.WAVE_FIELD]
        fields = [reader.deserialize(raw, c.msgtype) for c, _, raw in reader.messages(conns)]
    stamps = [_ns(f.header.stamp) for f in fields]
    # the run's time 0, then each episode's: a reset is the wave field again, stamped later
    assert stamps[0] == 0 and len(stamps) >= 5 and stamps == sorted(set(stamps))


def _placed_and_refused(env, probe, odom, first):
    """A reset to a given state: odom says it; bad requests refused by field and value."""
    client = probe.node.create_client(Reset, names.RESET)
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = 10.0, -5.0, 0.2
    pose.orientation.z, pose.orientation.w = math.sin(0.4), math.cos(0.4)
    twist = Twist()
    twist.linear.x, twist.angular.z = 1.5, 0.1
    answer = probe.call(client, Reset.Request(seed=1, names=[""], poses=[pose], twists=[twist]))
    assert answer.success, answer.message
    probe.spin_until(lambda: odom and _ns(odom[-1].header.stamp) == _ns(answer.stamp), 10.0,
                     "the placed boat's odom")
    got = odom[-1]
    assert (got.pose.pose.position.x, got.pose.pose.position.y) == pytest.approx(
        (10.0, -5.0), abs=1e-12)
    assert got.pose.pose.position.z == pytest.approx(0.2, abs=1e-12)
    assert got.pose.pose.orientation.z == pytest.approx(math.sin(0.4), abs=1e-15)
    assert got.twist.twist.linear.x == pytest.approx(1.5, abs=1e-12)
    assert got.twist.twist.angular.z == pytest.approx(0.1, abs=1e-15)
    bad = Pose()
    bad.position.y = math.nan
    for request, match in [
        (Reset.Request(names=["ghost"], poses=[Pose()]), "names[0]: 'ghost' is not allowed"),
        (Reset.Request(names=[""], poses=[bad]), "poses[0].position.y: nan is not allowed"),
        (Reset.Request(names=[""], poses=[Pose(orientation=Quaternion(w=2.0))]),
         "poses[0].orientation: [0.0, 0.0, 0.0, 2.0] is not allowed: a unit quaternion"),
        (Reset.Request(seed=-2), "seed: -2 is not allowed"),
        (Reset.Request(names=[""], poses=[]), "poses: 0 given for 1 names"),
    ]:
        answer = probe.call(client, request)
        assert not answer.success and match in answer.message, answer.message
    # refused, the simulation goes on as it was: the environment's next episode
    env.reset(seed=7)
    obs, *_ = env.step(ACTIONS[0])
    np.testing.assert_array_equal(obs, first[1][:-2])
