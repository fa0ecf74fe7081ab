"""`boatsim plot BAG`: trajectory, attitude, speed and wrench sources of a recorded run."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from boat_dynamics.physics.rigid_body import quat_to_euler
from boat_dynamics.tools.bags import BagError, read_bag
from boat_msgs_py import names

__all__ = ["plot_bag"]



def plot_bag(bag: str | Path, out: str | Path | None = None) -> Path:
    """Draw every boat of a bag into one PNG (headless); returns the file written.

    Panels: trajectory in the plane; heave, roll and pitch; speed; the force of each
    wrench source (body-frame magnitude). Boats are found by their ``odom`` topics.

    Raises:
        BagError: unreadable bag or no odometry in it.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bag = Path(bag)
    messages = read_bag(bag)
    odoms = sorted(t for t in messages if names.boat_of(t, names.ODOM) is not None)
    if not odoms:
        raise BagError(f"{bag}: no odom topic to plot (topics: {', '.join(sorted(messages))})")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9), constrained_layout=True)
    (ax_xy, ax_att), (ax_speed, ax_force) = axes
    for topic in odoms:
        boat = names.boat_of(topic, names.ODOM)
        label = boat or "boat"
        rows = messages[topic]
        t = np.array([s for s, _ in rows]) / 1e9
        p = np.array([(m.pose.pose.position.x, m.pose.pose.position.y, m.pose.pose.position.z)
                      for _, m in rows])
        q = np.array([(m.pose.pose.orientation.x, m.pose.pose.orientation.y,
                       m.pose.pose.orientation.z, m.pose.pose.orientation.w) for _, m in rows])
        v = np.array([(m.twist.twist.linear.x, m.twist.twist.linear.y) for _, m in rows])
        rp = np.degrees(np.array([quat_to_euler(x)[:2] for x in q]))
        ax_xy.plot(p[:, 0], p[:, 1], label=label)
        ax_xy.plot(p[:1, 0], p[:1, 1], "o", color=ax_xy.lines[-1].get_color())
        ax_att.plot(t, p[:, 2], label=f"{label} heave z [m]")
        ax_att.plot(t, rp[:, 0] / 10, "--", label=f"{label} roll [10 deg]")
        ax_att.plot(t, rp[:, 1] / 10, ":", label=f"{label} pitch [10 deg]")
        ax_speed.plot(t, np.hypot(v[:, 0], v[:, 1]), label=label)
        for source in names.WRENCH_SOURCES:
            wrench = messages.get(names.wrench_topic(boat, source))
            if not wrench:
                continue
            tw = np.array([s for s, _ in wrench]) / 1e9
            f = np.array([(m.wrench.force.x, m.wrench.force.y, m.wrench.force.z)
                          for _, m in wrench])
            ax_force.plot(tw, np.linalg.norm(f, axis=1) / 1e3, label=f"{label} {source}")
    ax_xy.set(title="trajectory (world, ENU; o = start)", xlabel="x east [m]",
              ylabel="y north [m]")
    ax_xy.set_aspect("equal", adjustable="datalim")
    ax_att.set(title="heave and attitude", xlabel="t [s]")
    ax_speed.set(title="speed over ground", xlabel="t [s]", ylabel="[m/s]")
    ax_force.set(title="wrench sources, |force| (body frame)", xlabel="t [s]", ylabel="[kN]")
    for ax in axes.ravel():
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"boatsim: {bag.name}")
    target = Path(out) if out else bag.with_suffix(".png")
    fig.savefig(target, dpi=100)
    plt.close(fig)
    return target
