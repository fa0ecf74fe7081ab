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
    "DEFAULT_MAX_FIELDS",
    "ODOMETRY_TYPE",
    "BagError",
    "Comparison",
    "FieldDifference",
    "TopicComparison",
    "compare_bags",
    "flatten",
    "odometry_topics",
    "read_bag",
    "read_bag_topics",
    "read_bag_types",
]

#: Absolute tolerance of fields no --tol pattern matches.
DEFAULT_TOLERANCE = 1e-9

#: Topics left out of a comparison unless asked for: logs and parameter events carry wall
#: time and process ids, never equal between two runs; lockstep grants and a lockstep node's
#: word to the replayer are protocol.
UNCOMPARED_TOPICS = (names.ROSOUT, names.PARAMETER_EVENTS, names.LOCKSTEP,
                     names.LOCKSTEP_READY)


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
        from boat_dynamics.tools.bagfile import recorder_alive

        hint, pid = "", recorder_alive(p) if p.is_dir() else None
        if pid is not None:
            hint = f"; it is still being recorded (process {pid}): read it when that ends"
        elif p.is_dir() and any(p.glob("*.mcap")):
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
    return sorted(read_bag_types(path))


def read_bag_types(path: str | Path) -> dict[str, str]:
    """Each topic of a bag and its message type (``nav_msgs/msg/Odometry``).

    Raises:
        BagError: the bag is missing or unreadable.
    """
    with _open_bag(path) as (_, reader):
        return {c.topic: c.msgtype for c in reader.connections}


#: The type of a boat's odometry, which plot and view draw.
ODOMETRY_TYPE = "nav_msgs/msg/Odometry"


def odometry_topics(path: str | Path) -> dict[str, str]:
    """A bag's boats: ``*/odom`` topic -> boat name, those of type nav_msgs/msg/Odometry.

    Raises:
        BagError: the bag is unreadable, or has no such topic (naming any ``*/odom`` of
            another type).
    """
    types = read_bag_types(path)
    named = {t: b for t in types if (b := names.boat_of(t, names.ODOM)) is not None}
    boats = {t: b for t, b in named.items() if types[t] == ODOMETRY_TYPE}
    if not boats:
        wrong = "; ".join(f"{t} is {types[t]}" for t in sorted(named))
        raise BagError(f"{path}: no */odom topic of type {ODOMETRY_TYPE}"
                       + (f" ({wrong})" if wrong else f" (it has: {', '.join(sorted(types))})"))
    return boats


#: numpy dtypes of sensor_msgs/PointField datatypes (1 INT8 .. 8 FLOAT64).
_POINT_TYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


def _cloud_points(msg: object, prefix: str) -> dict[str, np.ndarray]:
    """A PointCloud2's points by field: {"points.x": (N,) float64, ...} (N = width x height).

    Raises:
        BagError: a field type or layout the message's own description does not allow.
    """
    order = ">" if msg.is_bigendian else "<"
    try:
        dtype = np.dtype({"names": [f.name for f in msg.fields],
                          "formats": [(order + _POINT_TYPES[f.datatype], (f.count,))
                                      if f.count > 1 else order + _POINT_TYPES[f.datatype]
                                      for f in msg.fields],
                          "offsets": [f.offset for f in msg.fields],
                          "itemsize": msg.point_step})
        raw = np.asarray(msg.data, dtype=np.uint8).reshape(msg.height, msg.row_step)
        points = np.frombuffer(raw[:, :msg.width * msg.point_step].tobytes(), dtype=dtype)
    except (KeyError, ValueError, TypeError) as exc:
        raise BagError(f"{prefix or 'a PointCloud2'}: its points do not match its fields "
                       f"({_one_line(exc)})") from exc
    base = f"{prefix}.points" if prefix else "points"
    return {f"{base}.{name}": points[name].astype(np.float64).ravel() for name in dtype.names}


def flatten(msg: object, prefix: str = "") -> dict[str, float | str | np.ndarray]:
    """Leaf fields of a message as {"pose.pose.position.x": value}.

    Numbers become floats, strings stay strings, numeric arrays stay arrays (one entry,
    compared element by element), a PointCloud2's bytes become its points by field
    (``points.x``, ``points.normal_z``, ...); sequences of messages are indexed
    (``status[0].level``). The header is left out (it is the key messages are aligned on).
    """
    out: dict[str, float | str | np.ndarray] = {}
    names = getattr(msg, "__dataclass_fields__", None)
    if names is None:
        if isinstance(msg, (bool, int, float, np.integer, np.floating)):
            out[prefix] = float(msg)
        elif isinstance(msg, str):
            out[prefix] = msg
        elif isinstance(msg, (bytes, bytearray)):
            out[prefix] = np.frombuffer(bytes(msg), dtype=np.uint8).astype(np.float64)
        elif isinstance(msg, np.ndarray):
            out[prefix] = msg.astype(np.float64).ravel()
        elif isinstance(msg, (list, tuple)):
            for i, v in enumerate(msg):
                out.update(flatten(v, f"{prefix}[{i}]"))
        return out
    cloud = all(hasattr(msg, a) for a in ("point_step", "row_step", "fields", "data"))
    for name in names:
        if name == "header" or name.startswith("__") or name.isupper():  # ROS constants
            continue
        path = f"{prefix}.{name}" if prefix else name
        if cloud and name == "data":
            out.update(_cloud_points(msg, prefix))
        else:
            out.update(flatten(getattr(msg, name), path))
    return out


#: Fields a report shows per topic unless told otherwise (``--max-fields``).
DEFAULT_MAX_FIELDS = 20
#: The longest text value a report quotes, characters.
_QUOTED = 40


def _quoted(text: str) -> str:
    return repr(text if len(text) <= _QUOTED else text[:_QUOTED - 3] + "...")


@dataclass(frozen=True)
class FieldDifference:
    """The largest difference of one field between the two bags.

    Attributes:
        field: field path, e.g. ``pose.pose.position.x``.
        max_abs: largest |a - b| (inf when a text, an array's length or the set of fields
            differs).
        stamp_ns: stamp of the message where it happened.
        tolerance: the tolerance that applies.
        index: for an array field, the element where it happened; None otherwise.
        texts: for a text field that differs, its (A, B) values there; None otherwise.
    """

    field: str
    max_abs: float
    stamp_ns: int
    tolerance: float
    index: int | None = None
    texts: tuple[str, str] | None = None

    @property
    def ok(self) -> bool:
        """Within tolerance."""
        return self.max_abs <= self.tolerance

    @property
    def excess(self) -> float:
        """How far outside its tolerance: max_abs / tolerance (inf for a zero tolerance)."""
        if self.max_abs == 0.0:
            return 0.0
        return self.max_abs / self.tolerance if self.tolerance > 0.0 else math.inf

    def line(self) -> str:
        """The report's line for this field."""
        where = f"t = {self.stamp_ns / 1e9:.3f} s"
        if self.texts is not None:
            return (f"{self.field}: differs at {where}: A {_quoted(self.texts[0])}, "
                    f"B {_quoted(self.texts[1])}")
        name = self.field if self.index is None else f"{self.field}[{self.index}]"
        return (f"{name}: max |a - b| = {self.max_abs:.6g} at {where} (tolerance "
                f"{self.tolerance:g})" + ("" if self.ok else "  <-- outside"))


@dataclass(frozen=True)
class TopicComparison:
    """One topic's comparison.

    Messages are aligned on their stamps; messages of one stamp in order (the k-th of a
    stamp in A with the k-th of that stamp in B), so a repeated stamp is a message too.

    Attributes:
        topic: the topic.
        matched: messages aligned (same stamp, same place among that stamp's, in both bags).
        only_a: messages of A with no counterpart in B.
        only_b: messages of B with no counterpart in A.
        fields: per-field differences, the farthest outside its tolerance first.
        repeated: messages whose stamp an earlier message of the topic had, in A and in B.
    """

    topic: str
    matched: int
    only_a: int
    only_b: int
    fields: list[FieldDifference] = field(default_factory=list)
    repeated: tuple[int, int] = (0, 0)

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

    def report(self, max_fields: int = DEFAULT_MAX_FIELDS) -> str:
        """Per topic, every field that moved, the farthest outside its tolerance first.

        Args:
            max_fields: at most this many fields a topic (0: every one); a last line says
                how many more moved.
        """
        lines = []
        for t in self.topics:
            state = "ok" if t.ok else "DIFFERENT"
            lines.append(f"{t.topic}: {state}: {t.matched} messages matched"
                         + (f", {t.only_a} only in A" if t.only_a else "")
                         + (f", {t.only_b} only in B" if t.only_b else "")
                         + (f" (repeated stamps: {t.repeated[0]} in A, {t.repeated[1]} in B)"
                            if any(t.repeated) else ""))
            moved = [f for f in t.fields if f.max_abs > 0.0]
            if not moved:
                lines.append(f"  all {len(t.fields)} fields equal")
                continue
            shown = moved if max_fields <= 0 else moved[:max_fields]
            lines += [f"  {f.line()}" for f in shown]
            if len(moved) > len(shown):
                outside = sum(1 for f in moved[len(shown):] if not f.ok)
                lines.append(f"  ... {len(moved) - len(shown)} more fields moved ({outside} "
                             "outside their tolerance); --max-fields 0 shows every one")
        return "\n".join(lines)


def _difference(va: object, vb: object) -> tuple[float, int | None]:
    """(largest |a - b|, the array index where) of one field's values in two messages."""
    if isinstance(va, np.ndarray) and isinstance(vb, np.ndarray):
        if va.shape != vb.shape:
            return math.inf, None
        if va.size == 0:
            return 0.0, None
        nan_a, nan_b = np.isnan(va), np.isnan(vb)
        diff = np.where(nan_a & nan_b, 0.0, np.abs(va - vb))
        diff[nan_a != nan_b] = math.inf
        i = int(np.argmax(diff))
        return float(diff[i]), i
    if isinstance(va, float) and isinstance(vb, float):
        if va == vb or (math.isnan(va) and math.isnan(vb)):
            return 0.0, None
        diff = abs(va - vb)
        return (math.inf if math.isnan(diff) else diff), None  # a NaN on one side only
    return (0.0 if isinstance(va, str) and va == vb else math.inf), None


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
        keyed_a, keyed_b = _keyed(msgs_a), _keyed(bag_b[topic])
        only_b = len(keyed_b.keys() - keyed_a.keys())
        worst: dict[str, FieldDifference] = {}
        matched = only_a = 0
        for (stamp, _), msg in keyed_a.items():
            other = keyed_b.get((stamp, _))
            if other is None:
                only_a += 1
                continue
            matched += 1
            fa, fb = flatten(msg), flatten(other)
            for key in fa.keys() | fb.keys():
                diff, index = _difference(fa.get(key), fb.get(key))
                if key not in worst or diff > worst[key].max_abs:
                    texts = ((str(fa.get(key, "(absent)")), str(fb.get(key, "(absent)")))
                             if diff > 0.0 and (isinstance(fa.get(key), str)
                                                or isinstance(fb.get(key), str)) else None)
                    worst[key] = FieldDifference(key, diff, stamp,
                                                 _tolerance(key, topic, tolerances), index,
                                                 texts)
        fields = sorted(worst.values(), key=lambda f: (f.ok, -f.excess, -f.max_abs, f.field))
        repeated = (sum(1 for _, k in keyed_a if k), sum(1 for _, k in keyed_b if k))
        results.append(TopicComparison(topic, matched, only_a, only_b, fields, repeated))
    return Comparison(results)


def _keyed(messages: list[tuple[int, object]]) -> dict[tuple[int, int], object]:
    """{(stamp ns, k): the k-th message of that stamp}, in bag order."""
    seen: dict[int, int] = {}
    out = {}
    for stamp, msg in messages:
        k = seen.get(stamp, 0)
        seen[stamp] = k + 1
        out[(stamp, k)] = msg
    return out
