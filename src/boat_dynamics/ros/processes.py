"""`boatsim run --processes | --shards N`: the ocean and the boats' dynamics in processes.

``--processes`` gives each boat a dynamics process of its own; ``--shards N`` spreads the
boats over N, each stepping its share as one fleet. The ocean has a process of its own.

Start-up is a handshake, not a delay. Every child builds its nodes, waits (real time with
``--record``) until the recorder has subscribed to each of its publishers, and says "ready"
on a pipe; once all are ready the parent sends each the epoch on its stdin ("go EPOCH").

Time. In real time the epoch is the wall-clock time of simulation time 0, a moment ahead, and
every process paces itself to it; a child that falls behind catches up (it steps without
waiting until it is on time), so no simulation time is skipped. With ``--fast`` (and
``--lockstep``) the ocean's process owns the clock: the step barrier
(:mod:`boat_dynamics.ros.barrier`) grants the steps, so every process is at the same
simulation time within a few steps and /clock comes from one place.

Recording. In real time a recorder process (``boatsim record``) subscribes to every topic.
With ``--fast`` every process records what it publishes (and the ocean's what the others
publish, such as /rosout) into a bag of its own beside the target, and the parent merges them
into one when the run ends (:func:`boat_dynamics.tools.bagfile.merge`): a subscriber could not
keep up with processes running flat out.

Supervision: the children die with the parent (SIGTERM on its death on Linux, and the end of
their stdin everywhere); the parent reports a child that dies (which one, how); a dead ocean
is restarted and joins at the current simulation time with the scenario's sea state (the
boats keep the last sea state they had meanwhile: they need no ocean to step). With
``--fast`` every dynamics process saves a snapshot of its boats every simulated second
(:data:`boat_dynamics.ros.runner.CHECKPOINT_PERIOD`, its bag part flushed first); a dead one
is started again from its last snapshot (at most :data:`_RESTARTS` times) and rejoins the
step barrier, the others waiting for it meanwhile; the merged bag takes the dead process's
part up to the snapshot and the new one's after it, so each message is there once. What its
boats received after the snapshot is lost (at most a second of simulation time of commands),
and subscribers see that second of its boats' topics again. Under ``--lockstep`` a dead
dynamics process stops the run instead (the replayer's commands it had received since the
snapshot would be missing; the barrier would wait for them forever); in real time it is not
restarted (the others go on). The run's exit status is 1 when any child died, else 3
(:data:`~boat_dynamics.ros.runner.EXIT_STOPPED`) when one stopped a boat whose state
diverged. SIGINT and
SIGTERM are forwarded; the recorder is stopped (its bag finalized) after the simulation's
processes. Only the first dynamics process shows the status line.
"""

from __future__ import annotations

import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

from boat_dynamics.physics.scenario import Scenario
from boat_dynamics.physics.wave_making.interaction import feels_made_waves
from boat_dynamics.ros.barrier import shard_slice
from boat_dynamics.ros.runner import EXIT_STOPPED, RunOptions
from boat_dynamics.tools.recording import RecordError
from boat_msgs_py.process import (
    STOP_SIGNALS,
    pid_alive,
    start_child,
    stop_processes,
    temporary_prefix,
)

__all__ = ["merge_orphaned_parts", "run_processes"]

#: Simulation time 0 is this far (s, wall clock) after the last child said ready.
_GO_AHEAD = 0.5
#: How long the children may take to be ready, s (wall clock).
_READY_TIMEOUT = 120.0
#: Period of the parent's watch over its children, s.
_WATCH_PERIOD = 0.1
#: A dynamics process is started again at most this many times.
_RESTARTS = 3


@dataclass
class _Child:
    """One child process: ``label`` ("ocean", "boat alpha"), its ``_node`` arguments."""

    label: str
    args: list[str]
    proc: subprocess.Popen | None = None
    ready_fd: int | None = None  # read end of its ready pipe, until it said ready
    status: int | None = None  # its exit status, once it exited
    snapshot: Path | None = None  # a dynamics process's snapshot file (--fast, no lockstep)
    restarts: int = 0


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


def _apart_note(scenario: Scenario, count: int) -> str | None:
    """The warning for a run whose boats in different processes would feel each other's waves.

    Made waves are not exchanged between processes (:mod:`.wave_making.interaction` steps
    the boats of one process): a boat that makes waves (``made_waves``) and a boat with
    coefficients in another shard do not meet. None when no such pair exists.
    """
    shards = [scenario.boats[shard_slice(k, count, len(scenario.boats))] for k in range(count)]
    makes = [any(b.params.made_waves != "none" for b in shard) for shard in shards]
    feels = [any(feels_made_waves(b.params) for b in shard) for shard in shards]
    if not any(makes[k] and feels[j] for k in range(count) for j in range(count) if j != k):
        return None
    return ("boatsim: warning: boats in different processes do not feel each other's made "
            "waves (hydrodynamics.made_waves: wakes, radiated and scattered waves); run them "
            "in one process to have them")


def _children(scenario: Scenario, path: str, options: RunOptions,
              parts: Path | None, snapshots: Path | None) -> list[_Child]:
    """The ocean's child and each shard's, with their ``_node`` arguments (no epoch yet).

    Args:
        scenario: the scenario (its boats are shared out).
        path: its file, which every child reads.
        options: how to run (``shards``, ``fast``, ``lockstep``, ``record``, ...).
        parts: with ``--fast --record``: the directory of each process's bag.
        snapshots: where each shard saves its snapshot (``--fast``), or None.
    """
    common = [path, *(["--duration", repr(options.duration)] if options.duration else [])]
    if options.fast:
        common += ["--fast", *(["--lockstep"] if options.lockstep else [])]
        if options.exclude_topics:
            common += ["--exclude-topics", *options.exclude_topics]
    elif options.record:
        common += ["--await-recorder"]

    def part(name: str) -> list[str]:
        return ["--record", str(parts / name)] if parts is not None else []

    count = options.process.shards
    out = [_Child("ocean", ["ocean", *common, *part("ocean"), "--quiet",
                            *(["--shards", str(count)] if options.fast else [])])]
    for k in range(count):
        boats = scenario.boats[shard_slice(k, count, len(scenario.boats))]
        label = (f"boat {boats[0].name or '(root)'}" if len(boats) == 1
                 else f"shard {k}/{count}")
        snapshot = snapshots / f"shard-{k}.npz" if snapshots is not None else None
        out.append(_Child(label, ["shard", *common, *part(f"shard-{k}"), "--shard",
                                  f"{k}/{count}", *(["--quiet"] if k else []),
                                  *(["--checkpoint", str(snapshot)] if snapshot else [])],
                          snapshot=snapshot))
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


def _restart_ocean(ocean: _Child, epoch: float, status: TextIO) -> None:
    """Start a dead ocean again, joining the run at ``epoch`` (no handshake)."""
    ocean.status = None
    args = [a for a in ocean.args if a != "--await-recorder"]
    if "--epoch" not in args:
        args += ["--epoch", repr(epoch)]
    if "--record" in args:  # a fresh part: the dead one's stays and is merged too
        i = args.index("--record") + 1
        args[i] = f"{args[i]}+"
    ocean.args = args
    _spawn(ocean, handshake=False)
    print(f"boatsim: restarted the ocean (pid {ocean.proc.pid}); it joins at the current "
          "simulation time with the scenario's sea state; the boats keep the last sea state "
          "they had meanwhile", file=status)


def _restart_shard(shard: _Child, epoch: float, cuts: dict[Path, int],
                   status: TextIO) -> bool:
    """Start a dead dynamics process again from its last snapshot; False when it cannot be.

    Its bag part (if it records) is cut at the snapshot's time in ``cuts``: the new process
    records what follows into a fresh part.
    """
    from boat_dynamics.physics.core.snapshot import SnapshotError, load

    if shard.snapshot is None or shard.restarts >= _RESTARTS:
        return False
    try:
        saved = load(shard.snapshot)
        stamp_ns, steps = int(saved["stamp_ns"]), int(saved["steps"])
    except (SnapshotError, KeyError) as exc:
        print(f"boatsim: cannot restart {shard.label}: {exc}", file=status)
        return False
    args = [a for a in shard.args if a != "--await-recorder"]
    if "--resume" not in args:
        args += ["--resume", str(shard.snapshot), "--epoch", repr(epoch)]
    if "--record" in args:  # a fresh part; the dead one's is cut at the snapshot
        i = args.index("--record") + 1
        cuts[Path(args[i])] = stamp_ns
        args[i] = f"{args[i]}+"
    shard.args, shard.status = args, None
    shard.restarts += 1
    _spawn(shard, handshake=False)
    print(f"boatsim: restarted {shard.label} (pid {shard.proc.pid}) from its snapshot at step "
          f"{steps} (t = {stamp_ns / 1e9 - epoch:g} s); the other processes wait for it at the "
          "step barrier; what its boats received since the snapshot is lost", file=status)
    return True


def _watch(children: list[_Child], epoch: float, stopping, status: TextIO,
           barrier: bool, cuts: dict[Path, int]) -> bool:
    """Until every dynamics process has exited: report deaths, restart what can be.

    Args:
        children: the ocean's child first.
        epoch: s, wall-clock time of simulation time 0 (a restarted ocean joins on it).
        stopping: forwards the signals the parent received; True once there was one.
        status: where to report.
        barrier: the processes share a step barrier (``--fast``): a dead dynamics process is
            restarted from its snapshot, or, when it has none (``--lockstep``), stops the run.
        cuts: filled with the bag parts of restarted processes and where to cut them, ns.

    Returns:
        True when a child died.
    """
    died = False
    shards = children[1:]
    ocean = children[0]
    while any(c.status is None for c in shards):
        time.sleep(_WATCH_PERIOD)
        stopped = stopping()  # forwards a SIGINT / SIGTERM the parent received
        for c in children:
            if c.status is not None or (code := c.proc.poll()) is None:
                continue
            c.status = code
            if code in (0, EXIT_STOPPED) or stopped:  # finished (a boat stopped is no crash)
                continue
            died = True
            print(f"boatsim: process {c.label} (pid {c.proc.pid}) died: {_describe(code)}",
                  file=status)
            if c is ocean:
                _restart_ocean(c, epoch, status)
            elif barrier and not _restart_shard(c, epoch, cuts, status):
                why = ("under --lockstep its commands since the snapshot would be missing"
                       if c.snapshot is None else f"restarted {c.restarts} times already")
                print(f"boatsim: stopping the run ({why}): the other processes would wait "
                      "for its boats at the step barrier forever", file=status)
                stop_processes([s.proc for s in shards], timeout=10.0)
    return died


def run_processes(scenario: Scenario, path: str, options: RunOptions,
                  status: TextIO | None = None) -> int:
    """Run ``scenario`` (read from ``path``) in processes; returns the exit status.

    ``options.process.shards`` dynamics processes and an ocean process.

    Raises:
        RecordError: the bag directory of ``options.record`` already exists.
    """
    status = sys.stderr if status is None else status  # now, not at import
    record = Path(options.record) if options.record else None
    if record is not None and record.exists():  # refused here, before any process starts
        raise RecordError(f"{record} already exists; choose a new directory for the bag")
    if record is not None:
        merge_orphaned_parts(record.parent, status)
    parts, recorder = _prepare_recording(record, options)
    snapshots = (Path(tempfile.mkdtemp(prefix=temporary_prefix("snapshots")))
                 if options.fast and not options.lockstep else None)
    children = _children(scenario, path, options, parts, snapshots)
    cuts: dict[Path, int] = {}
    signals: list[int] = []
    previous = {sig: signal.signal(sig, lambda signum, _: signals.append(signum))
                for sig in STOP_SIGNALS}  # (list.append takes no lock: see stop_on_signals)
    start = time.monotonic()
    try:
        for c in children:
            _spawn(c, handshake=True)
        kind = "boats" if options.process.shards == len(scenario.boats) else "shards"
        note = _apart_note(scenario, options.process.shards)
        if note:
            print(note, file=status)
        print(f"boatsim: started {len(children)} processes (ocean + {options.process.shards} {kind}"
              f"{', one clock: ' + _clock_words(options) if options.fast else ''}): pids "
              f"{' '.join(str(c.proc.pid) for c in children)}"
              + _recording_words(options, recorder, parts), file=status)
        if not _await_ready(children, lambda: bool(signals), status):
            return 0 if signals else 1
        epoch = 0.0 if options.fast else time.time() + _GO_AHEAD
        _go(children, epoch)
        print(f"boatsim: every process ready after {time.monotonic() - start:.1f} s"
              + (" (the recorder subscribed to each)" if recorder else "")
              + "; simulation time 0 is now", file=status)
        died = _watch(children, epoch, _forwarder(signals, children), status, options.fast,
                      cuts)
        stop_processes([children[0].proc])  # the ocean, when it runs with no duration
        ok = all(c.status in (0, None) for c in children) and not died
        if not ok and not died and any(c.status == EXIT_STOPPED for c in children):
            return EXIT_STOPPED
        return 0 if ok else 1
    finally:
        stop_processes([c.proc for c in children if c.proc is not None])
        if recorder is not None:
            stop_processes([recorder], timeout=30.0)
            print(f"boatsim: recorded to {options.record}", file=status)
        if parts is not None:
            _merge_parts(parts, record, status, cuts)
        if snapshots is not None:
            shutil.rmtree(snapshots, ignore_errors=True)
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _prepare_recording(record: Path | None, options: RunOptions
                       ) -> tuple[Path | None, subprocess.Popen | None]:
    """(a directory for a bag per process, or None; the recorder process, or None).

    Fast: each process writes its own bag, merged at the end. Real time: one recorder.
    """
    if record is None:
        return None, None
    if options.fast:
        parts = record.parent / f".{record.name}.parts-{os.getpid()}"
        shutil.rmtree(parts, ignore_errors=True)
        parts.mkdir(parents=True)
        return parts, None
    return None, _start_recorder(options.record, options.exclude_topics)


def _recording_words(options: RunOptions, recorder: subprocess.Popen | None,
                     parts: Path | None) -> str:
    if recorder is not None:
        return f"; recording to {options.record} (pid {recorder.pid})"
    if parts is not None:
        return (f"; recording to {options.record} (a bag per process in {parts}, merged at "
                "the end, or by the next run recording in that directory)")
    return ""


def _forwarder(signals: list[int], children: list[_Child]) -> Callable[[], bool]:
    """A ``stopping()`` for :func:`_watch`: True once a signal has come.

    Each call passes the signals new since the last on to the children still running.
    """
    forwarded = 0

    def stopping() -> bool:
        nonlocal forwarded
        for sig in signals[forwarded:]:
            for c in children:
                if c.proc.poll() is None:
                    c.proc.send_signal(sig)
        forwarded = len(signals)
        return bool(signals)

    return stopping


def _clock_words(options: RunOptions) -> str:
    return ("the ocean's process grants every step, after the replayer's grants (lockstep)"
            if options.lockstep else "the ocean's process grants every step")


def merge_orphaned_parts(directory: Path, status: TextIO) -> list[Path]:
    """Merge the per-process bags that a killed run left in ``directory``; returns the bags.

    A ``run --fast --record BAG`` over processes writes a bag per process into
    ``.BAG.parts-PID`` and merges them at its end; a parent killed with SIGKILL never does
    (its children, seeing it gone, close their bags). The next such run in that directory
    merges them into BAG, or into ``BAG.recovered-PID`` when BAG exists, and says so.
    """
    merged = []
    for parts in sorted(directory.glob(".*.parts-*")):
        name, _, pid = parts.name[1:].rpartition(".parts-")
        if not (pid.isdigit() and parts.is_dir()) or pid_alive(int(pid)):
            continue
        target = directory / name
        if target.exists():
            target = directory / f"{name}.recovered-{pid}"
        try:
            _merge_parts(parts, target, status, {})
        except Exception as exc:  # a damaged part: named, left for the user
            print(f"boatsim: warning: {parts} holds the bags of a run killed before it merged "
                  f"them (pid {pid}); merging them failed ({exc}); they are left there",
                  file=status)
            continue
        print(f"boatsim: {parts} held the bags of a run killed before it merged them (pid "
              f"{pid}): merged into {target}", file=status)
        merged.append(target)
    return merged


def _merge_parts(parts: Path, record: Path, status: TextIO, cuts: dict[Path, int]) -> None:
    """Merge the processes' bags in ``parts`` into ``record``, then remove them.

    ``cuts``: the parts of restarted processes, each taken up to its time (ns).
    """
    from boat_dynamics.tools.bagfile import merge

    bags = sorted(p for p in parts.iterdir() if p.is_dir() and any(p.glob("*.mcap")))
    if not bags:
        print(f"boatsim: nothing recorded (no process wrote a bag in {parts})", file=status)
        return
    counts = merge(bags, record, until={p: cuts[p] for p in bags if p in cuts})
    shutil.rmtree(parts, ignore_errors=True)
    print(f"boatsim: recorded {sum(counts.values())} messages on {len(counts)} topics to "
          f"{record} (merged from {len(bags)} processes' bags)", file=status)
