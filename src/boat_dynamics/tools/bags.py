"""Reading and comparing rosbag2 bags (any storage rosbags reads), without ROS.

:func:`compare_bags` is the regression check behind ``boatsim compare`` and is usable from
pytest as a plain function: it aligns two bags topic by topic on the messages' header stamps
(the bag's receive time when a message has no header) and reports, per field, the largest
difference and where it happened.
"""

from __future__ import annotations

import fnmatch
import math
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from boat_msgs_py import names

__all__ = [
    "BagError",
    "Comparison",
    "FieldDifference",
    "TopicComparison",
    "compare_bags",
    "flatten",
    "read_bag",
    "read_bag_topics",
]

#: Absolute tolerance of fields no --tol pattern matches.
DEFAULT_TOLERANCE = 1e-9

#: Topics left out of a comparison unless asked for: logs and parameter events carry wall
#: time and process ids, never equal between two runs; lockstep grants are protocol.
UNCOMPARED_TOPICS = (names.ROSOUT, names.PARAMETER_EVENTS, names.LOCKSTEP)


class BagError(ValueError):
    """A bag that cannot be read (missing, corrupt), or a topic that is not in it."""


def _one_line(exc: Exception) -> str:
    """An exception's text on one line (rosbags and YAML errors span several)."""
    return " ".join(str(exc).split()) or type(exc).__name__


def _stamp(msg: object, fallback: int) -> int:
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    if stamp is None:
        stamp = getattr(msg, "clock", None)  # rosgraph_msgs/Clock
    if stamp is None or not hasattr(stamp, "sec"):
        return fallback
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


@contextmanager
def _open_bag(path: str | Path) -> Iterator[tuple[Path, object]]:
    """(path, rosbags AnyReader) of a bag; every failure to read it becomes a BagError."""
    from rosbags.highlevel import AnyReader

    p = Path(path)
    if not p.exists():
        raise BagError(f"{p}: no such bag")
    try:
        with AnyReader([p]) as reader:
            yield p, reader
    except BagError:
        raise
    except Exception as exc:  # rosbags raises ReaderError, OSError, ...
        hint = ""
        if p.is_dir() and any(p.glob("*.mcap")):
            hint = (f"; if its recording was killed, `boatsim reindex {p}` makes it readable "
                    "(it loses at most the last second)")
        raise BagError(f"{p}: not a readable rosbag2 bag ({_one_line(exc)}){hint}") from exc


def read_bag(path: str | Path, topics: Iterable[str] | None = None
             ) -> dict[str, list[tuple[int, object]]]:
    """Messages of a bag per topic, as (stamp ns, deserialized message), in bag order.

    Raises:
        BagError: the bag is missing or unreadable, or a requested topic is not in it.
    """
    with _open_bag(path) as (p, reader):
        available = {c.topic for c in reader.connections}
        wanted = set(available if topics is None else topics)
        missing = sorted(wanted - available)
        if missing:
            raise BagError(f"{p}: topic(s) not in the bag: {', '.join(missing)} "
                           f"(it has: {', '.join(sorted(available))})")
        out: dict[str, list[tuple[int, object]]] = {t: [] for t in sorted(wanted)}
        conns = [c for c in reader.connections if c.topic in wanted]
        for conn, t_ns, raw in reader.messages(connections=conns):
            try:
                msg = reader.deserialize(raw, conn.msgtype)
            except Exception as exc:  # rosbags raises several types
                raise BagError(f"{p}: cannot decode {conn.topic} [{conn.msgtype}]: "
                               f"{_one_line(exc)}") from exc
            out[conn.topic].append((_stamp(msg, t_ns), msg))
        return out


def read_bag_topics(path: str | Path) -> list[str]:
    """The topics of a bag.

    Raises:
        BagError: the bag is missing or unreadable.
    """
    with _open_bag(path) as (_, reader):
        return sorted({c.topic for c in reader.connections})


def flatten(msg: object, prefix: str = "") -> dict[str, float | str]:
    """Leaf fields of a message as {"pose.pose.position.x": value}; arrays as "data[3]".

    Numbers become floats, strings stay strings; the header is left out (it is the key the
    messages are aligned on).
    """
    out: dict[str, float | str] = {}
    names = getattr(msg, "__dataclass_fields__", None)
    if names is None:
        if isinstance(msg, (bool, int, float, np.integer, np.floating)):
            out[prefix] = float(msg)
        elif isinstance(msg, str):
            out[prefix] = msg
        elif isinstance(msg, (bytes, bytearray)):
            out[prefix] = msg.hex()
        elif isinstance(msg, np.ndarray):
            for i, v in enumerate(msg.ravel().tolist()):
                out[f"{prefix}[{i}]"] = float(v)
        elif isinstance(msg, (list, tuple)):
            for i, v in enumerate(msg):
                out.update(flatten(v, f"{prefix}[{i}]"))
        return out
    for name in names:
        if name == "header" or name.startswith("__") or name.isupper():  # ROS constants
            continue
        out.update(flatten(getattr(msg, name), f"{prefix}.{name}" if prefix else name))
    return out


@dataclass(frozen=True)
class FieldDifference:
    """The largest difference of one field between the two bags.

    Attributes:
        field: field path, e.g. ``pose.pose.position.x``.
        max_abs: largest |a - b| (inf when a string or the set of fields differs).
        stamp_ns: stamp of the message where it happened.
        tolerance: the tolerance that applies.
    """

    field: str
    max_abs: float
    stamp_ns: int
    tolerance: float

    @property
    def ok(self) -> bool:
        """Within tolerance."""
        return self.max_abs <= self.tolerance


@dataclass(frozen=True)
class TopicComparison:
    """One topic's comparison.

    Attributes:
        topic: the topic.
        matched: messages aligned (same stamp in both bags).
        only_a: stamps present in A only.
        only_b: stamps present in B only.
        fields: per-field differences, worst first.
    """

    topic: str
    matched: int
    only_a: int
    only_b: int
    fields: list[FieldDifference] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """Same messages, every field within tolerance."""
        return self.only_a == 0 and self.only_b == 0 and all(f.ok for f in self.fields)


@dataclass(frozen=True)
class Comparison:
    """The result of :func:`compare_bags`."""

    topics: list[TopicComparison]

    @property
    def ok(self) -> bool:
        """Every topic within tolerance."""
        return all(t.ok for t in self.topics)

    def report(self, limit: int = 5) -> str:
        """Human-readable lines: per topic, the worst fields and where they happened."""
        lines = []
        for t in self.topics:
            state = "ok" if t.ok else "DIFFERENT"
            lines.append(f"{t.topic}: {state}: {t.matched} messages matched"
                         + (f", {t.only_a} only in A" if t.only_a else "")
                         + (f", {t.only_b} only in B" if t.only_b else ""))
            shown = [f for f in t.fields if not f.ok][:limit] or t.fields[:1]
            for f in shown:
                lines.append(f"  {f.field}: max |a - b| = {f.max_abs:.6g} at t = "
                             f"{f.stamp_ns / 1e9:.3f} s (tolerance {f.tolerance:g})"
                             + ("" if f.ok else "  <-- outside"))
        return "\n".join(lines)


def _tolerance(path: str, topic: str, tolerances: Mapping[str, float]) -> float:
    best = DEFAULT_TOLERANCE
    for pattern, tol in tolerances.items():
        if fnmatch.fnmatchcase(path, pattern) or fnmatch.fnmatchcase(f"{topic}:{path}",
                                                                     pattern):
            best = tol
    return best


def compare_bags(a: str | Path, b: str | Path, topics: Iterable[str] | None = None,
                 tolerances: Mapping[str, float] | None = None) -> Comparison:
    """Compare two bags topic by topic, aligned on message stamps.

    Args:
        a: the reference bag.
        b: the bag to check.
        topics: topics to compare (default: every topic of A but :data:`UNCOMPARED_TOPICS`).
        tolerances: {pattern: absolute tolerance}; a pattern (fnmatch) matches the field path
            (``*.position.*``) or ``topic:field`` (``/odom:twist.*``); the last match wins;
            other fields get :data:`DEFAULT_TOLERANCE`.

    Raises:
        BagError: unreadable bag, or a topic missing from either bag.
    """
    tolerances = dict(tolerances or {})
    if topics is None:
        topics = [t for t in read_bag_topics(a) if t not in UNCOMPARED_TOPICS]
    bag_a = read_bag(a, topics)
    bag_b = read_bag(b, bag_a.keys())
    results = []
    for topic, msgs_a in bag_a.items():
        by_stamp_b = {}
        for stamp, msg in bag_b[topic]:
            by_stamp_b.setdefault(stamp, msg)
        stamps_a = {stamp for stamp, _ in msgs_a}
        only_b = len(set(by_stamp_b) - stamps_a)
        worst: dict[str, tuple[float, int]] = {}
        matched = only_a = 0
        seen = set()
        for stamp, msg in msgs_a:
            if stamp in seen:
                continue
            seen.add(stamp)
            other = by_stamp_b.get(stamp)
            if other is None:
                only_a += 1
                continue
            matched += 1
            fa, fb = flatten(msg), flatten(other)
            for key in fa.keys() | fb.keys():
                va, vb = fa.get(key), fb.get(key)
                if isinstance(va, float) and isinstance(vb, float):
                    both_nan = math.isnan(va) and math.isnan(vb)
                    diff = 0.0 if va == vb or both_nan else abs(va - vb)
                    if math.isnan(diff):  # a NaN on one side only
                        diff = math.inf
                else:
                    diff = 0.0 if va == vb else math.inf
                if key not in worst or diff > worst[key][0]:
                    worst[key] = (diff, stamp)
        fields = sorted(
            (FieldDifference(k, d, s, _tolerance(k, topic, tolerances))
             for k, (d, s) in worst.items()),
            key=lambda f: (f.ok, -f.max_abs / max(f.tolerance, 1e-300), f.field))
        results.append(TopicComparison(topic, matched, only_a, only_b, fields))
    return Comparison(results)
