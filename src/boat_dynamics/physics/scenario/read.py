"""Typed readers of YAML values: each refusal names the key, the value and what is allowed.

Each reader also tells :func:`keys_read`, when one is open, which key it read, its default
and what it allows: the design document's table of every scenario key is generated from
these calls (``boat_dynamics.tools.scenario_keys``), so it cannot drift from the reader.
Outside :func:`keys_read` nothing is kept.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any

import numpy as np

from boat_dynamics.physics.scenario.specs import ScenarioError

__all__ = ["MAX_NAME_LENGTH", "ROS_NAME_RULE", "BlockDoc", "KeyDoc", "choice", "describe",
           "flag", "integer", "is_ros_name", "keys_read", "mapping", "number", "only", "unlisted",
           "vector", "yaml_depth"]

#: The longest boat, thruster or sensor name: each goes into topic, frame and node names,
#: which ROS 2 caps at 255 characters (rmw's validation).
MAX_NAME_LENGTH = 64
#: What a boat, thruster or sensor name must be (ROS 2's name-token rules, ASCII).
ROS_NAME_RULE = (f"a ROS name: an ASCII letter, then ASCII letters, digits or _, at most "
                 f"{MAX_NAME_LENGTH} characters")
_ROS_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")


def yaml_depth(text: str, limit: int) -> int:
    """How deep YAML ``text`` nests mappings and sequences, counted up to ``limit + 1``.

    Read from the parser's events, which libyaml produces with a stack of its own, not by
    recursion; so a document nested 100,000 levels deep is measured before the composer, which
    recurses once per level (in C: a stack overflow, SIGSEGV), builds it.

    Raises:
        yaml.YAMLError: ``text`` is not YAML.
    """
    import yaml

    depth = deepest = 0
    for event in yaml.parse(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            deepest = max(deepest, depth)
            if deepest > limit:
                break
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
    return deepest


def is_ros_name(value: object) -> bool:
    """Whether ``value`` is a name :data:`ROS_NAME_RULE` allows (rclpy refused the others)."""
    return (isinstance(value, str) and len(value) <= MAX_NAME_LENGTH
            and _ROS_NAME.fullmatch(value) is not None)


@dataclass(frozen=True)
class KeyDoc:
    """A key as a reader read it.

    Attributes:
        path: its path, e.g. ``boats[0].mass``.
        default: its default, as text (a value, or what it is derived from).
        allowed: what is allowed, with the unit.
    """

    path: str
    default: str
    allowed: str


@dataclass(frozen=True)
class BlockDoc:
    """A mapping's keys as :func:`only` allows them (``path`` "" = the file's top level)."""

    path: str
    keys: tuple[str, ...]


_READ: ContextVar[list | None] = ContextVar("boatsim_scenario_keys_read", default=None)


@contextmanager
def keys_read() -> Iterator[list[KeyDoc | BlockDoc]]:
    """Collect what the readers read while a scenario is parsed in this block."""
    seen: list[KeyDoc | BlockDoc] = []
    token = _READ.set(seen)
    try:
        yield seen
    finally:
        _READ.reset(token)


@contextmanager
def unlisted() -> Iterator[None]:
    """Read without listing the keys (a block the reader wrote itself: a buoy's boat)."""
    token = _READ.set(None)
    try:
        yield
    finally:
        _READ.reset(token)


def _shown(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return ".inf" if value == math.inf else f"{value:g}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_shown(float(v) if not isinstance(v, str) else v)
                               for v in value) + "]"
    return "null" if value is None else str(value)


def describe(path: str, default: object, allowed: str, default_doc: str | None = None) -> None:
    """Tell :func:`keys_read` of a key read without a typed reader (its own checks)."""
    seen = _READ.get()
    if seen is not None:
        seen.append(KeyDoc(path, default_doc or _shown(default), allowed))


def mapping(value: Any, key: str) -> Mapping[str, Any]:
    """A mapping (None = empty), or ScenarioError."""
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise ScenarioError(key, value, "must be a mapping (key: value)")
    return value


def only(d: Mapping[str, Any], key: str, allowed: tuple[str, ...]) -> None:
    """Refuse keys of ``d`` outside ``allowed``, naming the first."""
    seen = _READ.get()
    if seen is not None:
        seen.append(BlockDoc(key, tuple(allowed)))
    for k in d:
        if k not in allowed:
            raise ScenarioError(f"{key}.{k}" if key else str(k), d[k],
                                f"unknown key; allowed keys here: {', '.join(allowed)}")


def number(
    d: Mapping[str, Any],
    name: str,
    key: str,
    default: float,
    low: float = -math.inf,
    high: float = math.inf,
    low_open: bool = False,
    unit: str = "",
    allow_inf: bool = False,
    default_doc: str | None = None,
    range_doc: str | None = None,
) -> float:
    """``d[name]`` (or ``default``) as a float in the range, or ScenarioError naming it.

    ``default_doc``, ``range_doc``: how the key table states a default or range that depends
    on other keys (the hull's size, ``simulation.rate_hz``), instead of this one's value.
    """
    path = f"{key}.{name}" if key else name
    v = d.get(name, default)
    bounds = ("(" if low_open else "[") + f"{low:g}, {high:g}]" + (f" {unit}" if unit else "")
    describe(path, default, f"number in {range_doc or bounds}", default_doc)
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ScenarioError(path, v, f"must be a number in {bounds}")
    try:
        v = float(v)
    except OverflowError:  # an integer of hundreds of digits
        raise ScenarioError(path, v, f"must be in {bounds}") from None
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise ScenarioError(path, v, f"must be a finite number in {bounds}")
    if v < low or v > high or (low_open and v == low):
        raise ScenarioError(path, v, f"must be in {bounds}")
    return v


def vector(d: Mapping[str, Any], name: str, key: str, n: int, default: list[float],
            low: float = -math.inf, default_doc: str | None = None, unit: str = "",
            bound: float = math.inf) -> np.ndarray:
    """``d[name]`` as an (n,) float array of finite numbers >= ``low``, or ScenarioError.

    ``bound``: every entry within +-bound too.
    """
    path = f"{key}.{name}"
    v = d.get(name, default)
    describe(path, default, f"{n} numbers" + (f" >= {low:g}" if low > -math.inf else "")
             + (f" within +-{bound:g}" if bound < math.inf else "")
             + (f", {unit}" if unit else ""), default_doc)
    if (not isinstance(v, (list, tuple)) or len(v) != n
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)):
        raise ScenarioError(path, v, f"must be a list of {n} numbers")
    try:
        arr = np.array(v, dtype=float)
    except OverflowError:  # an integer of hundreds of digits
        raise ScenarioError(path, v, f"must be a list of {n} finite numbers") from None
    if not np.all(np.isfinite(arr)):
        raise ScenarioError(path, v, f"must be a list of {n} finite numbers")
    if np.any(arr < low):
        raise ScenarioError(path, v, f"every entry must be >= {low:g}")
    if np.any(np.abs(arr) > bound):
        raise ScenarioError(path, v, f"every entry must be within +-{bound:g}")
    return arr


def flag(d: Mapping[str, Any], name: str, key: str, default: bool) -> bool:
    """``d[name]`` as a bool, or ScenarioError."""
    describe(f"{key}.{name}" if key else name, default, "true or false")
    v = d.get(name, default)
    if not isinstance(v, bool):
        raise ScenarioError(f"{key}.{name}", v, "must be true or false")
    return v


def choice(d: Mapping[str, Any], name: str, key: str, default: str,
            allowed: tuple[str, ...]) -> str:
    """``d[name]`` as one of ``allowed``, or ScenarioError listing them."""
    path = f"{key}.{name}"
    describe(path, default, f"one of: {', '.join(allowed)}")
    v = d.get(name, default)
    if v not in allowed:
        raise ScenarioError(path, v, f"must be one of: {', '.join(allowed)}")
    return str(v)


def integer(d: Mapping[str, Any], name: str, key: str, default: int, low: int,
            high: int | None = None, note: str = "") -> int:
    """``d[name]`` as an integer in [low, high] (None: no upper bound), or ScenarioError.

    ``note``: said after the range in a refusal, e.g. "(quads per box face edge)".
    """
    path = f"{key}.{name}" if key else name
    bounds = f" in [{low}, {high}]" if high is not None else f" >= {low}"
    describe(path, default, f"integer{bounds}" + (f" {note}" if note else ""))
    v = d.get(name, default)
    if (isinstance(v, bool) or not isinstance(v, int) or v < low
            or (high is not None and v > high)):
        raise ScenarioError(path, v, f"must be an integer{bounds}" + (f" {note}" if note else ""))
    return v


# --------------------------------------------------------------------------- sections
