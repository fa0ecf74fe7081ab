"""Drive scenarios/harbour.yaml's boats for a minute without ROS and draw the plan.

The USV goes north up the channel at full thrust and turns to port after 20 s; the ferry
runs its script across the channel. The picture: the obstacles, both tracks, where contact
pushed a boat (dots), the two channel buoys where they drifted on their lines, and the USV's
2-D scanner's last scan (its returns as points).

    .venv/bin/python examples/harbour_plan.py docs/images/harbour.png
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.model import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.scenario import load_scenario
from boat_dynamics.physics.sensors import LidarSpec, measure_lidar, stream_key
from boat_dynamics.physics.sensors.lidar import lidar_directions
from boat_dynamics.physics.world.obstacles import Prism
from ocean_sim.physics.waves import sample_surface

ROOT = Path(__file__).resolve().parents[1]


def drive(seconds: float = 60.0):
    """(T, B, 3) reference points, (T, B) contact force magnitudes (N), the last state."""
    scenario = load_scenario(ROOT / "scenarios" / "harbour.yaml")
    system, state = pipeline.start(scenario.boats, scenario.sea)
    dt, track, pushed = 1.0 / scenario.simulation.rate_hz, [], []
    for _ in range(int(seconds / dt)):
        rudder = 0.3 if 20.0 <= state.t < 26.0 else 0.0
        inputs = FleetInputs.stack([BoatInputs(1.0, rudder), BoatInputs(0.8, 0.0)]
                                   + [BoatInputs(0.0, 0.0)] * (len(scenario.boats) - 2))
        done = pipeline.step(system, state, inputs, scenario.sea, dt,
                             environment=scenario.environment, world=scenario.world)
        state = done.state
        rot = rotation_matrix(state.orientation)
        track.append(state.position - np.einsum("bij,bj->bi", rot, system.center_of_mass))
        pushed.append(np.linalg.norm(done.forces.collision.force, axis=1))
    return scenario, system, state, np.array(track), np.array(pushed)


def scan_points(scenario, system, state) -> np.ndarray:
    """(N, 2) m, world: the USV's scanner's returns at ``state``."""
    spec = next(s for s in scenario.boats[0].sensors if isinstance(s, LidarSpec))
    rot = rotation_matrix(state.orientation)
    ref = state.position - np.einsum("bij,bj->bi", rot, system.center_of_mass)
    ranges = measure_lidar(spec, stream_key(0, "usv", spec.name), 0, rot[0], ref[0],
                           scenario.world, (system.footprints, rot, ref),
                           lambda xy: sample_surface(scenario.sea, xy, state.t).heights, own=0)
    hit = np.isfinite(ranges)
    origin = ref[0] + rot[0] @ spec.position
    return (origin + (lidar_directions(spec)[hit] * ranges[hit, None]) @ rot[0].T)[:, :2]


def main(out: str) -> None:
    """Drive, then draw the plan into ``out`` (a PNG)."""
    scenario, system, state, track, pushed = drive()
    fig, ax = plt.subplots(figsize=(7, 6))
    for o in scenario.world.obstacles:
        if isinstance(o, Prism):
            ax.fill(*o.points.T, color="0.65")
        else:
            ax.add_patch(plt.Circle(o.center, o.radius, color="0.3"))
    for i, boat in enumerate(scenario.boats):
        if boat.kind == "buoy":  # its watch circle's worth of drift, and where it ends
            colour = "red" if "red" in boat.name else "green"
            ax.plot(track[:, i, 0], track[:, i, 1], color=colour, linewidth=0.8)
            ax.add_patch(plt.Circle(track[-1, i, :2], boat.params.hull.length / 2,
                                    color=colour))
            continue
        ax.plot(track[:, i, 0], track[:, i, 1], label=boat.name)
        hit = pushed[:, i] > 0.0
        ax.plot(track[hit, i, 0], track[hit, i, 1], ".", color="red", markersize=3)
    seen = scan_points(scenario, system, state)
    ax.plot(seen[:, 0], seen[:, 1], ".", color="black", markersize=2, label="scanner's returns")
    ax.set(xlim=(-50, 50), ylim=(-10, 80), aspect="equal", xlabel="x east (m)",
           ylabel="y north (m)", title="scenarios/harbour.yaml, 60 s (red: in contact)")
    ax.legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "harbour.png")
