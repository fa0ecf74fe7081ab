"""Process settings: memory tuning (applied on this Linux/glibc machine, harmless to call
twice), and signal handlers that cannot deadlock."""

import ctypes
import os
import signal
import subprocess
import sys
import textwrap
import threading

from boat_msgs_py.process import MMAP_THRESHOLD, keep_freed_memory, stop_on_signals


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


def _python(code: str, stdin: int | None = None) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(code)], stdin=stdin,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _outcome(process: subprocess.Popen, timeout: float = 60.0) -> str:
    """The process's stdout once it ends, or "hung" (then it is killed)."""
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        return "hung"
    assert process.returncode == 0, err
    return out


def test_a_stop_signal_that_interrupts_the_events_own_lock_does_not_deadlock():
    # A Python handler runs between two bytecodes of the main thread, for instance inside an
    # earlier handler's Event.set, while the event's (not re-entrant) lock is held. Holding
    # that lock and raising the signal puts the handler exactly there. A handler calling
    # stop.set() blocks for ever at this point (measured: the old lambda hangs).
    process = _python("""
        import signal, threading
        from boat_msgs_py.process import stop_on_signals
        stop = threading.Event()
        restore = stop_on_signals(stop)
        with stop._cond:  # the lock Event.set holds
            signal.raise_signal(signal.SIGTERM)
            signal.raise_signal(signal.SIGINT)
            print("handlers returned", stop.is_set())
        print("stop set", stop.wait(30))
        restore()
    """)
    # the relay sets stop once the lock is free, not before
    assert _outcome(process).split("\n")[:2] == ["handlers returned False", "stop set True"]


def test_a_burst_of_stop_signals_ends_the_process():
    # The deadlock as seen: a --processes child (stop on SIGINT/SIGTERM or on stdin's end)
    # that gets several SIGTERMs close together. With handlers calling stop.set(), this
    # burst hung 17 child processes in 20.
    for _ in range(3):
        process = _python("""
            import threading
            from boat_msgs_py.process import stop_on_signals, watch_stdin
            stop = threading.Event()
            restore = stop_on_signals(stop)
            watch_stdin(stop)
            print("ready", flush=True)
            while not stop.is_set():
                pass
            restore()
            print("stopped")
        """, stdin=subprocess.PIPE)
        assert process.stdout.readline() == "ready\n"
        for _ in range(200):
            process.send_signal(signal.SIGTERM)
        assert _outcome(process) == "stopped\n"  # (communicate closes its stdin)


def test_stop_on_signals_puts_back_the_previous_handlers_and_leaves_no_thread_or_fd():
    before = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    fds = set(os.listdir("/proc/self/fd"))
    stop = threading.Event()
    restore = stop_on_signals(stop)
    assert signal.getsignal(signal.SIGTERM) is not before[signal.SIGTERM]
    signal.raise_signal(signal.SIGINT)
    assert stop.wait(30)
    relay = next(t for t in threading.enumerate() if t.name == "boatsim-signals")
    restore()
    relay.join(30)
    assert not relay.is_alive()
    assert {sig: signal.getsignal(sig) for sig in before} == before
    assert set(os.listdir("/proc/self/fd")) == fds


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_the_next_run_sweeps_what_a_killed_run_left_in_the_temp_directory(tmp_path, monkeypatch):
    import tempfile

    from boat_msgs_py.process import SharedTime, sweep_temporaries, temporary_prefix

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    dead = _dead_pid()
    (tmp_path / f"boatsim-snapshots-{dead}-abc").mkdir()
    (tmp_path / f"boatsim-snapshots-{dead}-abc" / "shard-0.npz").write_bytes(b"x")
    (tmp_path / f"boatsim-time-{dead}-xyz").write_bytes(bytes(8))
    ours = tmp_path / f"{temporary_prefix('snapshots')}live"
    ours.mkdir()
    other = tmp_path / "boatsim-test-chromium"  # not ours: no pid in its name
    other.mkdir()
    shared = SharedTime()  # in /dev/shm where there is one: named with our pid
    try:
        assert shared.path.name.startswith(temporary_prefix("time"))
        removed = sweep_temporaries()
        assert sorted(p.name for p in removed) == [f"boatsim-snapshots-{dead}-abc",
                                                   f"boatsim-time-{dead}-xyz"]
        assert ours.exists() and other.exists() and shared.path.exists()
    finally:
        shared.close()


def test_the_next_run_merges_the_bags_a_killed_parent_left(tmp_path):
    import io

    from boat_dynamics.ros.processes import merge_orphaned_parts
    from boat_dynamics.tools.bagfile import JazzyWriter
    from boat_dynamics.tools.bags import read_bag
    from boat_msgs_py.typestore import typestore

    store = typestore()
    clock, time_ = store.types["rosgraph_msgs/msg/Clock"], store.types[
        "builtin_interfaces/msg/Time"]

    def part(path, steps):
        writer = JazzyWriter(path)
        writer.open()
        conn = writer.add_connection("/clock", "rosgraph_msgs/msg/Clock", typestore=store)
        for k in steps:
            data = store.serialize_cdr(clock(time_(0, k * 10_000_000)), "rosgraph_msgs/msg/Clock")
            writer.write(conn, k * 10_000_000, bytes(data))
        writer.close()

    dead = _dead_pid()
    for name in ("bag", "taken"):
        parts = tmp_path / f".{name}.parts-{dead}"
        parts.mkdir()
        part(parts / "ocean", range(0, 50, 2))
        part(parts / "shard-0", range(1, 50, 2))
    (tmp_path / "taken").mkdir()  # its name was used since: merged beside it
    live = tmp_path / f".live.parts-{os.getpid()}"  # a run still going: left alone
    live.mkdir()
    status = io.StringIO()

    merged = merge_orphaned_parts(tmp_path, status)

    assert merged == [tmp_path / "bag", tmp_path / f"taken.recovered-{dead}"]
    for bag in merged:
        assert [t for t, _ in read_bag(bag)["/clock"]] == [k * 10_000_000 for k in range(50)]
    assert not list(tmp_path.glob(f".*.parts-{dead}")) and live.exists()
    assert f"held the bags of a run killed before it merged them (pid {dead})" in status.getvalue()
