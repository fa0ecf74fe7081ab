"""Steer a batch of boats to their waypoints through the Gymnasium environment (no ROS).

A proportional helmsman, not a learner: the rudder turns the bow towards the waypoint
(observation ``waypoint_port`` against ``waypoint_ahead``), the throttle is full. Sixteen
copies of the scenario's boat sail in one batch (``BoatVectorEnv``: one physics step for all);
each arrives within the task's radius or runs out of time.

Run it with the venv's Python (``make setup``)::

    .venv/bin/python examples/gym_waypoints.py [SCENARIO] [--boats N] [--seed S]
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from boat_dynamics.gym import OBSERVATION_FIELDS, BoatVectorEnv, Task
from boat_dynamics.physics.scenario import default_scenario_path

AHEAD = OBSERVATION_FIELDS.index("waypoint_ahead")
PORT = OBSERVATION_FIELDS.index("waypoint_port")
#: rad of rudder per rad of bearing to the waypoint.
GAIN = 1.5


def helmsman(observations: np.ndarray, max_rudder: float) -> np.ndarray:
    """(N, 2) actions: full throttle, rudder towards each waypoint (rad, + to port)."""
    bearing = np.arctan2(observations[:, PORT], observations[:, AHEAD])
    rudder = np.clip(GAIN * bearing, -max_rudder, max_rudder)
    return np.column_stack([np.ones(len(observations)), rudder])


def main(argv: list[str] | None = None) -> int:
    """Sail one episode per boat; print how many arrived and their returns."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenario", nargs="?", default=str(default_scenario_path()))
    parser.add_argument("--boats", type=int, default=16)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    task = Task(episode_time=60.0, waypoint_range=(15.0, 30.0))
    envs = BoatVectorEnv(args.scenario, args.boats, task=task)
    max_rudder = float(envs.single_action_space.high[1])
    observations, _ = envs.reset(seed=args.seed)
    returns = np.zeros(args.boats)
    arrived = np.zeros(args.boats, bool)
    done = np.zeros(args.boats, bool)
    for _ in range(math.ceil(task.episode_time / task.control_period)):
        observations, reward, terminated, truncated, _ = envs.step(
            helmsman(observations, max_rudder))
        returns += np.where(done, 0.0, reward)  # after its episode: the next one's
        arrived |= terminated & ~done & (reward > 0.0)
        done |= terminated | truncated
        if done.all():
            break
    print(f"{arrived.sum()} of {args.boats} boats arrived; returns "
          f"{returns.min():.1f} .. {returns.max():.1f} (mean {returns.mean():.1f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
