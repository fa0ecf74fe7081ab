"""The user docs' Python examples run as written (docs/python.md)."""

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _python_blocks(path: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.DOTALL)


def test_the_python_api_example_runs_and_steps_every_boat():
    (block,) = _python_blocks(ROOT / "docs" / "python.md")
    out = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True,
                         text=True, timeout=600,
                         env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert [line.split(":")[0] for line in lines[:3]] == ["alpha", "bravo", "charlie"]
    # each boat got going: surge between 1 and 3 m/s at half throttle
    surges = [float(re.search(r"surge\s+([-\d.]+)", line).group(1)) for line in lines[:3]]
    assert all(1.0 < s < 3.0 for s in surges), lines
    assert lines[3].startswith("total force on the first boat")
