"""rosbag2 MCAP bags as rosbag2 Jazzy writes them, that survive a kill, and their recovery.

:class:`JazzyWriter` is rosbags' rosbag2 writer with four differences:

- a chunk is closed and handed to the operating system as soon as it spans
  :data:`CHUNK_SPAN_NS` (half a second) of bag time (or :meth:`JazzyWriter.flush_due` finds
  it that old), so a recording killed at any moment (SIGKILL, an OOM kill, a CI timeout)
  keeps every message up to at most one second before the kill; rosbags alone closes a chunk
  at 1 MiB only. Each chunk carries the CRC-32 of its records (rosbags writes 0, "none"), so
  a damaged chunk is told from an intact one.
- while it records, it holds a lock in the bag directory (:data:`LOCK_NAME`, ``flock``, with
  its pid), which the kernel releases however the recorder dies: :func:`recorder_alive`.
- each MCAP channel carries ``topic_type_hash`` beside ``offered_qos_profiles``, as
  rosbag2_storage_mcap does since Iron;
- ``ros_distro`` is ``jazzy`` (rosbags writes ``rosbags``), in metadata.yaml and in the
  MCAP's own copy of it.

A killed recording has no summary and no metadata.yaml, so no reader opens it.
:func:`reindex` (``boatsim reindex BAG``, as ``ros2 bag reindex``) reads every intact chunk
(:mod:`boat_dynamics.tools.mcapscan`, which steps over damage in the middle of a file) and
writes the bag again, summary and metadata.yaml included, keeping the original file
unchanged beside it; it refuses a bag whose recorder is alive. :func:`merge` joins the bags
that the processes of a sharded run wrote. It uses rosbags' MCAP writer internals (rosbags is
pinned in requirements/run.txt); tests/boat_dynamics/tools/test_bagfile.py checks the result
with rosbags and the mcap library.
"""

from __future__ import annotations

import fcntl
import io
import os
import shutil
import struct
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import ClassVar

from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.rosbag2.metadata import parse_qos
from rosbags.rosbag2.storage_mcap import Channel, McapWriter, write_channel, write_string
from rosbags.typesys import get_types_from_msg
from rosbags.typesys.store import Typestore

from boat_dynamics.tools.mcapscan import MCAP_MAGIC

__all__ = ["CHUNK_SPAN_NS", "LOCK_NAME", "ROS_DISTRO", "JazzyWriter", "ReindexError",
           "ReindexReport", "merge", "recorder_alive", "reindex"]

#: Longest span of bag time one MCAP chunk holds before it is written out, ns. Half the
#: promised second: a kill can fall between a message's publication and its write, so the
#: loss is one span plus a step (10.99 s kept of 12.0 s published with a 1 s span, measured).
CHUNK_SPAN_NS = 500_000_000
#: The lock a recording holds in its bag directory while it writes (``flock``; the kernel
#: releases it when the recorder dies, however it dies); it holds the recorder's pid.
LOCK_NAME = ".recording.lock"
#: The ROS distribution the bags say they come from.
ROS_DISTRO = "jazzy"
_ROSBAGS_DISTRO = "ros_distro: rosbags"
#: Where a chunk record's uncompressed CRC lies: opcode, length, start and end times, size.
_CRC_OFFSET = 1 + 8 + 8 + 8 + 8


class ReindexError(ValueError):
    """A directory that holds no MCAP file, or one that is not MCAP at all."""


class _CrashSafeMcap(McapWriter):
    """rosbags' MCAP storage, closing chunks by time and writing rosbag2 Jazzy's metadata."""

    def add_connection(self, connection, offered_qos_profiles: str) -> None:
        metadata = io.BytesIO()
        for key, value in (("offered_qos_profiles", offered_qos_profiles),
                           ("topic_type_hash", connection.digest)):
            write_string(metadata, key)
            write_string(metadata, value)
        self.channels.append(Channel(connection.id, connection.msgtype, connection.topic,
                                     connection.ext.serialization_format, metadata.getvalue()))
        self.channel_stats[connection.id] = 0
        write_channel(self.chunk.bio, self.channels[-1], self.schemas)

    def write(self, connection, timestamp: int, data: bytes | memoryview) -> None:
        self.flush_due(timestamp)
        super().write(connection, timestamp, data)

    def flush_due(self, now_ns: int) -> None:
        """Write the pending chunk out if its first message is CHUNK_SPAN_NS older than now."""
        if self.chunk.msgs and now_ns - self.chunk.message_start_time >= CHUNK_SPAN_NS:
            self.close_chunk()

    #: File offset where the last chunk handed to the operating system (and its indexes) end.
    whole_until = 0

    def close_chunk(self) -> None:
        start, crc = self.bio.tell(), zlib.crc32(self.chunk.bio.getvalue())
        super().close_chunk()
        end = self.bio.tell()  # rosbags writes a CRC of 0 ("not computed"): write it
        self.bio.seek(start + _CRC_OFFSET)
        self.bio.write(struct.pack("<I", crc))
        self.bio.seek(end)
        self.bio.flush()  # to the operating system: survives the process, not a power cut
        self.whole_until = end

    def abandon(self) -> None:
        """Stop writing after a failed write: cut the file after its last whole chunk.

        What the buffer still holds is dropped (flushing it failed); the file is then a killed
        recording's, which :func:`reindex` reads, and the cut frees what the partial chunk
        took on a full disk.
        """
        fd = self.bio.fileno()
        for action in (lambda: os.ftruncate(fd, self.whole_until), lambda: os.close(fd),
                       self.bio.close):  # close: its flush fails on the closed descriptor
            try:
                action()
            except (OSError, ValueError):
                pass

    def close(self, version: int, metadata: str) -> None:
        super().close(version, metadata.replace(_ROSBAGS_DISTRO, f"ros_distro: {ROS_DISTRO}"))


class JazzyWriter(Writer):
    """rosbags' :class:`~rosbags.rosbag2.Writer` for MCAP bags, crash-safe (module docstring).

    Args:
        path: directory to create; must not exist.
    """

    STORAGE_PLUGINS: ClassVar = MappingProxyType({StoragePlugin.MCAP: _CrashSafeMcap})

    def __init__(self, path: str | Path) -> None:
        super().__init__(path, version=9, storage_plugin=StoragePlugin.MCAP)
        self._lock: int | None = None

    def open(self) -> None:
        """Create the bag and take its recording lock (:data:`LOCK_NAME`, with our pid)."""
        super().open()
        self._lock = os.open(self.path / LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o644)
        fcntl.flock(self._lock, fcntl.LOCK_EX)
        os.write(self._lock, str(os.getpid()).encode())

    def flush_due(self, now_ns: int) -> None:
        """Write out the pending chunk if its first message is CHUNK_SPAN_NS older.

        Args:
            now_ns: the bag time now, ns. Call it when no message may come for a while.
        """
        if self.storage is not None:
            self.storage.flush_due(now_ns)

    def flush(self) -> None:
        """Write out the pending chunk now (its messages survive a kill from here on)."""
        if self.storage is not None and self.storage.chunk.msgs:
            self.storage.close_chunk()

    def abandon(self) -> None:
        """Stop after a failed write: the file up to its last whole chunk, the lock released.

        ``boatsim reindex`` makes the bag readable (:meth:`_CrashSafeMcap.abandon`).
        """
        if self.storage is not None:
            self.storage.abandon()
            self.storage = None
        self._release_lock()

    def _release_lock(self) -> None:
        """Remove the lock file and close it, which releases the flock."""
        if self._lock is not None:
            (self.path / LOCK_NAME).unlink(missing_ok=True)
            os.close(self._lock)
            self._lock = None

    def close(self) -> None:
        """Write the summary and metadata.yaml (``ros_distro: jazzy``)."""
        super().close()
        text = self.metapath.read_text()
        self.metapath.write_text(text.replace(_ROSBAGS_DISTRO, f"ros_distro: {ROS_DISTRO}"))
        self._release_lock()


def recorder_alive(bag: str | Path) -> int | None:
    """The pid of the live process recording ``bag``, or None when nothing records it.

    A lock left by a killed recorder is free (the kernel released it), so it reads as None.
    """
    lock = Path(bag) / LOCK_NAME
    try:
        fd = os.open(lock, os.O_RDONLY)
    except OSError:
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except BlockingIOError:
        text = os.read(fd, 32).decode(errors="replace").strip()
        return int(text) if text.isdigit() else -1
    finally:
        os.close(fd)
    return None


@dataclass
class ReindexReport:
    """What :func:`reindex` recovered.

    Attributes:
        counts: messages per topic in the rewritten bag (or in the whole bag left alone).
        dropped_bytes: bytes at the end of the file that held no intact record (the chunk
            being written when the recording was killed), 0 for a closed bag.
        end_ns: bag time of the last message kept, ns (0 when none).
        damaged: (start, end) byte ranges in the middle of the file that were stepped over;
            every intact chunk after them is kept.
        lost: messages a closed file's statistics list that could not be read; None when
            the file has no statistics (a killed recording).
        orphans: messages whose channel's definition was lost with a damaged chunk.
        original: where the original file now is (unchanged), None when nothing was written.
    """

    counts: dict[str, int] = field(default_factory=dict)
    dropped_bytes: int = 0
    end_ns: int = 0
    damaged: list[tuple[int, int]] = field(default_factory=list)
    lost: int | None = None
    orphans: int = 0
    original: Path | None = None

    @property
    def whole(self) -> bool:
        """Nothing was damaged or lost (a truncated tail may have been dropped)."""
        return not self.damaged and not self.orphans and not self.lost


def _write(found, target: Path, store: Typestore, report: ReindexReport) -> None:
    """Write the messages of a :func:`mcapscan.scan` to a new bag at ``target``."""
    writer = JazzyWriter(target)
    writer.open()
    conns: dict[int, object] = {}
    try:
        for message in found.messages:
            conn = conns.get(message.channel_id)
            if conn is None and message.channel_id in found.channels:
                sid, topic, encoding, meta = found.channels[message.channel_id]
                if sid in found.schemas:
                    conn = conns[message.channel_id] = _connection(
                        writer, topic, encoding, meta, found.schemas[sid], store)
            if conn is None:
                report.orphans += 1
                continue
            writer.write(conn, message.log_time, message.data)
            report.counts[conn.topic] = report.counts.get(conn.topic, 0) + 1
            report.end_ns = max(report.end_ns, message.log_time)
    finally:
        writer.close()
    kept = sum(report.counts.values())
    report.lost = None if found.listed is None else max(found.listed - kept, 0)


def _connection(writer: JazzyWriter, topic: str, encoding: str, meta: dict, schema,
                store: Typestore):
    """The writer's connection for an MCAP channel of a rosbag2 bag."""
    name, _, data = schema
    text = data.decode()
    digest = meta.get("topic_type_hash", "")
    if not digest:  # a bag from before the hash was written: compute it
        if name not in store.fielddefs:
            store.register(get_types_from_msg(text, name))
        digest = store.hash_rihs01(name)
    qos = meta.get("offered_qos_profiles", "")
    return writer.add_connection(topic, name, msgdef=text, rihs01=digest,
                                 serialization_format=encoding,
                                 offered_qos_profiles=parse_qos(qos) if qos else ())


def _listed_in_metadata(bag: Path) -> int | None:
    """metadata.yaml's message count, None without a readable one."""
    import yaml

    try:
        text = (bag / "metadata.yaml").read_text()
        if len(text) > 2**20:
            return None
        info = yaml.safe_load(text)["rosbag2_bagfile_information"]
        return int(info["message_count"])
    except (OSError, yaml.YAMLError, KeyError, TypeError, ValueError):
        return None


def _readable(bag: Path) -> int | None:
    """How many messages rosbags' reader reads from ``bag`` through its summary, or None."""
    from rosbags.rosbag2 import Reader

    try:
        with Reader(bag) as reader:
            return sum(1 for _ in reader.messages())
    except Exception:  # any failure to read means: not whole
        return None


def _free_name(path: Path) -> Path:
    """``path`` + ``.orig`` (``.orig.1``, ... when taken): where an original is kept."""
    candidate, n = path.with_name(path.name + ".orig"), 0
    while candidate.exists():
        n += 1
        candidate = path.with_name(f"{path.name}.orig.{n}")
    return candidate


def _bag_file(bag: Path) -> Path:
    """The one .mcap file of ``bag``, refusing what is not a bag or is being recorded."""
    files = sorted(bag.glob("*.mcap")) if bag.is_dir() else []
    if len(files) != 1:
        raise ReindexError(f"{bag}: not a bag directory with one .mcap file "
                           f"(found {len(files)})")
    pid = recorder_alive(bag)
    if pid is not None:
        raise ReindexError(f"{bag}: still being recorded (process {pid} holds "
                           f"{bag / LOCK_NAME}); reindex it after the recording ends")
    with files[0].open("rb") as f:
        if f.read(8) != MCAP_MAGIC:
            raise ReindexError(f"{files[0]}: not an MCAP file (it does not start with the "
                               "MCAP magic bytes)")
    return files[0]


def reindex(path: str | Path, keep_original: bool = True) -> ReindexReport:
    """Rebuild the MCAP summary and metadata.yaml of the bag directory ``path``.

    Every message of every intact chunk is kept, in file order, those after a damaged stretch
    included (:func:`boat_dynamics.tools.mcapscan.scan`); the incomplete tail of a killed
    recording is dropped. A whole, closed bag whose metadata.yaml lists every message is
    left alone. Otherwise the bag is written anew beside itself and swapped in with renames;
    the original file (and its metadata.yaml) is kept unchanged as ``NAME.orig`` unless
    ``keep_original`` is False, so a reindex never destroys anything.

    Raises:
        ReindexError: ``path`` is not a directory with exactly one .mcap file, the file does
            not start as an MCAP file, or a live process is still recording it.
    """
    from boat_dynamics.tools import mcapscan
    from boat_msgs_py.typestore import new_typestore

    bag = Path(path)
    source = _bag_file(bag)
    found = mcapscan.scan(source)
    report = ReindexReport(dropped_bytes=found.tail, damaged=found.damaged)
    if (found.closed and found.tail == 0 and not found.damaged
            and _listed_in_metadata(bag) == len(found.messages) == found.listed
            and _readable(bag) == found.listed):
        for m in found.messages:
            topic = found.channels.get(m.channel_id, (0, "?"))[1]
            report.counts[topic] = report.counts.get(topic, 0) + 1
            report.end_ns = max(report.end_ns, m.log_time)
        report.lost = 0
        return report
    work = bag.parent / f".{bag.name}.reindex"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir()
    try:
        _write(found, work / source.stem, new_typestore(), report)
        if keep_original:
            report.original = _free_name(source)
            os.rename(source, report.original)
            if (bag / "metadata.yaml").exists():
                os.rename(bag / "metadata.yaml", _free_name(bag / "metadata.yaml"))
        os.replace(work / source.stem / source.name, source)
        os.replace(work / source.stem / "metadata.yaml", bag / "metadata.yaml")
        (bag / LOCK_NAME).unlink(missing_ok=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return report


def merge(parts: list[str | Path], target: str | Path,
          until: dict[Path, int] | None = None) -> dict[str, int]:
    """Write every message of the bags ``parts`` into one new bag ``target``, in time order.

    The processes of a ``run --fast`` over several processes each record what they publish
    (and the clock owner what the others publish) to a bag of their own; this joins them.
    A part whose writer was killed is reindexed first (:func:`reindex`). Messages of equal
    time keep the order of ``parts``.

    Args:
        parts: bag directories, each with one .mcap file.
        target: the bag directory to create; must not exist.
        until: parts taken only up to a time (ns, inclusive): a killed process's, whose
            successor resumed from a snapshot of that time and recorded the rest.

    Returns:
        Messages per topic in ``target``.

    Raises:
        ReindexError: a part is not a bag.
    """
    import heapq

    from mcap.reader import make_reader

    from boat_msgs_py.typestore import new_typestore

    store = new_typestore()
    writer = JazzyWriter(target)
    writer.open()
    counts: dict[str, int] = {}
    conns: dict[str, object] = {}
    files = []
    try:
        streams = []
        for order, part in enumerate(Path(p) for p in parts):
            if not (part / "metadata.yaml").exists():
                reindex(part)
            files.append(next(part.glob("*.mcap")).open("rb"))
            messages = make_reader(files[-1]).iter_messages(
                log_time_order=True, ending_at=(until or {}).get(part))
            streams.append(((m.log_time, order, schema, channel, m)
                            for schema, channel, m in messages))
        for _, _, schema, channel, message in heapq.merge(*streams, key=lambda x: x[:2]):
            conn = conns.get(channel.topic)
            if conn is None:
                conn = conns[channel.topic] = _connection(
                    writer, channel.topic, channel.message_encoding, channel.metadata,
                    (schema.name, schema.encoding, schema.data), store)
            writer.write(conn, message.log_time, message.data)
            counts[channel.topic] = counts.get(channel.topic, 0) + 1
    finally:
        for f in files:
            f.close()
        writer.close()
    return counts
