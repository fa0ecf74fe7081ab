"""Process tuning: applied on this Linux/glibc machine, harmless to call twice."""

import ctypes
import subprocess
import sys

from boat_dynamics.process import MMAP_THRESHOLD, keep_freed_memory


def test_freed_memory_is_kept_on_glibc():
    assert keep_freed_memory() is True
    assert keep_freed_memory() is True  # idempotent
    # the mallopt call refuses a threshold above glibc's maximum: ours is accepted
    mallopt = ctypes.CDLL(None).mallopt
    assert mallopt(-3, MMAP_THRESHOLD) == 1


def _page_faults(setup: str) -> int:
    """Minor page faults of 50 rounds of six 1.4 MB temporaries (as in a step of big hulls)."""
    code = (f"{setup}\nimport resource, numpy as np\n"
            "def step(): return sum(a.sum() for a in [np.ones(180_000) for _ in range(6)])\n"
            "step()\n"
            "before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt\n"
            "for _ in range(50): step()\n"
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    return int(out)


def test_boatsim_reuses_freed_memory():
    # glibc's defaults hand the freed temporaries back to the system, and the next round
    # faults every page in again (1e5 faults measured); boatsim keeps them
    assert _page_faults("pass") > 20_000
    assert _page_faults("import boat_dynamics.cli") < 1_000
