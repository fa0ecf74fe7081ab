"""Regression suite: replay each golden run's commands and compare with the committed bag.

After an intended physics change, `make regold` re-records the goldens and prints the
differences it accepts.
"""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "golden"))

from golden_tools import HERE, record_run, specs

from boat_dynamics.tools.bags import compare_bags

#: Absolute tolerance on every field: far below any physical change, far above rounding.
TOLERANCE = {"*": 1e-6}


@pytest.mark.parametrize("name", sorted(specs()))
def test_golden_run_is_reproduced(name, tmp_path):
    golden = HERE / name
    assert (golden / "metadata.yaml").exists(), f"golden {name} missing: run `make regold`"
    size = sum(p.stat().st_size for p in golden.iterdir())
    assert size < 150_000  # small enough to commit
    record_run(name, tmp_path / "new", tmp_path / "work")
    result = compare_bags(golden, tmp_path / "new", tolerances=TOLERANCE)
    assert result.ok, result.report()
    odoms = [t for t in result.topics if t.topic.endswith("/odom")]
    assert odoms and all(t.matched > 40 for t in odoms)
