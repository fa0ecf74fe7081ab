"""Crash-safe bags and their recovery (boat_dynamics.tools.bagfile), checked with rosbags,
the mcap library and boatsim's own bag reader.

The writer runs in a child process that is killed with SIGKILL, as an OOM kill or a CI
time-out would; the stamps are bag time, so nothing here depends on the machine's speed.
"""

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import yaml
from geometry_msgs.msg import WrenchStamped
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mcap.reader import make_reader
from rclpy.serialization import serialize_message
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import Reader, StoragePlugin, Writer

from boat_dynamics.tools.bagfile import (
    CHUNK_SPAN_NS,
    LOCK_NAME,
    ROS_DISTRO,
    JazzyWriter,
    ReindexError,
    merge,
    recorder_alive,
    reindex,
)
from boat_dynamics.tools.bags import BagError, read_bag
from boat_msgs_py.typestore import typestore, zero_padding

STEP_NS = 10_000_000  # 100 Hz
CLOCK = "rosgraph_msgs/msg/Clock"
WRENCH = "geometry_msgs/msg/WrenchStamped"

_WRITER = textwrap.dedent("""
    import sys, time
    from boat_dynamics.tools.bagfile import JazzyWriter
    from boat_msgs_py.typestore import typestore, zero_padding
    store = typestore()
    Clock = store.types["rosgraph_msgs/msg/Clock"]
    Time = store.types["builtin_interfaces/msg/Time"]
    writer = JazzyWriter(sys.argv[1])
    writer.open()
    conn = writer.add_connection("/clock", "rosgraph_msgs/msg/Clock", typestore=store)
    n = int(sys.argv[2])
    for i in range(n):
        t = i * {step}
        data = store.serialize_cdr(Clock(Time(t // 10**9, t % 10**9)), "rosgraph_msgs/msg/Clock")
        writer.write(conn, t, bytes(data))
    print("written", (n - 1) * {step}, flush=True)
    time.sleep(600)
""").format(step=STEP_NS)


def _clock(t_ns: int) -> bytes:
    store = typestore()
    msg = store.types[CLOCK](store.types["builtin_interfaces/msg/Time"](t_ns // 10**9,
                                                                           t_ns % 10**9))
    return bytes(store.serialize_cdr(msg, CLOCK))


def _write_bag(path: Path, n: int, close: bool = True) -> JazzyWriter:
    """A bag of ``n`` /clock messages 10 ms apart (and a wrench every 10th)."""
    store = typestore()
    writer = JazzyWriter(path)
    writer.open()
    clock = writer.add_connection("/clock", CLOCK, typestore=store)
    wrench = writer.add_connection("/wrench/total", WRENCH, typestore=store)
    empty = zero_padding(serialize_message(WrenchStamped()), WRENCH)
    for i in range(n):
        writer.write(clock, i * STEP_NS, _clock(i * STEP_NS))
        if i % 10 == 0:
            writer.write(wrench, i * STEP_NS, empty)
    if close:
        writer.close()
    return writer


def _die(writer: JazzyWriter) -> None:
    """What the kernel does to a killed recorder's lock: release it (the file stays)."""
    os.close(writer._lock)


def _stamps(bag: Path) -> list[int]:
    with AnyReader([bag]) as reader:
        conns = [c for c in reader.connections if c.topic == "/clock"]
        return [t for _, t, _ in reader.messages(connections=conns)]


def test_a_recording_killed_mid_write_keeps_all_but_its_last_second(tmp_path):
    bag = tmp_path / "bag"
    n = 1234  # 12.33 s of bag time
    child = subprocess.Popen([sys.executable, "-c", _WRITER, str(bag), str(n)],
                             stdout=subprocess.PIPE, text=True)
    try:
        line = child.stdout.readline()
        assert line.startswith("written"), line
        last_written = int(line.split()[1])
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    assert not (bag / "metadata.yaml").exists()
    with pytest.raises(BagError, match="boatsim reindex"):  # the verbs say what to do
        read_bag(bag)

    report = reindex(bag)

    stamps = _stamps(bag)
    assert stamps == [i * STEP_NS for i in range(len(stamps))]  # a prefix, in order
    assert last_written - stamps[-1] < 1_000_000_000, (
        f"kept up to {stamps[-1] / 1e9} s of {last_written / 1e9} s")
    assert report.counts == {"/clock": len(stamps)}
    assert report.end_ns == stamps[-1]
    assert len(read_bag(bag)["/clock"]) == len(stamps)  # boatsim's reader
    with open(bag / "bag.mcap", "rb") as f:  # the mcap library, through the summary
        summary = make_reader(f).get_summary()
    assert summary.statistics.message_count == len(stamps)


def test_chunks_span_at_most_one_second_and_are_on_disk_before_close(tmp_path):
    writer = _write_bag(tmp_path / "bag", 550, close=False)  # 5.49 s, not closed
    on_disk = (tmp_path / "bag" / "bag.mcap").stat().st_size
    writer.close()
    with open(tmp_path / "bag" / "bag.mcap", "rb") as f:
        chunks = make_reader(f).get_summary().chunk_indexes
    spans = [c.message_end_time - c.message_start_time for c in chunks]
    assert len(chunks) == 11  # 5.49 s in spans under 0.5 s
    assert max(spans) < CHUNK_SPAN_NS
    assert on_disk > 0.8 * (tmp_path / "bag" / "bag.mcap").stat().st_size


def test_flush_due_writes_a_quiet_chunk_out(tmp_path):
    writer = _write_bag(tmp_path / "bag", 5, close=False)
    size = (tmp_path / "bag" / "bag.mcap").stat().st_size
    writer.flush_due(40 * STEP_NS)  # 0.4 s after the first message: not yet
    assert (tmp_path / "bag" / "bag.mcap").stat().st_size == size
    writer.flush_due(CHUNK_SPAN_NS)
    assert (tmp_path / "bag" / "bag.mcap").stat().st_size > size + 5 * 30
    writer.close()


def test_bags_say_jazzy_and_carry_each_channels_type_hash(tmp_path):
    _write_bag(tmp_path / "bag", 20)
    with Reader(tmp_path / "bag") as reader:
        assert reader.ros_distro == ROS_DISTRO == "jazzy"
    with open(tmp_path / "bag" / "bag.mcap", "rb") as f:
        mcap = make_reader(f)
        channels = mcap.get_summary().channels.values()
        schemas = mcap.get_summary().schemas
        embedded = yaml.safe_load(next(mcap.iter_metadata()).metadata["serialized_metadata"])
    assert embedded["ros_distro"] == "jazzy"
    assert {c.topic: c.metadata["topic_type_hash"] for c in channels} == {
        "/clock": typestore().hash_rihs01(CLOCK),
        "/wrench/total": typestore().hash_rihs01(WRENCH)}
    assert {schemas[c.schema_id].name for c in channels} == {CLOCK, WRENCH}


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(cut=st.floats(0.0, 1.0))
def test_reindex_of_a_bag_cut_anywhere_keeps_a_readable_prefix(tmp_path_factory, cut):
    root = tmp_path_factory.mktemp("cut")
    _write_bag(root / "full", 330)
    data = (root / "full" / "full.mcap").read_bytes()
    (root / "bag").mkdir()
    length = max(8, int(cut * len(data)))
    (root / "bag" / "bag.mcap").write_bytes(data[:length])

    report = reindex(root / "bag")

    stamps = _stamps(root / "bag") if report.counts else []
    assert stamps == [i * STEP_NS for i in range(len(stamps))]
    assert 0 <= report.dropped_bytes < length
    if length == len(data):
        assert len(stamps) == 330 and report.dropped_bytes == 0


def test_reindex_leaves_a_whole_closed_bag_alone(tmp_path):
    _write_bag(tmp_path / "bag", 250)
    files = {p.name: p.read_bytes() for p in (tmp_path / "bag").iterdir()}
    report = reindex(tmp_path / "bag")
    assert report.counts == {"/clock": 250, "/wrench/total": 25}
    assert report.whole and report.lost == 0 and report.original is None
    assert {p.name: p.read_bytes() for p in (tmp_path / "bag").iterdir()} == files


def test_reindex_keeps_the_original_and_is_idempotent(tmp_path):
    _write_bag(tmp_path / "bag", 250)
    before = read_bag(tmp_path / "bag")
    (tmp_path / "bag" / "metadata.yaml").unlink()  # as a killed recording has none
    original = (tmp_path / "bag" / "bag.mcap").read_bytes()
    report = reindex(tmp_path / "bag")
    assert report.original == tmp_path / "bag" / "bag.mcap.orig"
    assert report.original.read_bytes() == original
    first = (tmp_path / "bag" / "bag.mcap").read_bytes()
    assert reindex(tmp_path / "bag").original is None  # whole now: left alone
    assert (tmp_path / "bag" / "bag.mcap").read_bytes() == first
    after = read_bag(tmp_path / "bag")
    assert {t: len(m) for t, m in after.items()} == {"/clock": 250, "/wrench/total": 25}
    assert [s for s, _ in after["/clock"]] == [s for s, _ in before["/clock"]]


def test_reindex_computes_the_type_hash_of_a_bag_that_lacks_it(tmp_path):
    store = typestore()
    with Writer(tmp_path / "old", version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        conn = writer.add_connection("/clock", CLOCK, typestore=store)
        writer.write(conn, 0, _clock(0))
    (tmp_path / "old" / "metadata.yaml").unlink()
    reindex(tmp_path / "old")
    with open(tmp_path / "old" / "old.mcap", "rb") as f:
        (channel,) = make_reader(f).get_summary().channels.values()
    assert channel.metadata["topic_type_hash"] == store.hash_rihs01(CLOCK)


@pytest.mark.parametrize("content", [None, b"", b"not an mcap file at all",
                                     os.urandom(4096)])
def test_reindex_refuses_what_is_not_a_bag(tmp_path, content):
    bag = tmp_path / "bag"
    bag.mkdir()
    if content is not None:
        (bag / "bag.mcap").write_bytes(content)
    with pytest.raises(ReindexError, match="bag"):
        reindex(bag)
    assert not (tmp_path / ".bag.reindex").exists()


def _clock_bag(path: Path, steps: list[int], topic: str = "/clock", close: bool = True
               ) -> None:
    store = typestore()
    writer = JazzyWriter(path)
    writer.open()
    conn = writer.add_connection(topic, CLOCK, typestore=store)
    for i in steps:
        writer.write(conn, i * STEP_NS, _clock(i * STEP_NS))
    if close:
        writer.close()
    else:
        _die(writer)


def test_merge_joins_the_bags_of_several_processes_in_time_order(tmp_path):
    _clock_bag(tmp_path / "a", list(range(0, 300, 2)))
    _clock_bag(tmp_path / "b", list(range(1, 300, 2)))
    _clock_bag(tmp_path / "c", [0, 150, 299], topic="/other")
    # a process killed while recording: no summary; its chunks up to its last second count
    _clock_bag(tmp_path / "killed", list(range(200)), topic="/late", close=False)

    counts = merge([tmp_path / p for p in ("a", "b", "c", "killed")], tmp_path / "all")

    late = counts.pop("/late")
    assert counts == {"/clock": 300, "/other": 3} and 100 <= late < 200
    assert _stamps(tmp_path / "all") == [i * STEP_NS for i in range(300)]
    with AnyReader([tmp_path / "all"]) as reader:
        order = [(t, c.topic) for c, t, _ in reader.messages()]
    assert order == sorted(order, key=lambda x: x[0])  # one timeline across the parts
    meta = yaml.safe_load((tmp_path / "all" / "metadata.yaml").read_text())
    assert meta["rosbag2_bagfile_information"]["message_count"] == 303 + late
    with open(next((tmp_path / "all").glob("*.mcap")), "rb") as f:
        channels = make_reader(f).get_summary().channels.values()
    assert all(c.metadata["topic_type_hash"].startswith("RIHS01_") for c in channels)


def test_merge_refuses_what_is_not_a_bag(tmp_path):
    (tmp_path / "junk").mkdir()
    (tmp_path / "junk" / "junk.mcap").write_bytes(b"not an mcap file")
    with pytest.raises(ReindexError, match="not an MCAP file"):
        merge([tmp_path / "junk"], tmp_path / "all")


def test_merge_takes_a_restarted_processs_dead_part_up_to_its_snapshot(tmp_path):
    # the dead process recorded steps 0..249 (killed: no summary), flushing its bag at the
    # snapshot of step 200; its successor resumed from that snapshot and recorded 201..299
    writer = JazzyWriter(tmp_path / "dead")
    writer.open()
    conn = writer.add_connection("/clock", CLOCK, typestore=typestore())
    for i in range(250):
        writer.write(conn, i * STEP_NS, _clock(i * STEP_NS))
        if i == 200:
            writer.flush()
    _die(writer)
    _clock_bag(tmp_path / "dead+", list(range(201, 300)))
    counts = merge([tmp_path / "dead", tmp_path / "dead+"], tmp_path / "all",
                   until={tmp_path / "dead": 200 * STEP_NS})
    assert counts == {"/clock": 300}
    assert _stamps(tmp_path / "all") == [i * STEP_NS for i in range(300)]  # each once


def test_reindex_refuses_a_bag_that_is_still_being_recorded(tmp_path):
    bag = tmp_path / "bag"
    child = subprocess.Popen([sys.executable, "-c", _WRITER, str(bag), "300"],
                             stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().startswith("written")
        before = (bag / "bag.mcap").read_bytes()
        assert recorder_alive(bag) == child.pid
        with pytest.raises(ReindexError, match=f"still being recorded .process {child.pid}"):
            reindex(bag)
        with pytest.raises(BagError, match="still being recorded"):  # not "reindex it"
            read_bag(bag)
        assert (bag / "bag.mcap").read_bytes() == before
        assert sorted(p.name for p in bag.iterdir()) == [LOCK_NAME, "bag.mcap"]
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    assert recorder_alive(bag) is None  # the kernel released the dead recorder's lock
    report = reindex(bag)
    assert report.whole and report.counts["/clock"] > 0
    assert not (bag / LOCK_NAME).exists()


def _chunks(data: bytes) -> list[tuple[int, int, list[int]]]:
    """(start, end, log times) of each chunk of a closed bag, read with the mcap library."""
    from io import BytesIO

    from mcap.data_stream import ReadDataStream
    from mcap.records import Chunk, Message
    from mcap.stream_reader import breakup_chunk

    out = []
    for index in make_reader(BytesIO(data)).get_summary().chunk_indexes:
        start, end = index.chunk_start_offset, index.chunk_start_offset + index.chunk_length
        chunk = Chunk.read(ReadDataStream(BytesIO(data[start + 9:end])))
        out.append((start, end, [r.log_time for r in breakup_chunk(chunk)
                                 if isinstance(r, Message)]))
    return out


def test_reindex_recovers_every_chunk_after_a_damaged_length_byte(tmp_path):
    _write_bag(tmp_path / "bag", 501)
    data = bytearray((tmp_path / "bag" / "bag.mcap").read_bytes())
    chunks = _chunks(bytes(data))
    start, _, lost = chunks[2]
    data[start + 3] ^= 0x40  # the third chunk's length: 2^22 bytes more
    (tmp_path / "bag" / "bag.mcap").write_bytes(data)

    report = reindex(tmp_path / "bag")

    assert report.damaged and report.damaged[0][0] == start and report.dropped_bytes == 0
    assert report.lost == len(lost) and not report.whole  # the summary listed them
    assert report.original.read_bytes() == data  # kept, unchanged
    assert (tmp_path / "bag" / "metadata.yaml.orig").exists()
    kept = set(_stamps(tmp_path / "bag"))
    expected = {t for s, _, times in chunks if s != start for t in times}
    assert expected <= kept and not kept & (set(lost) - expected)


def _damage(data: bytes, at: int, noise: bytes) -> bytes:
    return data[:at] + noise + data[at + len(noise):]


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(where=st.floats(0.0, 1.0), noise=st.binary(min_size=1, max_size=40),
       cut=st.one_of(st.none(), st.floats(0.3, 1.0)))
def test_reindex_fuzz_never_loses_an_intact_chunk_nor_touches_the_original(
        tmp_path_factory, where, noise, cut):
    """Damage anywhere in the data section of a closed bag, or after the first chunk of a
    killed one (cut short, no summary: its first chunk holds the channel definitions)."""
    root = tmp_path_factory.mktemp("fuzz")
    (root / "src").mkdir()
    _write_bag(root / "src" / "bag", 330)
    full = (root / "src" / "bag" / "bag.mcap").read_bytes()
    chunks = _chunks(full)
    end = len(full) if cut is None else max(chunks[0][1] + 1, int(cut * len(full)))
    first = 8 if cut is None else chunks[0][1]
    data_end = chunks[-1][1]
    at = first + int(where * (min(end, data_end) - first - 1))
    damaged = _damage(full, at, noise)[:end]
    (root / "bag").mkdir()
    (root / "bag" / "bag.mcap").write_bytes(damaged)
    if cut is None:
        (root / "bag" / "metadata.yaml").write_bytes(
            (root / "src" / "bag" / "metadata.yaml").read_bytes())
    report = reindex(root / "bag")

    touched = range(at, at + len(noise))
    intact = {t for s, e, times in chunks if e <= end
              and not (s < touched.stop and touched.start < e) for t in times}
    everything = {t for _, _, times in chunks for t in times}
    kept = set(_stamps(root / "bag"))
    assert intact & set(range(0, 330 * STEP_NS, STEP_NS)) <= kept <= everything
    if report.original is not None:
        assert report.original.read_bytes() == damaged
    else:
        assert (root / "bag" / "bag.mcap").read_bytes() == damaged


def test_reindex_exit_status_tells_a_cut_tail_from_damage_in_the_middle(tmp_path, capsys):
    from boat_dynamics.cli import main

    _write_bag(tmp_path / "bag", 300)
    assert main(["reindex", str(tmp_path / "bag")]) == 0
    assert "is whole: 330 messages" in capsys.readouterr().out
    data = (tmp_path / "bag" / "bag.mcap").read_bytes()
    (tmp_path / "bag" / "metadata.yaml").unlink()
    (tmp_path / "bag" / "bag.mcap").write_bytes(data[: len(data) * 2 // 3])  # killed
    assert main(["reindex", str(tmp_path / "bag")]) == 0
    out = capsys.readouterr().out
    assert "truncated:" in out and "bag.mcap.orig" in out
    start = _chunks(data)[1][0]
    damaged = bytearray(data)
    damaged[start + 40] ^= 0xFF  # inside the second chunk: its CRC no longer matches
    (tmp_path / "bag" / "bag.mcap").write_bytes(damaged)
    assert main(["reindex", str(tmp_path / "bag")]) == 1
    err = capsys.readouterr().err
    assert f"damaged in the middle (bytes {start}-" in err and "of the 330 messages" in err


_FULL_DISK = textwrap.dedent("""
    import resource, signal, sys
    from boat_dynamics.tools.recording import BagWriter
    from boat_msgs_py.typestore import typestore
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails: EFBIG
    resource.setrlimit(resource.RLIMIT_FSIZE, (48 * 1024, 48 * 1024))
    store = typestore()
    Clock, Time = store.types["rosgraph_msgs/msg/Clock"], store.types["builtin_interfaces/msg/Time"]
    bag = BagWriter(sys.argv[1])
    for i in range(3000):
        t = i * {step}
        data = store.serialize_cdr(Clock(Time(t // 10**9, t % 10**9)), "rosgraph_msgs/msg/Clock")
        bag.write("/clock", "rosgraph_msgs/msg/Clock", bytes(data), t)
    bag.close()
    print(bag.last_ns, bag.dropped)
    print(bag.stopped_line())
""").format(step=STEP_NS)


def test_a_full_disk_stops_the_recording_not_the_writer_and_keeps_what_was_whole(tmp_path):
    """A file-size limit (RLIMIT_FSIZE: EFBIG) stands in for a full disk (ENOSPC): both are
    an OSError from a write; before, it went up through the publisher and ended the run."""
    out = subprocess.run([sys.executable, "-c", _FULL_DISK, str(tmp_path / "bag")],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    last, dropped = (int(v) for v in out.stdout.split("\n")[0].split())
    assert 0 < last < 2999 * STEP_NS and dropped == 2999 - last // STEP_NS
    assert "recording stopped at bag time" in out.stdout and "File too large" in out.stdout
    assert (tmp_path / "bag" / "bag.mcap").stat().st_size <= 48 * 1024
    assert not (tmp_path / "bag" / LOCK_NAME).exists()
    report = reindex(tmp_path / "bag")  # the file is a killed recording's: every whole chunk
    stamps = _stamps(tmp_path / "bag")
    assert stamps == [i * STEP_NS for i in range(len(stamps))]
    assert last - stamps[-1] < 1_000_000_000 and report.dropped_bytes == 0


def test_a_chunk_declaring_a_huge_size_is_damage_not_an_allocation(tmp_path):
    """A compressed-chunk bomb: a zstd chunk whose uncompressed size says 1 TiB."""
    import tracemalloc

    from rosbags.rosbag2 import CompressionFormat, CompressionMode

    store = typestore()
    writer = Writer(tmp_path / "zstd", version=9, storage_plugin=StoragePlugin.MCAP)
    writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    with writer:
        conn = writer.add_connection("/clock", CLOCK, typestore=store)
        for i in range(40_000):  # rosbags closes a chunk at 1 MiB: 2 chunks
            writer.write(conn, i * STEP_NS, _clock(i * STEP_NS))
    path = tmp_path / "zstd" / "zstd.mcap"
    data = bytearray(path.read_bytes())
    chunks = _chunks(bytes(data))
    assert len(chunks) >= 2
    start = chunks[0][0]
    data[start + 25:start + 33] = (2**40).to_bytes(8, "little")  # uncompressed_size
    path.write_bytes(data)
    tracemalloc.start()
    try:
        report = reindex(tmp_path / "zstd")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert report.damaged and report.lost == len(chunks[0][2])
    assert peak < 200 * 2**20  # far below the 1 TiB it asked for
    assert set(_stamps(tmp_path / "zstd")) == {t for _, _, ts in chunks[1:] for t in ts}
