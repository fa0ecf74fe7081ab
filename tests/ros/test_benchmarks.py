"""The benchmarks still find what they time (`make bench` is not run by the tests)."""

import importlib.util
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


def _module(name: str):
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_phase_the_bench_times_exists(monkeypatch):
    """`--only phases` broke when a refactor renamed what it wraps (found by running it)."""
    monkeypatch.syspath_prepend(str(BENCHMARKS))  # as `python benchmarks/run.py` has it
    for owner, name, label in _module("run").phase_patches():
        assert callable(getattr(owner, name, None)), f"{label}: {owner!r} has no {name}"

