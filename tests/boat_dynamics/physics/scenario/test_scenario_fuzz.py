"""Fuzzing the scenario reader: whatever a file holds, the answer is a scenario or a
ScenarioError (then InitError at most, for a hull that sinks), with a short message.

The examples are derandomized, so a fresh clone's run is repeatable; set
BOATSIM_FUZZ_EXAMPLES=5000 to explore with random seeds (how the last two defects were found).

Two kinds of damage, from the shipped scenarios: structural (a value replaced by another of
any type, a key removed or invented, a list made a mapping) and textual (bytes flipped,
inserted or cut in the YAML). Anything else (TypeError, KeyError, RecursionError,
ZeroDivisionError, a numpy warning turned error...) is a defect.
"""

import copy
import os
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.core.pipeline import InitError, start
from boat_dynamics.physics.scenario import ScenarioError, load_scenario, parse_scenario

SCENARIOS = Path(__file__).resolve().parents[4] / "scenarios"
#: Examples per test when exploring (random seeds); 0 = the fixed, derandomized run.
EXPLORE = int(os.environ.get("BOATSIM_FUZZ_EXAMPLES", "0"))


def _fuzz(examples: int, **kwargs):
    """Hypothesis settings: ``examples`` derandomized, or EXPLORE random ones."""
    return settings(max_examples=EXPLORE or examples, deadline=None,
                    derandomize=not EXPLORE, database=None, **kwargs)
#: The shipped scenarios with no file of their own beside them (the Otter has its STL).
BASES = {p.name: yaml.safe_load(p.read_text()) for p in sorted(SCENARIOS.glob("*.yaml"))
         if p.name != "otter.yaml"}

ODD_VALUES = st.one_of(
    st.none(), st.booleans(), st.integers(-10**30, 10**30),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=20),
    st.sampled_from([[], {}, [[]], {"x": 1}, "1e999", -0.0, 1e308, -1e308, 5e-324]),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=5),
)


def _paths(node, prefix=()):
    """Every (path, value) in a nested dict/list."""
    yield prefix, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _paths(v, (*prefix, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _paths(v, (*prefix, i))


def _odd(draw):
    """A drawn odd value, copied: the strategy's own lists and dicts must never be mutated."""
    return copy.deepcopy(draw(ODD_VALUES))


def _mutate(data, draw):
    paths = [p for p, _ in _paths(data) if p]
    if not paths:
        return {"boats": _odd(draw)}
    path = draw(st.sampled_from(paths))
    parent = data
    for key in path[:-1]:
        parent = parent[key]
    kind = draw(st.sampled_from(["replace", "delete", "invent", "retype"]))
    if kind == "replace":
        parent[path[-1]] = _odd(draw)
    elif kind == "delete":
        del parent[path[-1]]
    elif kind == "invent" and isinstance(parent, dict):
        parent[draw(st.text(min_size=1, max_size=12))] = _odd(draw)
    else:
        value = parent[path[-1]]
        parent[path[-1]] = (dict(enumerate(value)) if isinstance(value, list)
                            else [value] if not isinstance(value, dict) else list(value))
    return data


def _check(build) -> str:
    """``build()`` gives a scenario or raises ScenarioError / InitError, briefly worded.

    Returns:
        What happened: "refused", "sinks" or "started".
    """
    try:
        scenario = build()
    except ScenarioError as exc:
        assert len(str(exc)) < 600, str(exc)[:200]
        return "refused"
    try:
        # a NaN or an overflow reaching the physics is a defect too (underflow is harmless)
        with np.errstate(over="raise", divide="raise", invalid="raise"):
            start(scenario.boats, scenario.sea)
    except InitError as exc:
        assert len(str(exc)) < 600
        return "sinks"
    except FloatingPointError:
        pytest.fail(f"a scenario that loads made non-finite numbers: {scenario}"[:400])
    return "started"


@_fuzz(300)
@given(data=st.data(), base=st.sampled_from(sorted(BASES)))
def test_structural_damage_gives_a_scenario_or_a_scenario_error(data, base):
    damaged = copy.deepcopy(BASES[base])
    for _ in range(data.draw(st.integers(1, 3))):
        damaged = _mutate(damaged, data.draw)
    _check(lambda: parse_scenario(damaged, source="fuzz", base_dir=SCENARIOS))


@_fuzz(200, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data(), base=st.sampled_from(sorted(BASES)))
def test_textual_damage_gives_a_scenario_or_a_scenario_error(tmp_path, data, base):
    text = bytearray((SCENARIOS / base).read_bytes())
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, max(len(text) - 1, 0)))
        action = data.draw(st.sampled_from(["flip", "insert", "cut"]))
        if action == "flip" and text:
            text[at] = data.draw(st.integers(0, 255))
        elif action == "insert":
            text[at:at] = data.draw(st.binary(min_size=1, max_size=8))
        else:
            del text[at:at + data.draw(st.integers(1, 64))]
    path = tmp_path / "fuzz.yaml"
    path.write_bytes(bytes(text))
    _check(lambda: load_scenario(path))


def test_the_structural_fuzzing_reaches_the_physics():
    # a fuzzer whose every case is refused would test only the refusals
    outcomes = Counter()

    @settings(max_examples=150, deadline=None, database=None, derandomize=True)
    @given(data=st.data(), base=st.sampled_from(sorted(BASES)))
    def damage(data, base):
        outcomes[_check(lambda: parse_scenario(_mutate(copy.deepcopy(BASES[base]), data.draw),
                                               source="fuzz", base_dir=SCENARIOS))] += 1

    damage()
    assert outcomes["started"] >= 15 and outcomes["refused"] >= 15, outcomes
