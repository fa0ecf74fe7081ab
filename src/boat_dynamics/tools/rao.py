"""`boatsim rao SCENARIO`: a boat's heave, roll and pitch RAOs, simulated and by potential flow.

Each point runs the boat alone in one small regular wave
(:func:`boat_dynamics.physics.experiments.seakeeping.regular_wave_response`); when the boat has a
potential-flow coefficient file, the frequency-domain RAO of that file is printed and drawn
beside it (:func:`boat_dynamics.physics.experiments.seakeeping.potential_flow_rao`), so a user can
check their own hull against theory. At a ``speed`` the boat is towed on a carriage, as in a towing
tank, and meets the waves at the encounter frequency omega_e = omega - k U cos(beta): the
table gives it, and the plot draws against it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.tuning import derive
from boat_dynamics.physics.experiments.seakeeping import (
    MIN_ENCOUNTERS,
    Response,
    encounter_frequency,
    potential_flow_rao,
    regular_wave_response,
    rides,
    rigid_body_matrix,
)
from boat_dynamics.physics.scenario import BoatSpec, Scenario
from ocean_sim.physics.waves import angular_frequency

__all__ = ["DEFAULT_DIRECTIONS_DEG", "DEFAULT_WAVELENGTHS", "RaoError", "RaoPoint",
           "format_table", "plot_raos", "rao_points", "theory_curve"]

#: Wavelengths, in boat lengths, of a default run.
DEFAULT_WAVELENGTHS = (0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0)
#: Heave stays in m/m; roll and pitch go from rad/m to deg/m.
_DEG = np.array([1.0, 180 / math.pi, 180 / math.pi])

#: Wave directions (travelling toward, relative to the bow) of a default run: head, beam seas.
DEFAULT_DIRECTIONS_DEG = (180.0, 90.0)
#: m/s, the largest towing speed ahead or astern (the ``carriage`` key's bound).
MAX_SPEED = 50.0
#: The dofs a carriage holds: surge, sway, yaw.
_CARRIAGE = (0, 1, 5)
#: s of simulated time a point may take at most (:func:`.seakeeping.regular_wave_response`).
MAX_TIME = 300.0


class RaoError(ValueError):
    """A request ``boatsim rao`` cannot run: which option, which value, what is allowed."""


@dataclass(frozen=True)
class RaoPoint:
    """One simulated response and, with coefficients, potential flow's (heave, roll, pitch).

    Attributes:
        response: the simulated first harmonic per metre of wave.
        theory: (3,) |heave| m/m, |roll| and |pitch| rad/m by potential flow, or None.
    """

    response: Response
    theory: np.ndarray | None


def _boat(scenario: Scenario, name: str | None) -> BoatSpec:
    """The boat called ``name`` (None: the first one)."""
    if name is None:
        return scenario.boats[0]
    for boat in scenario.boats:
        if boat.name == name:
            return boat
    names = ", ".join(repr(b.name) for b in scenario.boats)
    raise RaoError(f"--boat: {name!r} is not a boat of the scenario (its boats: {names})")


def _check(wavelengths: Sequence[float], directions_deg: Sequence[float],
           amplitude: float | None, speed: float) -> None:
    for value in wavelengths:
        if not (math.isfinite(value) and 0.05 <= value <= 100.0):
            raise RaoError(f"--wavelengths: {value!r} is not allowed: wavelengths are in boat "
                           f"lengths, from 0.05 to 100")
    for value in directions_deg:
        if not math.isfinite(value):
            raise RaoError(f"--directions-deg: {value!r} is not allowed: a finite angle")
    if amplitude is not None and not (math.isfinite(amplitude) and amplitude > 0.0):
        raise RaoError(f"--amplitude: {amplitude!r} is not allowed: metres, > 0")
    if not (math.isfinite(speed) and abs(speed) <= MAX_SPEED):
        raise RaoError(f"--speed: {speed!r} is not allowed: m/s ahead (negative: astern), "
                       f"from -{MAX_SPEED:g} to {MAX_SPEED:g}")


def _met(wavelength: float, direction: float, speed: float, gravity: float, depth: float
         ) -> float:
    """rad/s, |omega_e| of the wave; RaoError if the boat would ride it."""
    k = 2 * math.pi / wavelength
    encounter = abs(encounter_frequency(float(angular_frequency(k, gravity, depth)), k, speed,
                                        direction))
    if rides(encounter, MAX_TIME):
        raise RaoError(f"--speed: {speed!r} m/s rides the wave of {wavelength:.3g} m from "
                       f"{math.degrees(direction):g} deg (encounter frequency "
                       f"{encounter:.3g} rad/s: fewer than {MIN_ENCOUNTERS} encounters in "
                       f"{MAX_TIME:g} s); "
                       f"leave out that wavelength or direction")
    return encounter


def rao_points(scenario: Scenario, boat: str | None = None,
               wavelengths: Sequence[float] = DEFAULT_WAVELENGTHS,
               directions_deg: Sequence[float] = DEFAULT_DIRECTIONS_DEG,
               amplitude: float | None = None, speed: float = 0.0) -> list[RaoPoint]:
    """Run the scenario's boat in each regular wave (direction-major order).

    Args:
        scenario: as read (its sea is replaced by each regular wave; its gravity and depth
            are kept).
        boat: the boat's name (None: the first).
        wavelengths: in boat lengths.
        directions_deg: the waves' direction of travel relative to the bow, degrees
            (180 head seas, 90 beam seas from starboard, 0 following seas).
        amplitude: m; default 0.5 % of the boat length, at most a steepness k a of 0.05.
        speed: m/s ahead on a towing carriage (0: held by a soft mooring); the scenario's
            own mooring or carriage is replaced.

    Raises:
        RaoError: an option out of range, a wave the boat would ride, or an unknown boat.
    """
    _check(wavelengths, directions_deg, amplitude, speed)
    spec = _boat(scenario, boat)
    params, sea = spec.params, scenario.sea
    length = params.hull.length
    directions = np.radians(np.asarray(directions_deg, dtype=float))
    for direction in directions:
        for multiple in wavelengths:
            _met(multiple * length, float(direction), speed, sea.gravity, sea.depth)
    curve = theory_curve(params, sea.gravity, sea.depth, speed)
    points = []
    for direction in directions:
        for multiple in wavelengths:
            wavelength = multiple * length
            a = amplitude or min(0.005 * length, 0.05 * wavelength / (2 * math.pi))
            r = regular_wave_response(params, wavelength, float(direction), a,
                                      gravity=sea.gravity, depth=sea.depth,
                                      max_time=MAX_TIME, speed=speed)
            theory = None if curve is None else curve(np.array([wavelength]),
                                                      float(direction))[0]
            points.append(RaoPoint(r, theory))
    return points


def format_table(points: Sequence[RaoPoint], length: float) -> str:
    """The points as a text table: heave m/m, roll and pitch deg/m, potential flow beside."""
    lines = ["direction_deg  lambda/L  lambda_m  omega_rad_s  heave_m/m (pf)  "
             "roll_deg/m (pf)  pitch_deg/m (pf)  omega_e_rad_s"]
    for p in points:
        r = p.response
        sim = (r.heave, math.degrees(r.roll), math.degrees(r.pitch))
        pf = (("-",) * 3 if p.theory is None
              else (f"{p.theory[0]:.3f}", f"{math.degrees(p.theory[1]):.2f}",
                    f"{math.degrees(p.theory[2]):.2f}"))
        lines.append(f"{math.degrees(r.direction):13.1f}  {r.wavelength / length:8.2f}  "
                     f"{r.wavelength:8.2f}  {r.omega:11.3f}  {sim[0]:6.3f} ({pf[0]:>6})  "
                     f"{sim[1]:7.2f} ({pf[1]:>6})  {sim[2]:7.2f} ({pf[2]:>6})  "
                     f"{r.encounter:13.3f}")
    return "\n".join(lines)


def theory_curve(params: BoatParams, gravity: float, depth: float, speed: float = 0.0
                 ) -> Callable[[np.ndarray, float], np.ndarray] | None:
    """Potential flow's |heave|, |roll|, |pitch| at wavelengths (m) and a direction (rad).

    At a ``speed`` (m/s), that of a boat on a carriage (surge, sway and yaw held) with the
    zero-speed coefficients at the encounter frequency and the speed terms the simulation
    carries (:func:`.seakeeping.potential_flow_rao`).

    With the boat's own linear viscous damping in roll, pitch and yaw (on its rates, as it is
    stepped; its viscous heave, sway and surge damping act on the velocity through the moving
    water and are left out). None for a boat without coefficients.
    """
    if params.hydro is None:
        return None
    mass = rigid_body_matrix(params)
    viscous = np.zeros(6)
    viscous[3:] = (derive(params) if params.derive is not None else params).damping_linear[3:]

    def curve(wavelengths: np.ndarray, direction: float) -> np.ndarray:
        k = 2 * math.pi / np.asarray(wavelengths, dtype=float)
        omega = angular_frequency(k, gravity, depth)
        return np.array([np.abs(potential_flow_rao(
            params.hydro, mass, float(w), direction, viscous,
            encounter_frequency(float(w), float(kk), speed, direction), speed,
            _CARRIAGE if speed else ())[2:5])
            for w, kk in zip(omega, k, strict=True)])

    return curve


def plot_raos(points: Sequence[RaoPoint], length: float, out: str | Path,
              title: str = "", theory=None, gravity: float = 9.81,
              depth: float = math.inf) -> Path:
    """Heave, roll and pitch RAOs against lambda / L (PNG, headless); returns the path.

    Markers: simulated; lines: potential flow on 200 wavelengths between the first and the
    last point (``theory``: :func:`theory_curve`), or through the points' own values. Points
    at a speed are drawn against the encounter frequency |omega_e| (rad/s; the sea's
    ``gravity``, m/s^2, and ``depth``, m, give it for the lines).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), constrained_layout=True)
    directions = sorted({p.response.direction for p in points}, reverse=True)
    for direction in directions:
        row = sorted((p for p in points if p.response.direction == direction),
                     key=lambda p: p.response.wavelength)
        speed = row[0].response.speed

        def axis(wavelengths: np.ndarray, direction=direction, speed=speed) -> np.ndarray:
            if speed == 0.0:
                return wavelengths / length
            k = 2 * math.pi / wavelengths
            return np.abs(encounter_frequency(angular_frequency(k, gravity, depth), k, speed,
                                              direction))

        x = axis(np.array([p.response.wavelength for p in row]))
        sim = np.array([(p.response.heave, math.degrees(p.response.roll),
                         math.degrees(p.response.pitch)) for p in row])
        label = f"{math.degrees(direction):g} deg"
        for k, ax in enumerate(axes):
            line = ax.plot(x, sim[:, k], "o", label=f"boatsim, {label}")[0]
            if theory is not None:
                ends = (row[0].response.wavelength, row[-1].response.wavelength)
                dense = np.geomspace(*ends, 200) if len(row) > 1 else np.array(ends[:1])
                pf = theory(dense, direction) * _DEG
                ax.plot(axis(dense), pf[:, k], "--", color=line.get_color(),
                        label=f"potential flow, {label}")
            elif all(p.theory is not None for p in row):
                pf = np.array([p.theory for p in row]) * _DEG
                ax.plot(x, pf[:, k], "--", color=line.get_color(),
                        label=f"potential flow, {label}")
    towed = any(p.response.speed != 0.0 for p in points)
    for ax, name in zip(axes, ("heave, m/m", "roll, deg/m", "pitch, deg/m"), strict=True):
        if towed:
            ax.set_xlabel(f"encounter frequency |omega_e|, rad/s "
                          f"(speed {points[0].response.speed:g} m/s)")
        else:
            ax.set_xscale("log")
            ax.set_xlabel("wavelength / boat length")
        ax.set_ylabel(name)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize="small")
    fig.suptitle(title or "RAOs (centre of mass; direction the waves travel toward, "
                          "relative to the bow: 180 head seas)")
    out = Path(out)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
