"""Helpers the ROS tests share (a module beside them: tests/ros is on their import path)."""

import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def cli_run(*args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    """Run ``boatsim ARGS`` to its end, from the repository's root; its output captured."""
    return subprocess.run([sys.executable, "-m", "boat_dynamics", *args], capture_output=True,
                          text=True, timeout=timeout, cwd=ROOT)


def rrd_entities(rrd) -> set[str]:
    """The entity paths of a .rrd file (`boatsim view --save`), from `rerun rrd stats`."""
    rerun = shutil.which("rerun", path=str(Path(sys.executable).parent))
    out = subprocess.run([rerun, "rrd", "stats", str(rrd)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    section = out.stdout.split("Num chunks per entity")[1].split("Num chunks per index")[0]
    return {line.split(":")[0].strip() for line in section.splitlines() if line.startswith("/")}
