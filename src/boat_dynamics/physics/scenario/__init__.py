"""Scenario files (YAML): parsing and validation into frozen specs, nothing more.

The reader computes no physics: what a boat's own hydrostatics fix (its equilibrium, the
damping the file leaves to derive) is asked for in ``BoatParams.derive``, and the boats start
at rest at their initial poses; :func:`boat_dynamics.physics.pipeline.init` derives it and
sets them afloat, once.

The keys are the public contract of docs/DESIGN.md ("Scenario file"). Every refusal raises
:class:`ScenarioError` naming the key (as a path such as ``boats[0].hull.length``), the value
and what is allowed. Pure Python + numpy; never imports rclpy. The parts: :mod:`.specs` (what
a file is read into), :mod:`.read` (typed value readers), :mod:`.sea` (``simulation``,
``ocean``), :mod:`.boat` (a boat, in key order) and :mod:`.models` (its model blocks).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from boat_dynamics.physics.scenario.boat import DEFAULT_CRITICAL_RATIO, boat_block
from boat_dynamics.physics.scenario.read import mapping, only
from boat_dynamics.physics.scenario.sea import environment_block, ocean_block, simulation_block
from boat_dynamics.physics.scenario.specs import (
    BoatSpec,
    Scenario,
    ScenarioError,
    SimulationSettings,
)

__all__ = [
    "DEFAULT_CRITICAL_RATIO",
    "BoatSpec",
    "Scenario",
    "ScenarioError",
    "SimulationSettings",
    "default_scenario_path",
    "load_scenario",
    "parse_scenario",
]


def default_scenario_path() -> Path:
    """Path of the shipped default scenario (scenarios/default.yaml)."""
    return Path(__file__).resolve().parents[4] / "scenarios" / "default.yaml"


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a scenario file.

    Raises:
        ScenarioError: unreadable file, bad YAML, or an invalid key or value.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ScenarioError("file", str(p), f"must be a readable file ({exc.strerror})") from exc
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "somewhere"
        raise ScenarioError("file", str(p), f"must be valid YAML (error at {where})") from exc
    return parse_scenario({} if data is None else data, source=str(p), base_dir=p.parent)


# --------------------------------------------------------------------------- readers


def parse_scenario(data: Any, source: str = "<scenario>", base_dir: Path | None = None
                   ) -> Scenario:
    """Validate a scenario given as parsed YAML (nested dicts and lists).

    Relative mesh paths are resolved against ``base_dir`` (the scenario file's directory;
    default: the current directory).

    Raises:
        ScenarioError: an invalid key or value, named by its path.
    """
    d = mapping(data, "")
    only(d, "", ("simulation", "ocean", "environment", "boats"))
    sim = simulation_block(d.get("simulation"))
    sea = ocean_block(d.get("ocean"), sim)
    environment = environment_block(d.get("environment"), sim.seed)
    boats_raw = d.get("boats")
    if boats_raw is None:
        boats_raw = [{}]
    if not isinstance(boats_raw, list) or not boats_raw:
        raise ScenarioError("boats", boats_raw, "must be a non-empty list of boats")
    lone = len(boats_raw) == 1
    base = Path.cwd() if base_dir is None else base_dir
    loaded: dict = {}  # coefficient files, shared by the boats that name the same one
    boats = tuple(boat_block(b, f"boats[{i}]", sim, lone, base, sea.depth, loaded)
                  for i, b in enumerate(boats_raw))
    names = [b.name for b in boats]
    for i, n in enumerate(names):
        if names.index(n) != i:
            raise ScenarioError(f"boats[{i}].name", n, "must be unique among the boats")
    return Scenario(simulation=sim, sea=sea, boats=boats, source=source,
                    environment=environment)
