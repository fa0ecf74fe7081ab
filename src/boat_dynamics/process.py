"""A process-wide setting for speed, applied by ``boatsim`` (and the benchmarks) at start-up.

(The other one, one BLAS thread, is an environment variable that ``boatsim`` sets before
numpy loads: see :mod:`boat_dynamics.cli`.)
"""

from __future__ import annotations

import ctypes
import sys

__all__ = ["keep_freed_memory"]

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
