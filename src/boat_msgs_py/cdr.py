"""Fast serialization of the fixed-layout messages the simulation publishes every step.

Building a ``nav_msgs/Odometry`` in Python and letting rclpy serialize it costs about 40 us
(measured here: 21 us to build and set the fields, 18 us to serialize and publish), while
publishing already-serialized bytes costs about 3 us. The messages a boat publishes at high
rate (odometry, pose, twist, wrenches, /clock) have a fixed layout once their frame ids are
fixed: only numbers change. A :class:`CdrTemplate` serializes a prototype message once with
rclpy, finds where each numeric field lives in the bytes (by serializing it again with that
field set to a sentinel), and then writes new values into a copy of the bytes with
:mod:`struct`. The result deserializes to the same message as
``rclpy.serialization.serialize_message`` gives for the same values, with the same length
(tested), so subscribers, bags and ROS tools cannot tell. The template's alignment padding,
which rclpy leaves uninitialized, is zeroed once (:func:`boat_msgs_py.typestore.zero_padding`),
so equal values always give equal bytes.
"""

from __future__ import annotations

import copy
import struct
from collections.abc import Callable, Sequence
from functools import lru_cache, reduce
from typing import NamedTuple

import numpy as np
from geometry_msgs.msg import PoseStamped, TransformStamped, TwistStamped, WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.serialization import serialize_message
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from boat_msgs_py.tap import type_name
from boat_msgs_py.typestore import zero_padding

__all__ = [
    "CdrTemplate",
    "FleetStateTemplate",
    "FleetTemplate",
    "TemplateError",
    "clock_template",
    "diagnostic_array_cdr",
    "odometry_template",
    "pose_template",
    "stamp_ns",
    "stamp_parts",
    "tf_template",
    "twist_template",
    "uint64_multi_array_cdr",
    "wrench_template",
]

_SENTINEL_F64 = struct.unpack("<d", bytes.fromhex("5ac37e11962bd43f"))[0]  # 0.318..., distinctive
_SENTINEL_I32 = 0x5AC37E11
_KINDS = {"float64": ("d", 8), "int32": ("i", 4), "uint32": ("I", 4)}


class TemplateError(ValueError):
    """A field cannot be located in a message's serialized form."""


def stamp_ns(seconds: float, epoch: float = 0.0) -> int:
    """The stamp, integer ns, of ``seconds`` after ``epoch`` (both s, >= 0).

    Each is rounded to the ns on its own and added as integers: a wall-clock epoch (1.7e9 s)
    plus a simulation time in one float is rounded to its 238 ns spacing, which made the
    stamps of steps 0.01 s apart differ by 0.01 s +-128 ns.
    """
    return round(epoch * 1e9) + round(seconds * 1e9)


def stamp_parts(seconds: float, epoch: float = 0.0) -> tuple[int, int]:
    """(sec, nanosec) of a builtin_interfaces/Time: :func:`stamp_ns` split."""
    return divmod(stamp_ns(seconds, epoch), 1_000_000_000)


def _step(obj: object, name: str) -> object:
    """``obj.name``, or ``obj.name[i]`` for a ``name[i]`` path segment."""
    if name.endswith("]"):
        name, index = name[:-1].split("[")
        return getattr(obj, name)[int(index)]
    return getattr(obj, name)


def _set(msg: object, path: str, value: object) -> None:
    *parents, leaf = path.split(".")
    setattr(reduce(_step, parents, msg), leaf, value)


class CdrTemplate:
    """The serialized bytes of a message, with its numeric fields writable in place.

    Args:
        msg_class: the message type, e.g. ``nav_msgs.msg.Odometry``.
        fields: dotted field paths in the order :meth:`pack` takes their values, each with its
            kind: ``("pose.pose.position.x", "float64")``, ``("header.stamp.sec", "int32")``.
        strings: dotted paths of string fields and their fixed values (frame ids).
        factory: makes the empty message (default ``msg_class()``): one whose sequences
            already have their fixed lengths, so ``transforms[2].transform.translation.x``
            is a field with a place.

    Raises:
        TemplateError: a field is not where a fixed-layout message would have it (for instance
            a field of a variable-length array, or a kind that does not match the type).
    """

    def __init__(self, msg_class: type, fields: Sequence[tuple[str, str]],
                 strings: dict[str, str] | None = None,
                 factory: Callable[[], object] | None = None) -> None:
        self._msg_class, self._fields, self._factory = msg_class, tuple(fields), factory
        self._strings = dict(strings or {})
        base = self._serialized(self._strings)
        prototype = self._prototype
        self._order = "<" if base[1] == 1 else ">"  # encapsulation: CDR_LE = 0x0001
        located = []
        for path, kind in fields:
            if kind not in _KINDS:
                raise TemplateError(f"{path}: kind {kind!r} is not one of {sorted(_KINDS)}")
            code, size = _KINDS[kind]
            msg = prototype(self._strings)
            sentinel = _SENTINEL_F64 if kind == "float64" else _SENTINEL_I32
            try:
                _set(msg, path, sentinel)
            except (AttributeError, AssertionError, TypeError, ValueError) as exc:
                raise TemplateError(f"{msg_class.__name__}.{path} cannot hold a {kind}: "
                                    f"{exc}") from exc
            probe = serialize_message(msg)
            # Alignment padding in rclpy's output is not initialized, so the field is found by
            # its sentinel's bytes, at an aligned offset (CDR aligns relative to byte 4).
            pattern = struct.pack(self._order + code, sentinel)
            places = [i for i in range(4, len(probe) - size + 1, size)
                      if probe[i:i + size] == pattern]
            if len(probe) != len(base) or len(places) != 1:
                raise TemplateError(f"{msg_class.__name__}.{path} is not a {kind} with a "
                                    "fixed place in the serialized message")
            located.append((places[0], code, size))
        self._base = zero_padding(bytes(base), type_name(msg_class))  # deterministic bytes
        #: (offset, struct code, size) of each field, in the constructor's order
        self.layout: tuple[tuple[int, str, int], ...] = tuple(located)
        # contiguous fields (x, y, z, w ...) are written with one struct call
        self._runs: list[tuple[struct.Struct, int, int]] = []  # (struct, offset, n values)
        start = 0
        for i in range(1, len(located) + 1):
            if i == len(located) or located[i][0] != located[i - 1][0] + located[i - 1][2]:
                codes = "".join(code for _, code, _ in located[start:i])
                self._runs.append((struct.Struct(self._order + codes), located[start][0],
                                   i - start))
                start = i
        self.size = len(base)

    def _prototype(self, strings: dict[str, str]) -> object:
        msg = self._msg_class() if self._factory is None else self._factory()
        for path, value in strings.items():
            _set(msg, path, value)
        return msg

    def _serialized(self, strings: dict[str, str]) -> bytes:
        return serialize_message(self._prototype(strings))

    def relabel(self, strings: dict[str, str]) -> CdrTemplate:
        """This template with other values of its string fields (a fleet's frame ids).

        CDR places a field by the lengths of the strings before it, so where every string
        has its old length in bytes the fields keep their places: one serialization instead
        of one per field (a 1000-boat fleet's templates: about 2 s less, measured). Other
        lengths locate the fields anew.

        Args:
            strings: dotted paths of the string fields (the constructor's) and their values.
        """
        if strings == self._strings:
            return self
        if strings.keys() != self._strings.keys() or any(
                len(v.encode()) != len(self._strings[k].encode()) for k, v in strings.items()):
            return CdrTemplate(self._msg_class, self._fields, strings, self._factory)
        twin = copy.copy(self)
        twin._strings = dict(strings)
        twin._base = zero_padding(self._serialized(twin._strings), type_name(self._msg_class))
        return twin

    @property
    def base(self) -> bytes:
        """The serialized prototype (every numeric field zero), padding zeroed."""
        return self._base

    @property
    def byte_order(self) -> str:
        """``<`` (CDR little-endian, what rclpy writes here) or ``>``."""
        return self._order

    def pack(self, *values: float | int) -> bytes:
        """The serialized message with ``values`` in the fields, in the constructor's order."""
        buf = bytearray(self._base)
        k = 0
        for packer, offset, n in self._runs:
            packer.pack_into(buf, offset, *values[k:k + n])
            k += n
        return bytes(buf)


class _Group(NamedTuple):
    """The boats of a :class:`FleetTemplate` whose messages have one layout."""

    select: slice | np.ndarray  #: their rows of the values (a slice when in fleet order)
    rows: list[int]  #: their indices in the fleet
    base: np.ndarray  #: (G, size) uint8, their serialized prototypes
    runs: list[tuple[int, int, int]]  #: the runs of doubles (:func:`_runs_of_doubles`)
    stamp: tuple[int, int]  #: byte offsets of header.stamp.sec and nanosec
    order: str  #: byte order, ``<`` or ``>``
    messages: list[slice]  #: each boat's message in the packed bytes


class FleetTemplate:
    """The templates of a fleet's messages of one type, packed in one numpy pass.

    Each boat's message differs from the others' only in its frame ids; boats whose ids have
    the same lengths have their fields at the same places, so their messages are rows of one
    (G, size) byte array whose numeric columns are written at once. :meth:`pack` gives
    exactly the bytes each template's :meth:`CdrTemplate.pack` gives for the same values
    (tested).

    Args:
        templates: one per boat, in fleet order; every one of the same message type and
            fields, the first two fields its stamp (int32 sec, uint32 nanosec), the others
            float64.

    Raises:
        TemplateError: a template's fields are not a stamp then float64s.
    """

    def __init__(self, templates: Sequence[CdrTemplate]) -> None:
        self.size = len(templates)
        groups: dict[tuple, list[int]] = {}
        for i, t in enumerate(templates):
            kinds = "".join(code for _, code, _ in t.layout)
            if kinds[:2] != "iI" or set(kinds[2:]) - {"d"}:
                raise TemplateError(f"a fleet template needs a stamp then float64 fields, "
                                    f"not {kinds!r}")
            groups.setdefault((len(t.base), t.layout, t.byte_order), []).append(i)
        self._groups: list[_Group] = []
        for (size, layout, order), rows in groups.items():
            base = np.frombuffer(b"".join(templates[i].base for i in rows),
                                 dtype=np.uint8).reshape(len(rows), size)
            in_order = rows == list(range(rows[0], rows[0] + len(rows)))
            self._groups.append(_Group(
                slice(rows[0], rows[0] + len(rows)) if in_order else np.array(rows), rows,
                base, _runs_of_doubles(layout[2:]), (layout[0][0], layout[1][0]), order,
                [slice(k * size, (k + 1) * size) for k in range(len(rows))]))
        # groups are made in the order of their first boats: one after the other if each is
        self._in_order = all(isinstance(g.select, slice) for g in self._groups)

    def pack(self, sec: int, nanosec: int, values: np.ndarray) -> list[bytes]:
        """Every boat's serialized message.

        Args:
            sec: header.stamp.sec, every boat's.
            nanosec: header.stamp.nanosec.
            values: (B, F) float64, each boat's float64 fields in the templates' order.

        Returns:
            B serialized messages, in fleet order.
        """
        if self._in_order:  # each layout's boats after the last's (b0 to b9, b10 to b99 ...)
            out: list[bytes] = []
            for group in self._groups:
                out += self._packed(group, sec, nanosec, values)
            return out
        out = [b""] * self.size
        for group in self._groups:
            for i, data in zip(group.rows, self._packed(group, sec, nanosec, values),
                               strict=True):
                out[i] = data
        return out

    @staticmethod
    def _packed(group: _Group, sec: int, nanosec: int, values: np.ndarray) -> list[bytes]:
        """The messages of one group of boats (one layout), in the group's order."""
        (o_sec, o_ns), order = group.stamp, group.order
        buf = group.base.copy()
        buf[:, o_sec:o_sec + 4].view(order + "i4")[:, 0] = sec
        buf[:, o_ns:o_ns + 4].view(order + "u4")[:, 0] = nanosec
        rows = group.select
        for offset, first, n in group.runs:
            buf[:, offset:offset + 8 * n].view(order + "f8")[:] = values[rows, first:first + n]
        data = buf.tobytes()
        return [data[s] for s in group.messages]


def _runs_of_doubles(layout: Sequence[tuple[int, str, int]]) -> list[tuple[int, int, int]]:
    """(byte offset, index of the first value, count) of each run of adjacent float64s."""
    runs: list[tuple[int, int, int]] = []
    for k, (offset, _, _) in enumerate(layout):
        if runs and runs[-1][0] + 8 * runs[-1][2] == offset:
            runs[-1] = (runs[-1][0], runs[-1][1], runs[-1][2] + 1)
        else:
            runs.append((offset, k, 1))
    return runs


_STAMP = (("header.stamp.sec", "int32"), ("header.stamp.nanosec", "uint32"))


def _doubles(prefix: str, names: str) -> tuple[tuple[str, str], ...]:
    return tuple((f"{prefix}.{n}", "float64") for n in names)


def _made(like: CdrTemplate | None, make: Callable[[dict[str, str]], CdrTemplate],
          strings: dict[str, str]) -> CdrTemplate:
    """``like`` relabelled with ``strings``, or ``make(strings)`` (``like``: a fleet's last)."""
    return make(strings) if like is None else like.relabel(strings)


def odometry_template(frame: str, child: str, like: CdrTemplate | None = None) -> CdrTemplate:
    """nav_msgs/Odometry; pack(sec, nanosec, px, py, pz, qx, qy, qz, qw, vx, vy, vz, wx, wy, wz).

    Covariances stay zero (unknown), as in :func:`boat_msgs_py.convert.odometry`. ``like``:
    an odometry template of other frames, relabelled (:meth:`CdrTemplate.relabel`); the same
    for the other template functions.
    """
    return _made(like, lambda s: CdrTemplate(
        Odometry, _STAMP + _doubles("pose.pose.position", "xyz")
        + _doubles("pose.pose.orientation", "xyzw") + _doubles("twist.twist.linear", "xyz")
        + _doubles("twist.twist.angular", "xyz"), s),
        {"header.frame_id": frame, "child_frame_id": child})


def pose_template(frame: str, like: CdrTemplate | None = None) -> CdrTemplate:
    """geometry_msgs/PoseStamped; pack(sec, nanosec, px, py, pz, qx, qy, qz, qw)."""
    return _made(like, lambda s: CdrTemplate(
        PoseStamped, _STAMP + _doubles("pose.position", "xyz")
        + _doubles("pose.orientation", "xyzw"), s), {"header.frame_id": frame})


def twist_template(frame: str, like: CdrTemplate | None = None) -> CdrTemplate:
    """geometry_msgs/TwistStamped; pack(sec, nanosec, vx, vy, vz, wx, wy, wz)."""
    return _made(like, lambda s: CdrTemplate(
        TwistStamped, _STAMP + _doubles("twist.linear", "xyz")
        + _doubles("twist.angular", "xyz"), s), {"header.frame_id": frame})


def wrench_template(frame: str, like: CdrTemplate | None = None) -> CdrTemplate:
    """geometry_msgs/WrenchStamped; pack(sec, nanosec, fx, fy, fz, tx, ty, tz)."""
    return _made(like, lambda s: CdrTemplate(
        WrenchStamped, _STAMP + _doubles("wrench.force", "xyz")
        + _doubles("wrench.torque", "xyz"), s), {"header.frame_id": frame})


def clock_template() -> CdrTemplate:
    """rosgraph_msgs/Clock; pack(sec, nanosec)."""
    return CdrTemplate(Clock, (("clock.sec", "int32"), ("clock.nanosec", "uint32")))


def tf_template(parent: str, child: str, like: CdrTemplate | None = None) -> CdrTemplate:
    """tf2_msgs/TFMessage of one transform, ``parent`` -> ``child``.

    pack(sec, nanosec, tx, ty, tz, qx, qy, qz, qw). One message per boat: a template of a
    fleet's transforms in one message would locate 9 fields per boat by serializing the whole
    message each time (1 s for 100 boats, measured), per-boat ones cost 9 small ones each.
    """
    prefix = "transforms[0]"
    return _made(like, lambda s: CdrTemplate(TFMessage, (
        (f"{prefix}.header.stamp.sec", "int32"), (f"{prefix}.header.stamp.nanosec", "uint32"),
        *_doubles(f"{prefix}.transform.translation", "xyz"),
        *_doubles(f"{prefix}.transform.rotation", "xyzw")), s,
        factory=lambda: TFMessage(transforms=[TransformStamped()])),
        {f"{prefix}.header.frame_id": parent, f"{prefix}.child_frame_id": child})


_PAD = (b"", b"\x00", b"\x00\x00", b"\x00\x00\x00")
_U32 = struct.Struct("<I").pack


def _cdr_string(parts: list[bytes], at: int, text: str) -> int:
    """Append a CDR string at offset ``at`` (after the encapsulation) to ``parts``.

    Its uint32 length (with the NUL) is aligned to 4 with zero bytes; returns the offset
    after its NUL.
    """
    data = text.encode()
    pad = -at % 4
    parts.append(_PAD[pad] + _U32(len(data) + 1) + data + b"\x00")
    return at + pad + len(data) + 5


def _cdr_count(parts: list[bytes], at: int, n: int) -> int:
    """Append a sequence's uint32 length at offset ``at``, aligned; returns the next offset."""
    pad = -at % 4
    parts.append(_PAD[pad] + _U32(n))
    return at + pad + 4


#: a string's NUL and the zeros after it to the next multiple of 4, by its length mod 4
_NUL_PADDED = (b"\x00" * 4, b"\x00" * 3, b"\x00" * 2, b"\x00")
_DIAGNOSTIC_HEAD = struct.Struct("<4siIIII")


@lru_cache(maxsize=4096)
def _padded_string(text: str) -> bytes:
    """A CDR string from a 4-aligned offset, padded to a multiple of 4; kept for the next call.

    For the strings a fleet's /diagnostics repeats at every report: its boats' names and the
    keys of their values.
    """
    data = text.encode()
    return _U32(len(data) + 1) + data + _NUL_PADDED[len(data) % 4]


def _status_body(name: str, message: str, values: Sequence[tuple[str, str]]) -> bytes:
    """A diagnostic_msgs/DiagnosticStatus after its level: from the name, at a 4-aligned offset.

    Every string but the last is padded to a multiple of 4 (CDR aligns the next length to 4
    from the name's), so the bytes do not depend on where the status is; the last one ends
    with its NUL (what follows decides its padding).
    """
    name_cdr = _padded_string(name)
    parts = [name_cdr, _U32(len(data := message.encode()) + 1), data,
             _NUL_PADDED[len(data) % 4], name_cdr, _U32(len(values))]  # hardware_id: the name
    for key, value in values:
        parts += (_padded_string(key), _U32(len(data := value.encode()) + 1), data,
                  _NUL_PADDED[len(data) % 4])
    if values:
        parts[-1] = b"\x00"  # the last string's NUL without its padding
    return b"".join(parts)


def diagnostic_array_cdr(sec: int, nanosec: int,
                         statuses: Sequence[tuple[str, int, str, Sequence[tuple[str, str]]]]
                         ) -> bytes:
    """diagnostic_msgs/DiagnosticArray serialized directly: little-endian CDR, padding zero.

    The same bytes as :func:`boat_msgs_py.convert.diagnostic_array` serialized by rclpy and
    zeroed (tested), and cheaper: a fleet's array holds ten strings a boat, 1.6 ms for 100
    boats as rclpy objects serialized by rclpy (measured; zeroing its padding would add
    more). A status's level is a byte right after the last status; the rest of it
    (:func:`_status_body`) is the same wherever it is.

    Args:
        sec: header.stamp.sec.
        nanosec: header.stamp.nanosec.
        statuses: (name, level 0-255, message, ((key, value), ...)) per status; the
            status's hardware_id is its name.
    """
    # CDR_LE, stamp, an empty header.frame_id (length 1, its NUL and padding), the count
    parts = [_DIAGNOSTIC_HEAD.pack(b"\x00\x01\x00\x00", sec, nanosec, 1, 0, len(statuses))]
    end = 0  # offset mod 4 after the last part (the count: aligned)
    for name, level, message, values in statuses:
        body = _status_body(name, message, values)
        parts += (bytes((level,)) + _PAD[-(end + 1) % 4], body)  # the name aligned to 4
        end = len(body) % 4
    return b"".join(parts)


class FleetStateTemplate:
    """boat_msgs/FleetState of a fixed list of boats, serialized directly (CDR, padding zero).

    Everything before the poses (the header's frame id, the names) is fixed, the poses and
    twists are two float64 blocks written from numpy: about 100 x 13 numbers in one pass.

    Args:
        frame: header.frame_id (``world``).
        names: the boats' namespaces, in fleet order.
    """

    def __init__(self, frame: str, names: Sequence[str]) -> None:
        parts = [b"\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"]  # CDR_LE, stamp
        at = _cdr_string(parts, 8, frame)
        at = _cdr_count(parts, at, len(names))
        for name in names:
            at = _cdr_string(parts, at, name)
        at = _cdr_count(parts, at, len(names))  # poses
        pad = -at % 8 if names else 0  # doubles align to 8
        self._head = b"".join(parts) + bytes(pad)
        end = at + pad + 56 * len(names)
        # twists: their count aligned to 4 after the poses, then the doubles to 8
        count_pad = -end % 4
        doubles_pad = -(end + count_pad + 4) % 8 if names else 0
        self._middle = bytes(count_pad) + _U32(len(names)) + bytes(doubles_pad)
        self.size = len(names)

    def pack(self, sec: int, nanosec: int, poses: np.ndarray, twists: np.ndarray) -> bytes:
        """The serialized message.

        Args:
            sec: header.stamp.sec.
            nanosec: header.stamp.nanosec.
            poses: (B, 7) position m, orientation (x, y, z, w), world frame.
            twists: (B, 6) linear m/s, angular rad/s, each boat's base_link frame.
        """
        head = self._head[:4] + struct.pack("<iI", sec, nanosec) + self._head[12:]
        return (head + np.ascontiguousarray(poses, dtype="<f8").tobytes() + self._middle
                + np.ascontiguousarray(twists, dtype="<f8").tobytes())


def uint64_multi_array_cdr(values: Sequence[int]) -> bytes:
    """std_msgs/UInt64MultiArray with an empty layout, serialized directly (padding zero).

    The step barrier's report (``/boatsim/step_done``), sent every few steps: about 4 us as a
    message object through rclpy, a tenth of that as bytes.
    """
    head = struct.pack("<4sIII", b"\x00\x01\x00\x00", 0, 0, len(values))  # dims, offset
    pad = bytes(4) if values else b""  # uint64s align to 8: the data starts at 16
    return head + pad + struct.pack(f"<{len(values)}Q", *values)
