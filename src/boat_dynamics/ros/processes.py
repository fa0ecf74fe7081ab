"""`boatsim run --processes`: the ocean and each boat's dynamics node in a process of its own.

Start-up is a handshake, not a delay. Every child builds its nodes, waits (with ``--record``)
until the recorder has subscribed to each of its publishers, and says "ready" on a pipe; once
all are ready the parent sends each the epoch (the wall-clock time of simulation time 0, a
moment ahead) on its stdin, and they start on it, paced to real time. A child that falls
behind catches up (it steps without waiting until it is on time), so no simulation time is
skipped and the bag holds every step from 0.

Supervision: the children die with the parent (SIGTERM on its death on Linux, and the end of
their stdin everywhere); the parent reports a child that dies (which one, how); a dead ocean
is restarted and joins at the current simulation time with the scenario's sea state (the
boats keep the last sea state they had meanwhile: they need no ocean to step); a dead boat is
not (its state is gone). The run's exit status is 1 when any child died. SIGINT and SIGTERM
are forwarded; the recorder is stopped (its bag finalized) after the simulation's processes.
Only the first boat's process shows the status line.
"""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

from boat_dynamics.physics.scenario import Scenario
from boat_dynamics.process import start_child, stop_processes
from boat_dynamics.ros.runner import RunOptions
from boat_dynamics.tools.recording import RecordError

__all__ = ["run_processes"]

#: Simulation time 0 is this far (s, wall clock) after the last child said ready.
_GO_AHEAD = 0.5
#: How long the children may take to be ready, s (wall clock).
_READY_TIMEOUT = 120.0
#: Period of the parent's watch over its children, s.
_WATCH_PERIOD = 0.1


@dataclass
class _Child:
    """One child process: ``label`` ("ocean", "boat alpha"), its ``_node`` arguments."""

    label: str
    args: list[str]
    proc: subprocess.Popen | None = None
    ready_fd: int | None = None  # read end of its ready pipe, until it said ready
    status: int | None = None  # its exit status, once it exited


def _spawn(child: _Child, handshake: bool) -> None:
    """Start ``child``: with a ready pipe (``handshake``), or joining a running simulation."""
    args = ["_node", *child.args]
    pass_fds: tuple[int, ...] = ()
    write_fd = None
    if handshake:
        child.ready_fd, write_fd = os.pipe()
        args += ["--ready-fd", str(write_fd)]
        pass_fds = (write_fd,)
    child.proc = start_child(args, pass_fds=pass_fds)
    if write_fd is not None:
        os.close(write_fd)


def _children(scenario: Scenario, path: str, options: RunOptions) -> list[_Child]:
    """The ocean's child and each boat's, with their ``_node`` arguments (no epoch yet)."""
    common = [path, *(["--duration", repr(options.duration)] if options.duration else [])]
    common += ["--await-recorder"] if options.record else []
    out = [_Child("ocean", ["ocean", *common, "--quiet"])]
    for i, boat in enumerate(scenario.boats):
        out.append(_Child(f"boat {boat.name or '(root)'}",
                          ["boat", *common, "--boat", boat.name, *(["--quiet"] if i else [])]))
    return out


def _start_recorder(record: str, exclude: tuple[str, ...]) -> subprocess.Popen:
    """A ``boatsim record`` process writing every topic to ``record`` (a new directory)."""
    if Path(record).exists():  # refused here, before any process starts
        raise RecordError(f"{Path(record)} already exists; choose a new directory for the bag")
    return start_child(["record", "-o", record,
                        *(["--exclude-topics", *exclude] if exclude else [])],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _describe(status: int) -> str:
    """An exit status in words: ``exit status 1``, ``killed by SIGKILL``."""
    if status < 0:
        try:
            return f"killed by {signal.Signals(-status).name}"
        except ValueError:
            return f"killed by signal {-status}"
    return f"exit status {status}"


def _await_ready(children: list[_Child], stopping, status: TextIO) -> bool:
    """Wait until every child wrote "ready"; False when one died first, or on a stop."""
    deadline = time.monotonic() + _READY_TIMEOUT
    while any(c.ready_fd is not None for c in children):
        if stopping():
            return False
        for c in children:
            if c.ready_fd is not None and (code := c.proc.poll()) is not None:
                c.status = code
                print(f"boatsim: process {c.label} (pid {c.proc.pid}) died before it was "
                      f"ready: {_describe(code)}", file=status)
                return False
        if time.monotonic() > deadline:
            late = ", ".join(c.label for c in children if c.ready_fd is not None)
            print(f"boatsim: not ready after {_READY_TIMEOUT:g} s: {late}", file=status)
            return False
        waiting = {c.ready_fd: c for c in children if c.ready_fd is not None}
        readable, _, _ = select.select(list(waiting), [], [], _WATCH_PERIOD)
        for fd in readable:
            if b"ready" in os.read(fd, 64):
                os.close(fd)
                waiting[fd].ready_fd = None
    return True


def _go(children: list[_Child], epoch: float) -> None:
    for c in children:
        try:
            c.proc.stdin.write(f"go {epoch!r}\n".encode())
            c.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            pass  # died meanwhile: the watch reports it


def _watch(children: list[_Child], epoch: float, stopping, status: TextIO) -> bool:
    """Until every boat's process has exited: report deaths, restart the ocean.

    Args:
        children: the ocean's child first.
        epoch: s, wall-clock time of simulation time 0 (a restarted ocean joins on it).
        stopping: forwards the signals the parent received; True once there was one.
        status: where to report.

    Returns:
        True when a child died.
    """
    died = False
    boats = [c for c in children if c.label != "ocean"]
    ocean = children[0]
    while any(c.status is None for c in boats):
        time.sleep(_WATCH_PERIOD)
        stopped = stopping()  # forwards a SIGINT / SIGTERM the parent received
        for c in children:
            if c.status is not None or (code := c.proc.poll()) is None:
                continue
            c.status = code
            if code == 0 or stopped:
                continue
            died = True
            print(f"boatsim: process {c.label} (pid {c.proc.pid}) died: {_describe(code)}",
                  file=status)
            if c is ocean:
                c.status = None
                if "--epoch" not in c.args:  # it joins: no handshake, no wait for the recorder
                    c.args = [a for a in c.args if a != "--await-recorder"]
                    c.args += ["--epoch", repr(epoch)]
                _spawn(c, handshake=False)
                print(f"boatsim: restarted the ocean (pid {c.proc.pid}); it joins at the "
                      "current simulation time with the scenario's sea state; the boats keep "
                      "the last sea state they had meanwhile", file=status)
    return died


def run_processes(scenario: Scenario, path: str, options: RunOptions,
                  status: TextIO = sys.stderr) -> int:
    """Run ``scenario`` (read from ``path``) as one process per node; returns the exit status.

    Raises:
        RecordError: the bag directory of ``options.record`` already exists.
    """
    recorder = _start_recorder(options.record, options.exclude_topics) if options.record else None
    children = _children(scenario, path, options)
    signals: list[int] = []
    previous = {sig: signal.signal(sig, lambda signum, _: signals.append(signum))
                for sig in (signal.SIGINT, signal.SIGTERM)}
    start = time.monotonic()
    try:
        for c in children:
            _spawn(c, handshake=True)
        print(f"boatsim: started {len(children)} processes (ocean + {len(scenario.boats)} "
              f"boats): pids {' '.join(str(c.proc.pid) for c in children)}"
              + (f"; recording to {options.record} (pid {recorder.pid})" if recorder else ""),
              file=status)
        if not _await_ready(children, lambda: bool(signals), status):
            return 0 if signals else 1
        epoch = time.time() + _GO_AHEAD
        _go(children, epoch)
        print(f"boatsim: every process ready after {time.monotonic() - start:.1f} s"
              + (" (the recorder subscribed to each)" if recorder else "")
              + "; simulation time 0 is now", file=status)
        forwarded = 0

        def stopping() -> bool:
            nonlocal forwarded
            for sig in signals[forwarded:]:
                for c in children:
                    if c.proc.poll() is None:
                        c.proc.send_signal(sig)
            forwarded = len(signals)
            return bool(signals)

        died = _watch(children, epoch, stopping, status)
        stop_processes([children[0].proc])  # the ocean, when it runs with no duration
        ok = all(c.status in (0, None) for c in children) and not died
        return 0 if ok else 1
    finally:
        stop_processes([c.proc for c in children if c.proc is not None])
        if recorder is not None:
            stop_processes([recorder], timeout=30.0)
            print(f"boatsim: recorded to {options.record}", file=status)
        for sig, handler in previous.items():
            signal.signal(sig, handler)
