"""rosbag2 MCAP bags as rosbag2 Jazzy writes them, that survive a kill, and their recovery.

:class:`JazzyWriter` is rosbags' rosbag2 writer with three differences:

- a chunk is closed and handed to the operating system as soon as it spans
  :data:`CHUNK_SPAN_NS` (half a second) of bag time (or :meth:`JazzyWriter.flush_due` finds
  it that old), so a recording killed at any moment (SIGKILL, an OOM kill, a CI timeout)
  keeps every message up to at most one second before the kill; rosbags alone closes a chunk
  at 1 MiB only.
- each MCAP channel carries ``topic_type_hash`` beside ``offered_qos_profiles``, as
  rosbag2_storage_mcap does since Iron;
- ``ros_distro`` is ``jazzy`` (rosbags writes ``rosbags``), in metadata.yaml and in the
  MCAP's own copy of it.

A killed recording has no summary and no metadata.yaml, so no reader opens it.
:func:`reindex` (``boatsim reindex BAG``, as ``ros2 bag reindex``) reads every complete chunk
with the mcap library's stream reader and writes the bag again, summary and metadata.yaml
included. :func:`merge` joins the bags that the processes of a sharded run wrote. It uses
rosbags' MCAP writer internals (rosbags is pinned in requirements/run.txt);
tests/boat_dynamics/tools/test_bagfile.py checks the result with rosbags and the mcap library.
"""

from __future__ import annotations

import io
import os
import shutil
import struct
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import ClassVar

from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.rosbag2.metadata import parse_qos
from rosbags.rosbag2.storage_mcap import Channel, McapWriter, write_channel, write_string
from rosbags.typesys import get_types_from_msg
from rosbags.typesys.store import Typestore

__all__ = ["CHUNK_SPAN_NS", "ROS_DISTRO", "JazzyWriter", "ReindexError", "ReindexReport",
           "merge", "reindex"]

#: Longest span of bag time one MCAP chunk holds before it is written out, ns. Half the
#: promised second: a kill can fall between a message's publication and its write, so the
#: loss is one span plus a step (10.99 s kept of 12.0 s published with a 1 s span, measured).
CHUNK_SPAN_NS = 500_000_000
#: The ROS distribution the bags say they come from.
ROS_DISTRO = "jazzy"
_ROSBAGS_DISTRO = "ros_distro: rosbags"
#: The first 8 bytes of every MCAP file.
MCAP_MAGIC = b"\x89MCAP0\r\n"


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

    def close_chunk(self) -> None:
        super().close_chunk()
        self.bio.flush()  # to the operating system: survives the process, not a power cut

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

    def close(self) -> None:
        """Write the summary and metadata.yaml (``ros_distro: jazzy``)."""
        super().close()
        text = self.metapath.read_text()
        self.metapath.write_text(text.replace(_ROSBAGS_DISTRO, f"ros_distro: {ROS_DISTRO}"))


@dataclass
class ReindexReport:
    """What :func:`reindex` recovered.

    Attributes:
        counts: messages per topic in the rewritten bag.
        dropped_bytes: bytes at the end of the file that were not a complete record (the
            chunk being written when the recording was killed), 0 for a closed bag.
        end_ns: bag time of the last message kept, ns (0 when none).
    """

    counts: dict[str, int] = field(default_factory=dict)
    dropped_bytes: int = 0
    end_ns: int = 0


def _complete_length(f: io.BufferedReader, size: int) -> int:
    """Length of ``f``'s prefix that a killed writer left whole.

    Args:
        f: an MCAP file, open for reading.
        size: its length, bytes.

    Returns:
        Bytes up to the end of its last complete top-level record.
    """
    pos = 8  # magic
    while pos + 9 <= size:
        f.seek(pos)
        head = f.read(9)
        length = int.from_bytes(head[1:], "little")
        if pos + 9 + length > size:
            break
        pos += 9 + length
    f.seek(pos)
    if pos + 8 == size and f.read(8) == MCAP_MAGIC:  # a closed file ends with the magic
        return size
    return min(pos, size)


def _rewrite(source: Path, target: Path, store: Typestore) -> ReindexReport:
    """Write every message of ``source``'s complete records to a new bag at ``target``."""
    from mcap.exceptions import McapError
    from mcap.records import Channel as McapChannel
    from mcap.records import Message, Schema
    from mcap.stream_reader import StreamReader

    report = ReindexReport()
    writer = JazzyWriter(target)
    writer.open()
    schemas: dict[int, Schema] = {}
    conns: dict[int, object] = {}
    with source.open("rb") as f:
        size = source.stat().st_size
        kept = _complete_length(f, size)
        report.dropped_bytes = size - kept
        f.seek(0)
        reader = StreamReader(f, skip_magic=False, emit_chunks=False)
        try:
            for record in reader.records:
                if isinstance(record, Schema):
                    schemas.setdefault(record.id, record)
                elif isinstance(record, McapChannel) and record.id not in conns:
                    conns[record.id] = _connection(writer, record, schemas[record.schema_id],
                                                   store)
                elif isinstance(record, Message) and record.channel_id in conns:
                    conn = conns[record.channel_id]
                    writer.write(conn, record.log_time, record.data)
                    report.counts[conn.topic] = report.counts.get(conn.topic, 0) + 1
                    report.end_ns = max(report.end_ns, record.log_time)
        except (McapError, EOFError, struct.error):
            pass  # the end of the complete records: a killed writer wrote no footer
    writer.close()
    return report


def _connection(writer: JazzyWriter, channel, schema, store: Typestore):
    """The writer's connection for an MCAP channel of a rosbag2 bag."""
    text = schema.data.decode()
    digest = channel.metadata.get("topic_type_hash", "")
    if not digest:  # a bag from before the hash was written: compute it
        if schema.name not in store.fielddefs:
            store.register(get_types_from_msg(text, schema.name))
        digest = store.hash_rihs01(schema.name)
    qos = channel.metadata.get("offered_qos_profiles", "")
    return writer.add_connection(channel.topic, schema.name, msgdef=text, rihs01=digest,
                                 serialization_format=channel.message_encoding,
                                 offered_qos_profiles=parse_qos(qos) if qos else ())


def reindex(path: str | Path) -> ReindexReport:
    """Rebuild the MCAP summary and metadata.yaml of the bag directory ``path``.

    Every message of every complete chunk is kept, in file order; the incomplete tail of a
    killed recording is dropped. The bag is written again beside itself and swapped in with
    atomic renames, so an interrupted reindex leaves the original in place.

    Raises:
        ReindexError: ``path`` is not a directory with exactly one .mcap file, or the file
            does not start as an MCAP file.
    """
    from boat_msgs_py.typestore import new_typestore

    bag = Path(path)
    files = sorted(bag.glob("*.mcap")) if bag.is_dir() else []
    if len(files) != 1:
        raise ReindexError(f"{bag}: not a bag directory with one .mcap file "
                           f"(found {len(files)})")
    source = files[0]
    with source.open("rb") as f:
        if f.read(8) != MCAP_MAGIC:
            raise ReindexError(f"{source}: not an MCAP file (it does not start with the "
                               "MCAP magic bytes)")
    work = bag.parent / f".{bag.name}.reindex"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir()
    try:
        report = _rewrite(source, work / source.stem, new_typestore())
        os.replace(work / source.stem / source.name, source)
        os.replace(work / source.stem / "metadata.yaml", bag / "metadata.yaml")
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
                conn = conns[channel.topic] = _connection(writer, channel, schema, store)
            writer.write(conn, message.log_time, message.data)
            counts[channel.topic] = counts.get(channel.topic, 0) + 1
    finally:
        for f in files:
            f.close()
        writer.close()
    return counts
