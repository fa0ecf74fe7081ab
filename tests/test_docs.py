"""The user docs' Python examples run as written (docs/python.md)."""

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _python_blocks(path: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.DOTALL)


def _run(block: str) -> list[str]:
    out = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True,
                         text=True, timeout=600,
                         env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    assert out.returncode == 0, out.stderr
    return out.stdout.splitlines()


def test_the_python_api_example_runs_and_steps_every_boat():
    block = _python_blocks(ROOT / "docs" / "python.md")[0]
    lines = _run(block)
    assert [line.split(":")[0] for line in lines[:3]] == ["alpha", "bravo", "charlie"]
    # each boat got going: surge between 1 and 3 m/s at half throttle
    surges = [float(re.search(r"surge\s+([-\d.]+)", line).group(1)) for line in lines[:3]]
    assert all(1.0 < s < 3.0 for s in surges), lines
    assert lines[3].startswith("total force on the first boat")


def test_the_gymnasium_example_runs_and_every_boat_makes_progress():
    (block,) = _python_blocks(ROOT / "docs" / "python.md")[1:]
    lines = _run(block)
    assert lines[0].startswith("distance to go (m):")
    made_good = [float(x) for x in lines[1].split("[")[1].rstrip("]").split()]
    # the boats turned towards their waypoints (those behind turn first) and got under way
    # (at most 2 m/s)
    assert len(made_good) == 8 and all(-2.0 < m < 20.0 for m in made_good), lines
    assert sum(made_good) > 30.0, lines
