"""numba for the physics core: one decorator, and one cache that every process finds.

numba (https://numba.pydata.org) compiles the core's hot loops to machine code; ``cache=True``
keeps the result on disk so that only the first process compiles. numba's own default keeps
that cache beside the source, and a read-only install (a system site-packages, a container
image) makes it recompile silently in every process. So boatsim chooses the directory before
numba loads:

1. ``NUMBA_CACHE_DIR`` when set (numba's own variable: a run's processes share it);
2. else ``$XDG_CACHE_HOME/boatsim/numba`` (``~/.cache/boatsim/numba``);
3. when that cannot be written: ``<temp>/boatsim-numba-<uid>``, with a warning saying where
   to point ``NUMBA_CACHE_DIR`` instead (:data:`CACHE_WARNING`).

``make setup`` compiles every kernel once (each kernel module's ``warm``) and prints how long
it took.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from pathlib import Path

__all__ = ["CACHE_WARNING", "cache_dir", "kernel"]

#: The warning when the chosen cache directory cannot be written (``{chosen}``, ``{used}``).
CACHE_WARNING = ("boatsim: the compiled kernels' cache directory {chosen} cannot be written; "
                 "using {used} (set NUMBA_CACHE_DIR to a writable directory that every "
                 "process of a run sees, or they may each compile again)")


def _writable(path: Path) -> bool:
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(path, os.W_OK | os.X_OK)


def cache_dir() -> Path:
    """The directory numba caches boatsim's kernels in (see the module docstring)."""
    explicit = os.environ.get("NUMBA_CACHE_DIR")
    if explicit:
        chosen = Path(explicit)
    else:
        base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
        chosen = Path(base) / "boatsim" / "numba"
    if _writable(chosen):
        return chosen
    used = Path(tempfile.gettempdir()) / f"boatsim-numba-{os.getuid()}"
    warnings.warn(CACHE_WARNING.format(chosen=chosen, used=used), RuntimeWarning, stacklevel=2)
    used.mkdir(parents=True, exist_ok=True)
    return used


_CACHE = cache_dir()
os.environ["NUMBA_CACHE_DIR"] = str(_CACHE)  # before numba reads its configuration

import numba  # noqa: E402  (after NUMBA_CACHE_DIR)

numba.config.CACHE_DIR = str(_CACHE)  # numba loaded earlier by someone else: still ours


def kernel(function):
    """Compile ``function`` with numba: nopython, cached on disk, IEEE arithmetic.

    ``error_model="numpy"``: a division by zero gives inf or nan as numpy does (the kernels'
    numpy oracles), not an exception; no ``fastmath``, so results keep float64 rounding.
    """
    return numba.njit(cache=True, nogil=True, error_model="numpy")(function)
