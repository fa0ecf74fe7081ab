"""Walk an MCAP file record by record, step over damage, and say what was damaged where.

:func:`scan` reads the top-level records of an MCAP file (MCAP specification,
https://mcap.dev/spec) from its start. A record that does not parse (an unknown opcode, a
length that runs past the end or does not match its fields, a chunk whose records do not add
up, whose CRC does not match or that would decompress to more than :data:`MAX_CHUNK_BYTES`) is
damage: the scan looks again from the end of the last whole chunk (a damaged length may have
sent it past a good chunk) for the next byte where a whole chunk parses and goes on from
there, so every intact chunk after a damaged one is read. Damage followed by no intact chunk is the
file's *tail*: the record a killed writer was writing when it died (a truncation) or a damaged
end. The summary section of a closed file (found from its footer) is read first for the
schemas and channels, so a chunk that held a channel's definition can be lost without losing
the channel's messages in later chunks.

Nothing here writes; :func:`boat_dynamics.tools.bagfile.reindex` writes the new bag.
"""

from __future__ import annotations

import mmap
import struct
import zlib
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["MAX_CHUNK_BYTES", "MCAP_MAGIC", "Scan", "ScannedMessage", "scan"]

#: The first and last 8 bytes of an MCAP file.
MCAP_MAGIC = b"\x89MCAP0\r\n"
#: Largest uncompressed chunk read, bytes; a chunk that declares more is damage (a
#: decompression bomb must not allocate it). boatsim's writer closes a chunk every half
#: second or at 1 MiB; rosbag2 writes 768 KiB chunks by default.
MAX_CHUNK_BYTES = 256 * 2**20

_CHUNK, _FOOTER, _STATISTICS = 0x06, 0x02, 0x0B
_SCHEMA, _CHANNEL, _MESSAGE = 0x03, 0x04, 0x05
_KNOWN = frozenset(range(0x01, 0x10))
_IN_CHUNK = frozenset((_SCHEMA, _CHANNEL, _MESSAGE))
_CHUNK_FIXED = 8 + 8 + 8 + 4 + 4 + 8  # times, size, crc, compression length, records length


class _Damaged(ValueError):
    """A record that does not parse."""


@dataclass(frozen=True)
class ScannedMessage:
    """One message record: channel id, log time (ns) and its serialized data."""

    channel_id: int
    log_time: int
    data: bytes


@dataclass
class Scan:
    """What :func:`scan` found.

    Attributes:
        schemas: schema id -> (name, encoding, data).
        channels: channel id -> (schema id, topic, message encoding, metadata).
        messages: every message of every intact chunk (and top-level message), in file order.
        damaged: (start, end) byte ranges stepped over, each followed by an intact chunk.
        tail: bytes at the end that held no intact record (0 for a whole, closed file).
        closed: the file ends with a footer and the magic bytes.
        listed: the message count of a closed file's statistics record, None without one.
    """

    schemas: dict[int, tuple[str, str, bytes]] = field(default_factory=dict)
    channels: dict[int, tuple[int, str, str, dict[str, str]]] = field(default_factory=dict)
    messages: list[ScannedMessage] = field(default_factory=list)
    damaged: list[tuple[int, int]] = field(default_factory=list)
    tail: int = 0
    closed: bool = False
    listed: int | None = None


def _string(buf: bytes, pos: int) -> tuple[str, int]:
    (n,) = struct.unpack_from("<I", buf, pos)
    if pos + 4 + n > len(buf):
        raise _Damaged("string past its record")
    return bytes(buf[pos + 4: pos + 4 + n]).decode(), pos + 4 + n


def _inner(opcode: int, body: bytes, found: Scan, messages: list) -> None:
    """Parse one schema, channel or message record's body into ``found`` / ``messages``."""
    if opcode == _MESSAGE:
        if len(body) < 22:
            raise _Damaged("short message")
        channel, _, log_time = struct.unpack_from("<HIQ", body, 0)
        messages.append(ScannedMessage(channel, log_time, bytes(body[22:])))
    elif opcode == _SCHEMA:
        (sid,) = struct.unpack_from("<H", body, 0)
        name, pos = _string(body, 2)
        encoding, pos = _string(body, pos)
        (n,) = struct.unpack_from("<I", body, pos)
        if pos + 4 + n != len(body):
            raise _Damaged("schema length")
        found.schemas.setdefault(sid, (name, encoding, bytes(body[pos + 4:])))
    elif opcode == _CHANNEL:
        cid, sid = struct.unpack_from("<HH", body, 0)
        topic, pos = _string(body, 4)
        encoding, pos = _string(body, pos)
        (n,) = struct.unpack_from("<I", body, pos)
        pos, end, meta = pos + 4, pos + 4 + n, {}
        while pos < end:
            key, pos = _string(body, pos)
            meta[key], pos = _string(body, pos)
        if pos != len(body):
            raise _Damaged("channel length")
        found.channels.setdefault(cid, (sid, topic, encoding, meta))


def _decompress(compression: str, data: bytes, size: int) -> bytes:
    if size > MAX_CHUNK_BYTES:
        raise _Damaged(f"chunk of {size} bytes")
    if compression == "":
        return data
    if compression == "zstd":
        import zstandard

        return zstandard.ZstdDecompressor().decompress(data, max_output_size=size)
    if compression == "lz4":
        import lz4.frame

        out = lz4.frame.LZ4FrameDecompressor().decompress(data, max_length=size)
        return out
    raise _Damaged(f"compression {compression!r}")


def _chunk(body: bytes, found: Scan) -> list[ScannedMessage]:
    """The messages of one chunk record's body; its schemas and channels go to ``found``."""
    if len(body) < _CHUNK_FIXED:
        raise _Damaged("short chunk")
    _, _, size, crc = struct.unpack_from("<QQQI", body, 0)
    compression, pos = _string(body, 28)
    (n,) = struct.unpack_from("<Q", body, pos)
    if pos + 8 + n != len(body):
        raise _Damaged("chunk length")
    try:
        records = _decompress(compression, bytes(body[pos + 8:]), size)
    except (ImportError, RuntimeError, ValueError) as exc:  # zstd/lz4 errors are these
        raise _Damaged(str(exc)) from exc
    if len(records) != size or (crc and zlib.crc32(records) != crc):
        raise _Damaged("chunk size or CRC")
    staged, messages, pos = Scan(), [], 0
    while pos < size:
        if pos + 9 > size:
            raise _Damaged("record header past the chunk")
        opcode, length = struct.unpack_from("<BQ", records, pos)
        if opcode not in _IN_CHUNK or pos + 9 + length > size:
            raise _Damaged("record in chunk")
        _inner(opcode, memoryview(records)[pos + 9: pos + 9 + length], staged, messages)
        pos += 9 + length
    found.schemas = {**staged.schemas, **found.schemas}
    found.channels = {**staged.channels, **found.channels}
    return messages


def _record(buf, pos: int, found: Scan) -> tuple[int, int]:
    """Parse the top-level record at ``pos``: (opcode, end offset). Raises _Damaged."""
    if pos + 9 > len(buf):
        raise _Damaged("header past the end")
    opcode, length = struct.unpack_from("<BQ", buf, pos)
    end = pos + 9 + length
    if opcode not in _KNOWN or end > len(buf):
        raise _Damaged("opcode or length")
    body = memoryview(buf)[pos + 9: end]
    try:
        if opcode == _CHUNK:
            found.messages.extend(_chunk(body, found))
        elif opcode in _IN_CHUNK:
            _inner(opcode, body, found, found.messages)
        elif opcode == _FOOTER and length != 20:
            raise _Damaged("footer length")
        elif opcode == _STATISTICS and length >= 8:
            (found.listed,) = struct.unpack_from("<Q", body, 0)
    except (struct.error, UnicodeDecodeError) as exc:
        raise _Damaged(str(exc)) from exc
    return opcode, end


def _resync(buf, start: int, found: Scan) -> int | None:
    """The first offset >= start where a whole chunk parses, or None."""
    pos = buf.find(bytes([_CHUNK]), start)
    while pos >= 0:
        try:
            if _record(buf, pos, found)[0] == _CHUNK:
                return pos
        except _Damaged:
            pass
        pos = buf.find(bytes([_CHUNK]), pos + 1)
    return None


def _summary(buf, found: Scan) -> bool:
    """Read a closed file's summary records (schemas, channels); True if the footer is whole."""
    footer = len(buf) - 8 - 29
    if footer < 8 or bytes(buf[-8:]) != MCAP_MAGIC:
        return False
    opcode, length, start = struct.unpack_from("<BQQ", buf, footer)
    if opcode != _FOOTER or length != 20 or not (start == 0 or 8 <= start <= footer):
        return False
    pos = start or footer
    while pos < footer:
        try:
            pos = _record(buf, pos, found)[1]
        except _Damaged:
            break
    return True


def scan(path: str | Path) -> Scan:
    """Every message, schema and channel an MCAP file still holds, and where it is damaged.

    Args:
        path: an MCAP file that starts with the magic bytes.

    Raises:
        ValueError: the file does not start with the MCAP magic bytes.
    """
    found = Scan()
    with open(path, "rb") as f:
        if f.read(8) != MCAP_MAGIC:
            raise ValueError(f"{path}: not an MCAP file (it does not start with the MCAP "
                             "magic bytes)")
        if Path(path).stat().st_size <= 8:
            return found
        with mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as buf:
            found.closed = _summary(buf, found)
            pos = verified = 8  # verified: the end of the last whole chunk
            while pos < len(buf):
                try:
                    opcode, end = _record(buf, pos, found)
                except _Damaged:  # here, or a length before it (back to the last chunk)
                    after = _resync(buf, verified, Scan(listed=found.listed))
                    if after is None:
                        found.tail = len(buf) - pos
                        break
                    found.damaged.append((pos if after > pos else verified, after))
                    pos = verified = after
                    continue
                if opcode == _FOOTER:
                    found.tail = 0 if end + 8 == len(buf) else len(buf) - end
                    break
                verified = end if opcode == _CHUNK else verified
                pos = end
    return found
