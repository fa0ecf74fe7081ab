"""Drive scenarios/wake_crossing.yaml without ROS, with and without the launch's wake, and plot.

The launch runs straight; the work boat crosses its track 25-40 m behind it. The picture: the
sea and the launch's Kelvin wake when the work boat is in it (plan view, both tracks), and the
work boat's roll and heave and the made waves' vertical force on it over time, beside the same
run with the launch making no waves (``made_waves: none``).

    .venv/bin/python examples/wake_crossing.py docs/images/wake_crossing.png
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_to_euler, rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.model import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.scenario import Scenario, load_scenario
from boat_dynamics.physics.wave_making.interaction import made_waves_elevation
from ocean_sim.physics.waves import sample_surface

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "scenarios" / "wake_crossing.yaml"


def scenario(made: str = "all") -> Scenario:
    """The scenario, its launch making waves (``all``) or not (``none``)."""
    sc = load_scenario(SCENARIO)
    launch = sc.boats[0]
    return replace(sc, boats=(replace(launch, params=replace(launch.params, made_waves=made)),
                              *sc.boats[1:]))


def drive(sc: Scenario, seconds: float = 30.0) -> dict[str, np.ndarray]:
    """The boats' tracks and the work boat's motions, every 0.1 s, over ``seconds``."""
    system, state = pipeline.start(sc.boats, sc.sea)
    dt = 1.0 / sc.simulation.rate_hz
    rows: dict[str, list] = {k: [] for k in ("t", "xy", "velocity", "roll", "heave", "fz")}
    for k in range(round(seconds / dt)):
        inputs = FleetInputs.stack([BoatInputs(*b.commands.at(state.t)) for b in sc.boats])
        done = pipeline.step(system, state, inputs, sc.sea, dt)
        state = done.state
        if k % 10 == 0:
            rot = rotation_matrix(state.orientation)
            rows["t"].append(state.t)
            rows["xy"].append((state.position - np.einsum("bij,bj->bi", rot,
                                                          system.center_of_mass))[:, :2])
            rows["velocity"].append(np.einsum("bij,bj->bi", rot, state.velocity)[:, :2])
            rows["roll"].append(math.degrees(quat_to_euler(state.orientation[1])[0]))
            rows["heave"].append(state.position[1, 2])
            rows["fz"].append(done.forces.made_waves.force[1, 2])
    out = {k: np.array(v) for k, v in rows.items()}
    out["ships"] = [p.thin_ship for p in system.params]
    return out


def main(path: str) -> None:
    """Drive both runs and draw the picture into ``path`` (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sc, runs = scenario(), {made: drive(scenario(made)) for made in ("all", "none")}
    run = runs["all"]
    i = int(np.argmin(np.abs(run["xy"][:, 1, 1])))  # the work boat on the launch's track
    launch = run["xy"][i, 0]
    west = min(launch[0] - 60.0, float(run["xy"][:, 1, 0].min()) - 10.0)
    gx, gy = np.meshgrid(np.linspace(west, launch[0] + 10, 4 * int(launch[0] + 10 - west) + 1),
                         np.linspace(-30, 30, 241), indexing="xy")
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    sea = sample_surface(sc.sea, xy, run["t"][i]).heights
    wake = made_waves_elevation(run["ships"][:1], run["xy"][i, :1], run["velocity"][i, :1], xy,
                                sc.sea.gravity)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), width_ratios=[1.3, 1])
    ax = axes[0]
    shown = ax.pcolormesh(gx, gy, (sea + wake).reshape(gx.shape), cmap="RdBu_r",
                          vmin=-0.5, vmax=0.5, shading="auto")
    fig.colorbar(shown, ax=ax, label="surface elevation, m")
    for b, colour in ((0, "k"), (1, "tab:orange")):
        ax.plot(run["xy"][: i + 1, b, 0], run["xy"][: i + 1, b, 1], colour, lw=1.5,
                label=sc.boats[b].name)
    ax.plot(run["xy"][i:, 1, 0], run["xy"][i:, 1, 1], "tab:orange", lw=0.8, ls=":",
            label="crosser, later")
    alone = runs["none"]["xy"][:, 1]
    ax.plot(alone[:, 0], alone[:, 1], "tab:orange", lw=0.8, ls="--",
            label="crosser, launch making no waves")
    edge = np.array([[0.0, 0.0], [-60.0, 60.0 / math.sqrt(8.0)]])
    for sign in (1, -1):
        ax.plot(launch[0] + edge[:, 0], launch[1] + sign * edge[:, 1], "k:", lw=0.8)
    ax.set(aspect="equal", xlabel="x, m (east)", ylabel="y, m (north)",
           title=f"t = {run['t'][i]:.1f} s: the launch's wake (19.47 deg dotted) and the sea")
    ax.legend(loc="lower left")
    ax = axes[1]
    for made, style in (("all", "-"), ("none", "--")):
        r = runs[made]
        ax.plot(r["t"], r["roll"], "tab:orange", ls=style, label=f"roll, deg (launch: {made})")
        ax.plot(r["t"], 100 * (r["heave"] - r["heave"][0]), "tab:blue", ls=style,
                label=f"heave, cm (launch: {made})")
    ax.plot(run["t"], run["fz"] / 1000.0, "k", lw=0.8, label="made waves' heave force, kN")
    ax.set(xlabel="t, s", title="the work boat crossing the wake")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "wake_crossing.png")
