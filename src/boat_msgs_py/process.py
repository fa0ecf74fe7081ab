"""Process-wide settings, and child processes that die with their parent.

Memory kept for speed is applied by ``boatsim`` and the benchmarks at start-up.

(The other speed setting, one BLAS thread, is an environment variable that ``boatsim`` sets
before numpy loads: see :mod:`boat_dynamics.cli`.)
"""

from __future__ import annotations

import ctypes
import mmap
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path

__all__ = ["STOP_SIGNALS", "SharedTime", "die_with_parent", "keep_freed_memory", "pid_alive",
           "start_child", "stop_on_signals", "stop_processes", "sweep_temporaries",
           "temporary_prefix", "watch_stdin"]

#: prctl option: the signal a process gets when its parent dies (linux/prctl.h).
_PR_SET_PDEATHSIG = 1


def die_with_parent() -> None:
    """In a child, before exec: SIGTERM when the parent dies (Linux; elsewhere nothing)."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


def start_child(args: list[str], **popen) -> subprocess.Popen:
    """A ``boatsim`` child process (``python -m boat_dynamics ARGS``) that dies with this one.

    Its stdin is a pipe from this process, so it also sees this process end on any system.
    """
    return subprocess.Popen([sys.executable, "-m", "boat_dynamics", *args],
                            stdin=subprocess.PIPE, preexec_fn=die_with_parent, **popen)


def watch_stdin(stop: threading.Event, on_line: Callable[[str], None] | None = None) -> None:
    """In a child of :func:`start_child`: a thread reading stdin.

    It hands each line to ``on_line`` and sets ``stop`` when stdin ends (the parent died or
    closed the pipe).
    """
    def listen() -> None:
        for line in sys.stdin:
            if on_line is not None:
                on_line(line)
        stop.set()

    threading.Thread(target=listen, daemon=True, name="boatsim-stdin").start()


#: The signals that end a run cleanly: Ctrl-C, and ``kill`` (or a parent's death, see
#: :func:`die_with_parent`).
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def stop_on_signals(stop: threading.Event,
                    signals: Sequence[int] = STOP_SIGNALS) -> Callable[[], None]:
    """In the main thread: set ``stop`` when one of ``signals`` arrives.

    A Python signal handler runs in the main thread between two bytecodes, so it can
    interrupt anything, an earlier handler included. A handler calling ``stop.set()`` can
    interrupt another's ``stop.set()`` while that one holds the event's lock, which is not
    re-entrant: the process then sleeps for ever (seen: a ``--processes`` child asleep 1.5 h
    after its parent died, when three SIGTERMs came close together). So the handler takes no
    lock: it writes a byte to a pipe, and a thread reading the pipe sets ``stop``.

    Args:
        stop: the event to set.
        signals: the signal numbers to catch.

    Returns:
        A function that puts the previous handlers back and ends the thread (call it from the
        main thread, once).
    """
    read, write = os.pipe()
    os.set_blocking(write, False)

    def handler(signum: int, frame: object) -> None:
        try:
            os.write(write, b"\0")
        except OSError:  # the pipe is full: a stop is already on its way
            pass

    def relay() -> None:
        while os.read(read, 64):  # b"" once restore() has closed the other end
            stop.set()
        os.close(read)

    previous = {sig: signal.signal(sig, handler) for sig in signals}
    threading.Thread(target=relay, daemon=True, name="boatsim-signals").start()

    def restore() -> None:
        for sig, old in previous.items():
            signal.signal(sig, old)
        os.close(write)  # no handler of ours can run any more: the fd may be reused

    return restore


def stop_processes(processes: Sequence[subprocess.Popen], sig: int = signal.SIGINT,
                   timeout: float = 10.0) -> None:
    """Send ``sig`` to those still running; kill any that outlives ``timeout`` (s, shared)."""
    running = [p for p in processes if p.poll() is None]
    for p in running:
        p.send_signal(sig)
    deadline = time.monotonic() + timeout
    for p in running:
        try:
            p.wait(timeout=max(deadline - time.monotonic(), 0.01))
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()

#: glibc mallopt parameters (malloc.h).
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3
#: Allocations up to this size come from the heap, not from fresh mmap'd pages (glibc's
#: maximum on 64-bit systems).
MMAP_THRESHOLD = 32 * 1024 * 1024
#: Freed heap memory up to this size stays with the process.
TRIM_THRESHOLD = 512 * 1024 * 1024


def keep_freed_memory() -> bool:
    """Let the C allocator keep and reuse freed memory instead of returning it to the system.

    numpy allocates each temporary array of a step anew. With glibc's defaults, arrays above
    a few hundred kB are mapped fresh and unmapped again, and the page faults of touching
    them cost more than the arithmetic: a step of 10 hulls of 972 triangles took 4.9-6.6 ms,
    2.4-3.6 ms with these settings (benchmarks/run.py, this 2-core machine). The process
    keeps its peak heap (tens of MB) in exchange.

    Returns:
        True if applied (Linux with glibc), False elsewhere (then nothing changed).
    """
    if not sys.platform.startswith("linux"):
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # not glibc (musl has no mallopt)
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    return bool(mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)
                and mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))


def _temporary_dirs() -> list[Path]:
    """Where boatsim's temporary files and folders live: the temp directory, and /dev/shm."""
    dirs = [Path(tempfile.gettempdir())]
    return [*dirs, Path("/dev/shm")] if os.path.isdir("/dev/shm") else dirs


def temporary_prefix(kind: str) -> str:
    """``boatsim-KIND-PID-``: the name of a temporary of this process starts so.

    The pid lets :func:`sweep_temporaries` tell a dead process's leftovers from a live one's.
    """
    return f"boatsim-{kind}-{os.getpid()}-"


def pid_alive(pid: int) -> bool:
    """Whether a process ``pid`` exists (another user's counts as alive)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return pid > 0


def sweep_temporaries() -> list[Path]:
    """Remove the temporaries (:func:`temporary_prefix`) of boatsim processes that are gone.

    A process killed with SIGKILL (or an OOM kill) cannot remove its snapshot folder or its
    shared-time file; the next boatsim run does. Returns what was removed.
    """
    removed = []
    for folder in _temporary_dirs():
        for p in folder.glob("boatsim-*-*-*"):
            pid = p.name.split("-")[2]
            if not pid.isdigit() or pid_alive(int(pid)):
                continue
            if p.is_dir():
                shutil.rmtree(p, ignore_errors=True)
            else:
                p.unlink(missing_ok=True)
            removed.append(p)
    return removed


class SharedTime:
    """One float64 (a time, s) in a memory-mapped file that another process reads.

    The simulation writes its time every step (a store of 8 aligned bytes, atomic on the
    machines ROS runs on, about 0.3 us); the surface server reads it when asked, with no
    message per step (following /clock over DDS cost it a third of a core in --fast mode).

    Args:
        path: the file; None = create one in /dev/shm (or the temp directory), removed by
            :meth:`close`, and open it for writing.
    """

    _FORMAT = struct.Struct("<d")

    def __init__(self, path: str | Path | None = None) -> None:
        self._owner = path is None
        if self._owner:
            shm = "/dev/shm" if os.path.isdir("/dev/shm") else None
            fd, name = tempfile.mkstemp(prefix=temporary_prefix("time"), dir=shm)
            os.write(fd, bytes(self._FORMAT.size))
            self.path = Path(name)
        else:
            self.path = Path(path)
            fd = os.open(self.path, os.O_RDONLY)
        access = mmap.ACCESS_WRITE if self._owner else mmap.ACCESS_READ
        self._map = mmap.mmap(fd, self._FORMAT.size, access=access)
        os.close(fd)

    def write(self, t: float) -> None:
        """Store ``t`` (s)."""
        self._FORMAT.pack_into(self._map, 0, t)

    def read(self) -> float:
        """The stored time, s."""
        return self._FORMAT.unpack_from(self._map, 0)[0]

    def close(self) -> None:
        """Unmap; the creator also removes the file."""
        self._map.close()
        if self._owner:
            self.path.unlink(missing_ok=True)
