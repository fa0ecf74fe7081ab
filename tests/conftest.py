"""The whole suite: one OpenBLAS thread, as every `boatsim` process runs (boat_dynamics/cli.py).

Set before numpy loads (pytest imports this file first, in each xdist worker too; numpy is not
loaded by then), unless the environment sets it. With OpenBLAS's default, a thread per core,
two xdist workers ran four BLAS threads on two cores, and each large product (the radiation
memory fit's SVD at every start of a hull with a coefficient file) spun waiting for a core:
with both cores busy, `test_scenario_fuzz.py -k structural` took 113 s, 21 s with one thread.
"""

import os

import pytest

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


@pytest.fixture
def ros_context(monkeypatch):
    """An rclpy context of the test's own, on localhost and a domain of this process's own.

    For nodes made in-process and fed their callbacks directly (no graph). Domain 10 plus
    the pytest-xdist worker's number (gw0, gw1, ...): tests/ros uses 30-231, after this part
    of the suite.
    """
    import rclpy

    worker = int(os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw"))
    monkeypatch.setenv("ROS_DOMAIN_ID", str(10 + worker))
    monkeypatch.setenv("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    monkeypatch.delenv("ROS_LOCALHOST_ONLY", raising=False)
    context = rclpy.Context()
    rclpy.init(context=context)
    yield context
    rclpy.try_shutdown(context=context)
