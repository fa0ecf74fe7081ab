"""`boatsim run --processes`: the ocean and each boat's dynamics node in a process of its own.

The processes share an epoch (the wall-clock time of simulation time 0, a second ahead so
that they all start on it; 2.5 s with ``--record``, so that the recorder has matched the
publishers by then) and pace themselves to real time; the parent forwards SIGINT and SIGTERM
and returns 0 when every child exited 0. Only the first boat's process shows the status line.
With ``options.record``, a ``boatsim record`` process records every topic and is stopped (bag
finalized) after the simulation processes have exited.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import TextIO

from boat_dynamics.physics.scenario import Scenario
from boat_dynamics.ros.runner import RunOptions
from boat_dynamics.tools.recording import RecordError

__all__ = ["run_processes"]

#: The command that starts a boatsim process.
_CLI = [sys.executable, "-m", "boat_dynamics"]


def _node_commands(scenario: Scenario, path: str, options: RunOptions, epoch: float
                   ) -> list[list[str]]:
    """The ``boatsim _node`` arguments of the ocean's process and of each boat's."""
    common = [path, "--epoch", repr(epoch)]
    if options.duration is not None:
        common += ["--duration", repr(options.duration)]
    commands = [["ocean", *common, "--quiet"]]
    for i, boat in enumerate(scenario.boats):
        commands.append(["boat", *common, "--boat", boat.name, *(["--quiet"] if i else [])])
    return commands


def _start_recorder(record: str, exclude: tuple[str, ...]) -> subprocess.Popen:
    """A ``boatsim record`` process writing every topic to ``record`` (a new directory)."""
    if Path(record).exists():  # refused here, before any process starts
        raise RecordError(f"{Path(record)} already exists; choose a new directory for the bag")
    return subprocess.Popen([*_CLI, "record", "-o", record,
                             *(["--exclude-topics", *exclude] if exclude else [])],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _wait_all(children: list[subprocess.Popen], recorder: subprocess.Popen | None,
              forward) -> list[int]:
    """Every child's exit status, in order; the recorder (last) is stopped once it is reached."""
    codes = []
    for c in children:
        if c is recorder and recorder.poll() is None:
            recorder.send_signal(signal.SIGINT)  # the simulation is over: finalize the bag
        while True:
            try:
                codes.append(c.wait())
                break
            except KeyboardInterrupt:
                forward(signal.SIGINT, None)
    return codes


def run_processes(scenario: Scenario, path: str, options: RunOptions,
                  status: TextIO = sys.stderr) -> int:
    """Run ``scenario`` (read from ``path``) as one process per node; returns the exit status.

    Raises:
        RecordError: the bag directory of ``options.record`` already exists.
    """
    epoch = time.time() + (2.5 if options.record else 1.0)
    recorder = _start_recorder(options.record, options.exclude_topics) if options.record else None
    children = [subprocess.Popen([*_CLI, "_node", *c])
                for c in _node_commands(scenario, path, options, epoch)]
    print(f"boatsim: started {len(children)} processes (ocean + {len(scenario.boats)} boats): "
          f"pids {' '.join(str(c.pid) for c in children)}"
          + (f"; recording to {options.record} (pid {recorder.pid})" if recorder else ""),
          file=status)
    if recorder is not None:
        children.append(recorder)  # stopped last: see _wait_all

    def forward(signum, _frame):
        for c in children:
            if c.poll() is None:
                c.send_signal(signal.SIGINT)

    previous = {sig: signal.signal(sig, forward) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        codes = _wait_all(children, recorder, forward)
        if recorder is not None:
            print(f"boatsim: recorded to {options.record}", file=status)
        return 0 if all(code == 0 for code in codes) else 1
    finally:
        for c in children:
            if c.poll() is None:
                c.kill()
        for sig, handler in previous.items():
            signal.signal(sig, handler)
