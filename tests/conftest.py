"""The whole suite: one OpenBLAS thread, as every `boatsim` process runs (boat_dynamics/cli.py).

Set before numpy loads (pytest imports this file first, in each xdist worker too; numpy is not
loaded by then), unless the environment sets it. With OpenBLAS's default, a thread per core,
two xdist workers ran four BLAS threads on two cores, and each large product (the radiation
memory fit's SVD at every start of a hull with a coefficient file) spun waiting for a core:
with both cores busy, `test_scenario_fuzz.py -k structural` took 113 s, 21 s with one thread.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
