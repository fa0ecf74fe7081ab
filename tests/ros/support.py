"""Helpers the ROS tests share (a module beside them: tests/ros is on their import path)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def cli_run(*args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    """Run ``boatsim ARGS`` to its end, from the repository's root; its output captured."""
    return subprocess.run([sys.executable, "-m", "boat_dynamics", *args], capture_output=True,
                          text=True, timeout=timeout, cwd=ROOT)
