"""Typed readers of YAML values: each refusal names the key, the value and what is allowed."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from boat_dynamics.physics.scenario.specs import ScenarioError


def mapping(value: Any, key: str) -> Mapping[str, Any]:
    """A mapping (None = empty), or ScenarioError."""
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise ScenarioError(key, value, "must be a mapping (key: value)")
    return value


def only(d: Mapping[str, Any], key: str, allowed: tuple[str, ...]) -> None:
    """Refuse keys of ``d`` outside ``allowed``, naming the first."""
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
) -> float:
    """``d[name]`` (or ``default``) as a float in the range, or ScenarioError naming it."""
    path = f"{key}.{name}" if key else name
    v = d.get(name, default)
    bounds = ("(" if low_open else "[") + f"{low:g}, {high:g}]" + (f" {unit}" if unit else "")
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ScenarioError(path, v, f"must be a number in {bounds}")
    v = float(v)
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise ScenarioError(path, v, f"must be a finite number in {bounds}")
    if v < low or v > high or (low_open and v == low):
        raise ScenarioError(path, v, f"must be in {bounds}")
    return v


def vector(d: Mapping[str, Any], name: str, key: str, n: int, default: list[float],
            low: float = -math.inf) -> np.ndarray:
    """``d[name]`` as an (n,) float array of finite numbers >= ``low``, or ScenarioError."""
    path = f"{key}.{name}"
    v = d.get(name, default)
    if (not isinstance(v, (list, tuple)) or len(v) != n
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)):
        raise ScenarioError(path, v, f"must be a list of {n} numbers")
    arr = np.array(v, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ScenarioError(path, v, f"must be a list of {n} finite numbers")
    if np.any(arr < low):
        raise ScenarioError(path, v, f"every entry must be >= {low:g}")
    return arr


def flag(d: Mapping[str, Any], name: str, key: str, default: bool) -> bool:
    """``d[name]`` as a bool, or ScenarioError."""
    v = d.get(name, default)
    if not isinstance(v, bool):
        raise ScenarioError(f"{key}.{name}", v, "must be true or false")
    return v


def choice(d: Mapping[str, Any], name: str, key: str, default: str,
            allowed: tuple[str, ...]) -> str:
    """``d[name]`` as one of ``allowed``, or ScenarioError listing them."""
    path = f"{key}.{name}"
    v = d.get(name, default)
    if v not in allowed:
        raise ScenarioError(path, v, f"must be one of: {', '.join(allowed)}")
    return str(v)


# --------------------------------------------------------------------------- sections
