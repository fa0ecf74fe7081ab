"""Process-wide settings, and child processes that die with their parent.

Memory kept for speed is applied by ``boatsim`` and the benchmarks at start-up.

(The other speed setting, one BLAS thread, is an environment variable that ``boatsim`` sets
before numpy loads: see :mod:`boat_dynamics.cli`.)
"""

from __future__ import annotations

import ctypes
import signal
import subprocess
import sys

__all__ = ["die_with_parent", "keep_freed_memory", "start_child"]

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
