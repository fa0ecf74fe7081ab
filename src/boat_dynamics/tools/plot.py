"""`boatsim plot BAG`: one figure per boat of a recorded run, each quantity on its own axis.

Panels, all against the time since the bag's first message but the first: the trajectory
with heading marks; the
commands (throttle, rudder, each named thruster) as the boat held them (the latest wins);
the response (speed over ground, yaw rate); heading; heave; roll and pitch; and the wrench
sources split by direction, surge force and yaw moment, so thrust and rudder are not
flattened beside tens of kN of buoyancy (which acts in z). A series that stays constant is
drawn with zero in view, never on an axis a few parts in a million wide. Headless
(matplotlib's Agg).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_to_euler
from boat_dynamics.physics.core.commands import CommandScript
from boat_dynamics.tools.bags import odometry_topics, read_bag
from boat_msgs_py import names

__all__ = ["PlotError", "plot_bag"]

#: Heading marks drawn along a trajectory.
_HEADING_MARKS = 16
#: The time axes' label: the bag's first message is t = 0 (a real-time run's stamps are the
#: wall clock's, 1.8e9 s from 1970).
_TIME = "t [s since the first message]"
#: A wrench source whose force and moment stay below these is listed as zero, not drawn.
_ZERO_FORCE, _ZERO_MOMENT = 1e-6, 1e-6  # N, N m


class PlotError(ValueError):
    """The figure cannot be written where it was asked (a folder that is a file, no access)."""


def _since_start(messages: dict) -> dict:
    """``messages`` with every stamp counted from the bag's first one (ns)."""
    firsts = [rows[0][0] for rows in messages.values() if rows]
    start = min(firsts) if firsts else 0
    return {topic: [(stamp - start, m) for stamp, m in rows] for topic, rows in messages.items()}


def _readable(fig) -> None:
    """Every autoscaled axis whose lines stay constant shows zero and the value with room.

    A constant (or constant to rounding) series otherwise gets an axis a few parts in a
    million wide, labelled by an offset. Tick labels never use an offset.
    """
    for ax in fig.axes:
        ax.ticklabel_format(axis="y", useOffset=False, style="plain")
        ys = [np.asarray(line.get_ydata(), dtype=float) for line in ax.lines]
        y = np.concatenate(ys) if ys else np.zeros(0)
        y = y[np.isfinite(y)]
        if not ax.get_autoscaley_on() or ax.get_aspect() != "auto" or not y.size:
            continue
        if np.ptp(y) <= 1e-9 * max(1.0, float(np.abs(y).max())):
            lo, hi = min(0.0, float(y.min())), max(0.0, float(y.max()))
            pad = 0.1 * max(hi - lo, 1.0)
            ax.set_ylim(lo - pad, hi + pad)


def _series(rows: list, value) -> tuple[np.ndarray, np.ndarray]:
    """(t s, values) of a topic's (stamp ns, message) rows."""
    return (np.array([s for s, _ in rows], dtype=float) / 1e9,
            np.array([value(m) for _, m in rows], dtype=float))


def _odometry(rows: list) -> dict[str, np.ndarray]:
    """Time, position, roll/pitch/yaw (rad), speed over ground and yaw rate of odom rows."""
    t, p = _series(rows, lambda m: (m.pose.pose.position.x, m.pose.pose.position.y,
                                    m.pose.pose.position.z))
    _, q = _series(rows, lambda m: (m.pose.pose.orientation.x, m.pose.pose.orientation.y,
                                    m.pose.pose.orientation.z, m.pose.pose.orientation.w))
    _, v = _series(rows, lambda m: (m.twist.twist.linear.x, m.twist.twist.linear.y,
                                    m.twist.twist.angular.z))
    euler = np.array([quat_to_euler(x) for x in q]).reshape(-1, 3)
    return {"t": t, "p": p.reshape(-1, 3), "euler": euler,
            "speed": np.hypot(v[:, 0], v[:, 1]) if len(v) else v, "yaw_rate": v[:, 2]
            if len(v) else v}


def _trajectory(ax, odom: dict) -> None:
    p, yaw = odom["p"], odom["euler"][:, 2]
    ax.plot(p[:, 0], p[:, 1], color="tab:blue", lw=1.2)
    ax.plot(p[:1, 0], p[:1, 1], "o", color="tab:green", label="start")
    ax.plot(p[-1:, 0], p[-1:, 1], "s", color="tab:red", label="end")
    marks = np.unique(np.linspace(0, len(p) - 1, _HEADING_MARKS).astype(int))
    span = max(np.ptp(p[:, 0]), np.ptp(p[:, 1]), 1.0)
    ax.quiver(p[marks, 0], p[marks, 1], np.cos(yaw[marks]), np.sin(yaw[marks]),
              angles="xy", scale_units="xy", scale=12.0 / span, width=0.004,
              color="tab:blue", alpha=0.7, label="heading")
    ax.set(title="trajectory (world, ENU)", xlabel="x east [m]", ylabel="y north [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=7, loc="best")


def _steps(ax, rows: list, value, end: float, **style) -> bool:
    """Draw a command topic as held until the next message (or ``end``); False if empty."""
    if not rows:
        return False
    t, y = _series(rows, value)
    ax.step(np.append(t, end), np.append(y, y[-1]), where="post", **style)
    return True


def _script(ax, angle_ax, script: CommandScript, end: float) -> bool:
    """A scenario's scripted throttle and rudder, held from each entry's time (s)."""
    t = np.append(script.times, max(end, script.times[-1]))
    ax.step(t, np.append(script.throttles, script.throttles[-1]), where="post",
            color="tab:blue", lw=2.0, alpha=0.6, label="scripted throttle")
    rudder = np.degrees(np.append(script.rudders, script.rudders[-1]))
    angle_ax.step(t, rudder, where="post", color="tab:orange", lw=2.0, alpha=0.6,
                  label="scripted rudder [deg]")
    return True


def _commands(ax, messages: dict, boat: str, end: float,
              script: CommandScript | None = None) -> None:
    """Throttle (left axis, -1..1) and rudder / thruster angles (right axis, deg).

    Those of the command topics, and the scenario's ``script`` if the boat has one (the run's
    start taken as the bag's first message).
    """
    thrust = messages.get(names.boat_topic(boat, names.CMD_THRUST), [])
    rudder = messages.get(names.boat_topic(boat, names.CMD_RUDDER), [])
    prefix = names.boat_topic(boat, "thrusters") + "/"
    thrusters = sorted(t for t in messages if t.startswith(prefix))
    angle_ax = ax.twinx()
    drawn = script is not None and _script(ax, angle_ax, script, end)
    drawn |= _steps(ax, thrust, lambda m: m.data, end, color="tab:blue",
                    label=names.CMD_THRUST)
    drawn |= _steps(angle_ax, rudder, lambda m: np.degrees(m.data), end, color="tab:orange",
                    label=f"{names.CMD_RUDDER} [deg]")
    for i, topic in enumerate(thrusters):
        name = topic[len(prefix):]
        is_angle = name.endswith("/" + names.THRUSTER_ANGLE)
        drawn |= _steps(angle_ax if is_angle else ax, messages[topic],
                        (lambda m: np.degrees(m.data)) if is_angle else (lambda m: m.data), end,
                        ls="--", color=f"C{i + 2}", label=name + (" [deg]" if is_angle else ""))
    ax.set(title="commands (as held: the latest wins)", xlabel=_TIME,
           ylabel="throttle [-1 .. 1]", ylim=(-1.1, 1.1))
    angle_ax.set_ylabel("angle [deg, + = bow to port]")
    if not drawn:
        ax.text(0.5, 0.5, "no command topics in the bag (none published, or scripted: "
                "--scenario draws a script)",
                ha="center", va="center", transform=ax.transAxes, fontsize=8)
    handles = [h for a in (ax, angle_ax) for h in a.get_legend_handles_labels()[0]]
    if handles:
        ax.legend(handles=handles, fontsize=7, loc="lower left")


def _response(ax, odom: dict) -> None:
    """Speed over ground (left) and yaw rate (right)."""
    ax.plot(odom["t"], odom["speed"], color="tab:blue", label="speed over ground")
    ax.set(title="response: speed and yaw rate", xlabel=_TIME, ylabel="speed [m/s]")
    rate_ax = ax.twinx()
    rate_ax.plot(odom["t"], np.degrees(odom["yaw_rate"]), color="tab:purple",
                 label="yaw rate")
    rate_ax.set_ylabel("yaw rate [deg/s, + = to port]")
    handles = ax.get_legend_handles_labels()[0] + rate_ax.get_legend_handles_labels()[0]
    ax.legend(handles=handles, fontsize=7, loc="upper left")


def _motions(axes, odom: dict) -> None:
    """Heading, heave, and roll with pitch, each on its own axis with its unit."""
    ax_heading, ax_heave, ax_att = axes
    t = odom["t"]
    ax_heading.plot(t, np.degrees(np.unwrap(odom["euler"][:, 2])), color="tab:blue")
    ax_heading.set(title="heading (yaw, unwrapped)", xlabel=_TIME,
                   ylabel="yaw [deg, 0 = east, + = CCW]")
    ax_heave.plot(t, odom["p"][:, 2], color="tab:cyan")
    ax_heave.set(title="heave (hull reference point)", xlabel=_TIME, ylabel="z [m]")
    ax_att.plot(t, np.degrees(odom["euler"][:, 0]), color="tab:red", label="roll")
    ax_att.plot(t, np.degrees(odom["euler"][:, 1]), color="tab:green", label="pitch")
    ax_att.set(title="roll and pitch", xlabel=_TIME, ylabel="[deg]")
    ax_att.legend(fontsize=7, loc="upper right")


def _wrenches(axes, messages: dict, boat: str) -> None:
    """Surge force and yaw moment of each wrench source (body frame); zero ones listed."""
    ax_fx, ax_mz = axes
    zero = []
    for i, source in enumerate(names.WRENCH_SOURCES):
        rows = messages.get(names.wrench_topic(boat, source))
        if not rows:
            continue
        t, w = _series(rows, lambda m: (m.wrench.force.x, m.wrench.force.y, m.wrench.force.z,
                                        m.wrench.torque.z))
        if np.abs(w[:, :3]).max() < _ZERO_FORCE and np.abs(w[:, 3]).max() < _ZERO_MOMENT:
            zero.append(source)
            continue
        style = {"color": f"C{i}", "lw": 1.6 if source in ("thrust", "rudder") else 1.0,
                 "label": source}
        ax_fx.plot(t, w[:, 0] / 1e3, **style)
        ax_mz.plot(t, w[:, 3] / 1e3, **style)
    ax_fx.set(title="surge force by source, body x", xlabel=_TIME, ylabel="[kN]")
    ax_mz.set(title="yaw moment by source, body z", xlabel=_TIME,
              ylabel="[kN m, + = to port]")
    for ax in axes:
        if zero:
            ax.text(0.01, 0.02, f"zero all along: {', '.join(zero)}", transform=ax.transAxes,
                    fontsize=7, color="0.4")
        if ax.lines:
            ax.legend(fontsize=7, ncol=4, loc="upper center", bbox_to_anchor=(0.5, -0.16))
        else:
            ax.text(0.5, 0.5, "no wrench topics in the bag", ha="center", va="center",
                    transform=ax.transAxes, fontsize=8)


def _figure(messages: dict, boat: str, title: str, script: CommandScript | None = None):
    """The boat's figure (matplotlib), its stamps already counted from the start."""
    import matplotlib.pyplot as plt

    odom = _odometry(messages[names.boat_topic(boat, names.ODOM)])
    fig, axes = plt.subplots(4, 2, figsize=(12, 15), constrained_layout=True)
    _trajectory(axes[0, 0], odom)
    _commands(axes[0, 1], messages, boat, float(odom["t"][-1]) if len(odom["t"]) else 0.0,
              script)
    _response(axes[1, 0], odom)
    _motions((axes[1, 1], axes[2, 0], axes[2, 1]), odom)
    _wrenches((axes[3, 0], axes[3, 1]), messages, boat)
    for ax in axes.ravel():
        ax.grid(True, alpha=0.3)
    _readable(fig)
    fig.suptitle(title)
    return fig


def plot_bag(bag: str | Path, out: str | Path | None = None,
             scenario: str | Path | None = None) -> list[Path]:
    """Draw each boat of a bag into a PNG of its own (headless); returns the files written.

    One boat: ``out`` (default: the bag's path with ``.png``). Several: ``out``'s name with
    ``_<boat>`` before the suffix. Boats are found by their ``odom`` topics; the output's
    folder is made if missing. ``scenario``: the run's scenario file, whose boats' scripted
    commands are drawn (they are on no topic).

    Raises:
        BagError: unreadable bag or no odometry in it.
        PlotError: the figure cannot be written at ``out`` (nothing is left half-written).
        ScenarioError: ``scenario`` is not a valid scenario.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bag = Path(bag)
    boats = sorted(odometry_topics(bag).values())  # BagError: none of the right type
    messages = _since_start(read_bag(bag))
    scripts = {}
    if scenario is not None:
        from boat_dynamics.physics.scenario import load_scenario

        scripts = {b.name: b.commands for b in load_scenario(scenario).boats}
    target = Path(out) if out else bag.with_suffix(".png")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise PlotError(f"cannot make the folder {target.parent} for {target.name}: "
                        f"{exc.strerror or exc}") from None
    written = []
    for boat in boats:
        path = target if len(boats) == 1 else target.with_name(
            f"{target.stem}_{boat or 'boat'}{target.suffix or '.png'}")
        fig = _figure(messages, boat, f"boatsim: {bag.name}, boat {boat or '(root namespace)'}",
                      scripts.get(boat))
        try:
            fig.savefig(path, dpi=100)
        except OSError as exc:
            raise PlotError(f"cannot write {path}: {exc.strerror or exc}") from None
        finally:
            plt.close(fig)
        written.append(path)
    return written
