"""ROS end-to-end fixtures: an isolated domain, `boatsim` subprocesses, a probe node.

Every test here runs on a ROS_DOMAIN_ID of its own (from the pytest process id and the
test's place in the run: a process a test SIGKILLed stays listed on its domain for its DDS
lease, 4 s for boatsim's processes and 20 s for others such as a probe, and a client of the
next test could send its request to that ghost only) with
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST, and stops every process it starts: at its end, any
process still carrying its BOATSIM_TEST_TAG (a child of a killed parent, for instance) is
given 20 s and then killed, with a warning.
"""

import itertools
import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: pytest-xdist's worker (gw0, gw1, ...) and their number: each worker has its own share of
#: the domains below, so two tests running at once never share one.
_WORKER = int(os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw"))
_WORKERS = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))


def _domain(first: int, count: int, i: int) -> int:
    """The ``i``-th domain of this worker's share of ``first .. first + count - 1``."""
    span = count // _WORKERS
    return first + _WORKER * span + i % span


#: Before a test's own domain is set (module fixtures): domains 30-99.
DOMAIN_ID = str(_domain(30, 70, os.getpid()))
os.environ["ROS_DOMAIN_ID"] = DOMAIN_ID
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.pop("ROS_LOCALHOST_ONLY", None)

import rclpy  # noqa: E402  (after the environment is set)
from rclpy.executors import SingleThreadedExecutor  # noqa: E402

pytestmark = pytest.mark.ros

#: Domains 101-231 (each a few UDP ports on localhost), one per test in turn.
_DOMAINS = (_domain(101, 131, os.getpid() * 7 + i) for i in itertools.count())


_TAGS = itertools.count()


def _tagged(tag: str) -> list[int]:
    """The processes whose environment holds ``BOATSIM_TEST_TAG=tag`` (zombies do not)."""
    entry = f"BOATSIM_TEST_TAG={tag}".encode()
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/environ", "rb") as environ:
                if entry in environ.read().split(b"\0"):
                    pids.append(int(pid))
        except OSError:  # gone, or not ours
            pass
    return pids


#: s of each file's tests, measured (the sums of `--durations=0` of this stage, two workers):
#: the order in which `make test`'s `--dist loadfile` hands the files to its workers, longest
#: first (see pytest_xdist_make_scheduler). A file not listed counts 6 s a test.
FILE_SECONDS = {
    "test_end_to_end.py": 140, "test_scale_out.py": 103, "test_regression.py": 96,
    "test_introspection_verbs.py": 60, "test_sensors.py": 52, "test_waypoints.py": 43,
    "test_view.py": 37, "test_golden.py": 25, "test_ocean_node.py": 25,
    "test_thrusters.py": 20, "test_fuzz.py": 13, "test_world.py": 12,
    "test_wrench_topics.py": 10, "test_fleet_state.py": 8, "test_hostile_inputs.py": 7,
    "test_wake_crossing.py": 18, "test_current_and_wind.py": 5, "test_lockstep_client.py": 4,
    "test_benchmarks.py": 1,
}


@pytest.hookimpl(optionalhook=True)  # pytest-xdist's hook: no error without it
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadfile``: the longest files first (:data:`FILE_SECONDS`), not the ones with
    the most tests (pytest-xdist's order): it handed out test_waypoints.py's one 46 s test
    last, and the other worker waited for it."""
    if config.getvalue("dist") != "loadfile":
        return None
    from xdist.scheduler import LoadFileScheduling

    class LongestFirst(LoadFileScheduling):
        _sorted = False

        def _assign_work_unit(self, node):
            if not self._sorted:  # the queue is complete on the first assignment
                units = sorted(self.workqueue.items(), key=lambda unit: -_seconds(*unit))
                self.workqueue.clear()
                self.workqueue.update(units)
                self._sorted = True
            super()._assign_work_unit(node)

    return LongestFirst(config, log)


def _seconds(scope: str, tests: dict) -> float:
    """The expected s of a file's tests (:data:`FILE_SECONDS`)."""
    return FILE_SECONDS.get(Path(scope).name, 6.0 * len(tests))


@pytest.fixture(autouse=True)
def own_domain(monkeypatch, request):
    """A ROS_DOMAIN_ID of the test's own for its processes and probe; none left at its end.

    Set up before the test's other fixtures, so torn down after them: the ``boatsim``
    processes are stopped by then, and what is left was lost (a ``--processes`` child
    outliving its killed parent once slept 1.5 h on the machine).
    """
    monkeypatch.setenv("ROS_DOMAIN_ID", str(next(_DOMAINS)))
    tag = f"{os.getpid()}-{next(_TAGS)}"
    monkeypatch.setenv("BOATSIM_TEST_TAG", tag)
    yield
    end = time.monotonic() + 20.0
    while (left := _tagged(tag)) and time.monotonic() < end:
        time.sleep(0.1)
    for pid in left:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    if left:
        warnings.warn(f"{request.node.name} left processes {left}: killed after 20 s",
                      stacklevel=1)


class Boatsim:
    """A `boatsim` subprocess whose output goes to a file (no pipe can fill up)."""

    def __init__(self, args, tmp_path: Path, name: str = "boatsim") -> None:
        self.log_path = tmp_path / f"{name}.log"
        self._log = open(self.log_path, "w")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "boat_dynamics", *args],
            stdout=self._log, stderr=subprocess.STDOUT, cwd=ROOT, env=os.environ.copy(),
        )

    def output(self) -> str:
        if not self._log.closed:
            self._log.flush()
        return self.log_path.read_text()

    def wait(self, timeout: float) -> int:
        try:
            return self.proc.wait(timeout=timeout)
        finally:
            self._log.close()

    def stop(self, sig=signal.SIGINT, timeout: float = 15.0) -> int:
        """Send ``sig``, wait; kill if it does not exit in ``timeout`` s. Returns the status."""
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._log.close()
        return self.proc.returncode


@pytest.fixture
def boatsim(tmp_path):
    started = []

    def start(*args, name="boatsim"):
        sim = Boatsim(list(args), tmp_path, name=f"{name}{len(started)}")
        started.append(sim)
        return sim

    yield start
    for sim in started:
        sim.stop(signal.SIGKILL if sim.proc.poll() is None else signal.SIGINT, timeout=5)


class Probe:
    """A test-side node with helpers to spin until a condition holds."""

    def __init__(self) -> None:
        self.context = rclpy.Context()
        rclpy.init(context=self.context)
        self.node = rclpy.create_node("probe", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._others = []

    def other_node(self, name: str):
        """A second node of the probe's, named ``name`` (spun with it, destroyed by close)."""
        node = rclpy.create_node(name, context=self.context)
        self.executor.add_node(node)
        self._others.append(node)
        return node

    def spin_for(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while (left := end - time.monotonic()) > 0:
            self.executor.spin_once(timeout_sec=min(left, 0.05))

    def spin_until(self, predicate, timeout: float, what: str = "condition") -> None:
        end = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() > end:
                raise AssertionError(f"timed out after {timeout} s waiting for {what}")
            self.executor.spin_once(timeout_sec=0.05)

    def call(self, client, request, timeout: float = 10.0):
        assert client.wait_for_service(timeout_sec=timeout), "service not available"
        future = client.call_async(request)
        self.spin_until(future.done, timeout, "service response")
        return future.result()

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=1.0)
        for node in self._others:
            node.destroy_node()
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)


@pytest.fixture
def probe():
    p = Probe()
    yield p
    p.close()
