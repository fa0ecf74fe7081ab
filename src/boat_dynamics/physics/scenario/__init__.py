"""Scenario files (YAML): parsing and validation into frozen specs, nothing more.

The reader computes no physics: what a boat's own hydrostatics fix (its equilibrium, the
damping the file leaves to derive) is asked for in ``BoatParams.derive``, and the boats start
at rest at their initial poses; :func:`boat_dynamics.physics.core.pipeline.init` derives it and
sets them afloat, once.

The keys are the public contract of docs/DESIGN.md ("Scenario file"). Every refusal raises
:class:`ScenarioError` naming the key (as a path such as ``boats[0].hull.length``), the value
and what is allowed. Pure Python + numpy; never imports rclpy. The parts: :mod:`.specs` (what
a file is read into), :mod:`.read` (typed value readers), :mod:`.sea` (``simulation``,
``ocean``), :mod:`.boat` (a boat, in key order) and :mod:`.models` (its model blocks).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import yaml

from boat_dynamics.physics.scenario.boat import DEFAULT_CRITICAL_RATIO, boat_block
from boat_dynamics.physics.scenario.read import describe, mapping, only, unlisted, yaml_depth
from boat_dynamics.physics.scenario.sea import environment_block, ocean_block, simulation_block
from boat_dynamics.physics.scenario.specs import (
    BoatSpec,
    Scenario,
    ScenarioError,
    SimulationSettings,
)
from boat_dynamics.physics.scenario.world import buoy_boats, world_block

__all__ = [
    "DEFAULT_CRITICAL_RATIO",
    "BoatSpec",
    "Scenario",
    "ScenarioError",
    "SimulationSettings",
    "check_bounded",
    "default_scenario_path",
    "document_digest",
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
        with p.open("rb") as f:
            raw = f.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ScenarioError("file", str(p), f"must be a readable file ({exc.strerror})") from exc
    if len(raw) > MAX_FILE_BYTES:
        raise ScenarioError("file", str(p), f"must be at most {MAX_FILE_BYTES} bytes of YAML")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ScenarioError("file", str(p), f"must be UTF-8 text (YAML); byte {exc.start} is "
                                            f"0x{raw[exc.start]:02x}") from exc
    try:
        if yaml_depth(text, MAX_DEPTH) > MAX_DEPTH:  # before the (recursive) composer
            raise ScenarioError("file", str(p), f"must nest at most {MAX_DEPTH} levels deep")
        data = yaml.load(text, Loader=_LOADER)  # a safe loader (_LOADER)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "somewhere"
        raise ScenarioError("file", str(p), f"must be valid YAML (error at {where})") from exc
    except RecursionError as exc:  # the YAML composer recurses once per level of nesting
        raise ScenarioError("file", str(p), f"must nest at most {MAX_DEPTH} levels deep "
                                            "(the YAML parser ran out of stack)") from exc
    return parse_scenario({} if data is None else data, source=str(p), base_dir=p.parent)


#: PyYAML's safe loader, in C where PyYAML was built with libyaml (1000 boats: 0.06 s, not 0.38)
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
#: The largest scenario file read, bytes (the shipped ones are under 5 kB).
MAX_FILE_BYTES = 1_000_000
#: The deepest nesting of mappings and lists a scenario may have.
MAX_DEPTH = 32
#: The most values (mappings, lists, scalars) a scenario may hold once its YAML aliases are
#: expanded (an alias bomb holds billions in a few hundred bytes).
MAX_VALUES = 200_000


def check_bounded(data: Any, source: str) -> None:
    """Refuse data nested deeper than MAX_DEPTH or of more than MAX_VALUES values expanded.

    One pass over the distinct containers (shared ones, YAML aliases, are counted by
    multiplication, not walked again), without recursion: a few milliseconds for any file.
    """
    size: dict[int, int] = {}
    depth: dict[int, int] = {}
    stack: list[tuple[Any, bool]] = [(data, False)]
    while stack:
        node, done = stack.pop()
        if not isinstance(node, dict | list) or (id(node) in size and not done):
            continue
        children = list(node.keys()) + list(node.values()) if isinstance(node, dict) else node
        inner = [c for c in children if isinstance(c, dict | list)]
        if not done:
            stack.append((node, True))
            stack += [(c, False) for c in inner if id(c) not in size]
            continue
        size[id(node)] = 1 + len(children) - len(inner) + sum(size[id(c)] for c in inner)
        depth[id(node)] = 1 + max((depth[id(c)] for c in inner), default=0)
        if depth[id(node)] > MAX_DEPTH:
            raise ScenarioError("file", source, f"must nest at most {MAX_DEPTH} levels deep")
        if size[id(node)] > MAX_VALUES:
            raise ScenarioError("file", source, f"must hold at most {MAX_VALUES} values with "
                                                "its YAML aliases expanded")


# --------------------------------------------------------------------------- readers


def parse_scenario(data: Any, source: str = "<scenario>", base_dir: Path | None = None
                   ) -> Scenario:
    """Validate a scenario given as parsed YAML (nested dicts and lists).

    Relative mesh paths are resolved against ``base_dir`` (the scenario file's directory;
    default: the current directory).

    Raises:
        ScenarioError: an invalid key or value, named by its path.
    """
    check_bounded(data, source)
    d = mapping(data, "")
    only(d, "", ("simulation", "ocean", "environment", "world", "boats"))
    sim = simulation_block(d.get("simulation"))
    sea = ocean_block(d.get("ocean"), sim)
    environment = environment_block(d.get("environment"), sim.seed)
    world = world_block(d.get("world"), sim)
    describe("boats", None, "a non-empty list of boats", default_doc="one default boat (a "
             "4 m x 2 m x 1 m box), with a warning")
    boats_raw = d.get("boats")
    defaulted = boats_raw is None
    if defaulted:
        boats_raw = [{}]
    if not isinstance(boats_raw, list) or not boats_raw:
        raise ScenarioError("boats", boats_raw, "must be a non-empty list of boats")
    lone = len(boats_raw) == 1
    base = Path.cwd() if base_dir is None else base_dir
    loaded: dict = {}  # coefficient files, shared by the boats that name the same one
    alike: dict = {}  # a boat's parameter blocks (repr) -> the first such boat's parameters
    boats = tuple(boat_block(b, f"boats[{i}]", sim, lone, base, sea.depth, loaded, alike)
                  for i, b in enumerate(boats_raw))
    buoys = buoy_boats(mapping(d.get("world"), "world").get("buoys"), sea.depth,
                       sim.water_density)
    with unlisted():  # the buoys' own keys are listed; the boat blocks are written here
        boats += tuple(replace(boat_block(b, k, sim, False, base, sea.depth), kind="buoy")
                       for k, b in buoys)
    keys = [f"boats[{i}]" for i in range(len(boats_raw))] + [k for k, _ in buoys]
    names = [b.name for b in boats]
    for i, n in enumerate(names):
        if names.index(n) != i:
            raise ScenarioError(f"{keys[i]}.name", n, "must be unique among the boats and "
                                "buoys")
    notes = ()
    if defaulted:
        hull, mass = boats[0].params.hull, boats[0].params.mass
        notes = (("the file is empty" if not d else "no `boats`") + ": one default boat (a "
                 f"{hull.length:g} m x {hull.beam:g} m x {hull.height:g} m box, {mass:,.0f} kg) "
                 "in the root namespace",)
    return Scenario(simulation=sim, sea=sea, boats=boats, source=source,
                    environment=environment, world=world, notes=notes,
                    digest=document_digest(d))


def document_digest(data: Any) -> str:
    """16 hex digits of the SHA-256 of a parsed YAML document (keys sorted; layout ignored)."""
    import hashlib
    import json

    try:
        text = json.dumps(data, sort_keys=True, separators=(",", ":"), default=repr)
    except TypeError:  # keys of mixed types cannot be sorted
        text = repr(data)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
