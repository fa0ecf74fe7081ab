"""ROS messages to and from YAML, as ``ros2 topic echo`` prints them and ``topic pub`` reads them.

The PyPI wheels have no ``rosidl_runtime_py`` (and no ``ros2`` command line), so boatsim's
``topic echo`` and ``topic pub`` use these: a message's fields in declaration order
(``get_fields_and_field_types``), nested messages indented by two spaces, arrays as YAML
lists, documents separated by ``---`` by the caller.
"""

from __future__ import annotations

import array
import importlib
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import yaml

__all__ = ["FieldError", "message_class", "message_to_yaml", "set_fields"]

#: Array elements an echo prints before it says how many more there are (``--full-length``
#: lifts it, as in ``ros2 topic echo``).
TRUNCATE_LENGTH = 128


class FieldError(ValueError):
    """A message type that is not installed, or values that do not fit a message."""


def message_class(type_name: str) -> type:
    """The message class of ``pkg/msg/Name`` (or ``pkg/Name``).

    Raises:
        FieldError: a malformed name or a type that is not installed here.
    """
    parts = type_name.split("/")
    if len(parts) == 2:
        parts = [parts[0], "msg", parts[1]]
    if len(parts) != 3 or not all(parts):
        raise FieldError(f"{type_name!r} is not a message type (expected pkg/msg/Name, e.g. "
                         "std_msgs/msg/Float64)")
    try:
        return getattr(importlib.import_module(f"{parts[0]}.{parts[1]}"), parts[2])
    except (ImportError, AttributeError):
        raise FieldError(f"message type {type_name} is not installed here") from None


def _scalar(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return ".nan"
        if math.isinf(value):
            return ".inf" if value > 0 else "-.inf"
        text = repr(value)  # YAML 1.1 reads 1e-300 as text: it wants 1.0e-300
        return text.replace("e", ".0e") if "e" in text and "." not in text else text
    if isinstance(value, str):  # quoted as YAML quotes it, where it must be
        text = yaml.safe_dump(value, default_flow_style=True, width=math.inf,
                              allow_unicode=True)
        return text.removesuffix("\n").removesuffix("\n...")
    if isinstance(value, bytes):  # a byte field (a DiagnosticStatus level): its number
        return str(value[0]) if len(value) == 1 else repr(value)
    return str(value)


def _lines(value: Any, indent: str, full: bool) -> list[str]:
    """YAML lines of a field's value; the first is appended to ``key:`` by the caller."""
    if hasattr(value, "get_fields_and_field_types"):
        out = []
        for name in value.get_fields_and_field_types():
            sub = _lines(getattr(value, name), indent + "  ", full)
            if sub and sub[0].startswith("\n"):
                out.append(f"{indent}{name}:{sub[0]}")
                out += sub[1:]
            else:
                out.append(f"{indent}{name}: {sub[0]}")
        return ["\n" + out[0].lstrip("\n"), *out[1:]] if out else ["{}"]
    if isinstance(value, (list, tuple, np.ndarray, array.array)):
        items = list(value.tolist() if isinstance(value, np.ndarray) else value)
        if not items:
            return ["[]"]
        dash = indent[:-2]  # block lists sit at their key's indent, as yaml.dump writes them
        shown = items if full else items[:TRUNCATE_LENGTH]
        out = []
        for item in shown:
            sub = _lines(item, indent, full)
            if sub[0].startswith("\n"):  # a message: its first field on the dash's line
                out.append(f"{dash}- {sub[0].strip()}")
                out += sub[1:]
            else:
                out.append(f"{dash}- {sub[0]}")
        if len(items) > len(shown):
            out.append(f"{dash}- '...'  # {len(items) - len(shown)} more (--full-length)")
        return ["\n" + out[0], *out[1:]]
    return [_scalar(value)]


def message_to_yaml(msg: Any, full_length: bool = False) -> str:
    """A message as ``ros2 topic echo`` prints it (without the ``---`` separator).

    Args:
        msg: an rclpy message.
        full_length: print every element of long arrays (else the first
            :data:`TRUNCATE_LENGTH`, then how many more).
    """
    lines = _lines(msg, "", full_length)
    return (lines[0].lstrip("\n") + "\n" + "\n".join(lines[1:])).rstrip("\n") + "\n"


_FLOATS = frozenset({"float", "double"})
_INTEGERS = frozenset({"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64",
                       "uint64", "char", "octet"})


def _check_kind(where: str, value: Any, field_type: str) -> None:
    """Refuse a value of another kind than a primitive field's.

    rclpy takes 'fast' for a float64 without a word (measured), and a message then fails
    to serialize far from the mistake.
    """
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    ok = {"boolean": isinstance(value, bool), "string": isinstance(value, str)}.get(
        field_type, number if field_type in _FLOATS else (
            number and float(value).is_integer() if field_type in _INTEGERS else True))
    if not ok:
        raise FieldError(f"{where}: {value!r} does not fit a {field_type}")


def _element_type(field_type: str) -> str:
    """``pkg/Name`` of ``sequence<pkg/Name>``, ``sequence<pkg/Name, 5>`` or ``pkg/Name[3]``."""
    inner = field_type.split("<", 1)[1].rstrip(">") if "<" in field_type else field_type
    return inner.split(",")[0].split("[")[0].strip()


def set_fields(msg: Any, values: Mapping[str, Any], path: str = "") -> Any:
    """Set ``msg``'s fields from a mapping (parsed YAML, as ``ros2 topic pub`` takes); returns msg.

    Raises:
        FieldError: a field the message does not have, or a value of the wrong kind.
    """
    if not isinstance(values, Mapping):
        raise FieldError(f"{path or 'the message'}: expected a mapping of fields, got "
                         f"{type(values).__name__} {values!r}")
    fields = msg.get_fields_and_field_types()
    for name, value in values.items():
        where = f"{path}.{name}" if path else str(name)
        if name not in fields:
            raise FieldError(f"{where}: {type(msg).__name__} has no such field (it has: "
                             f"{', '.join(fields)})")
        current = getattr(msg, name)
        _check_kind(where, value, fields[name])
        try:
            if hasattr(current, "get_fields_and_field_types"):
                set_fields(current, value, where)
            elif isinstance(current, float) and isinstance(value, int):
                setattr(msg, name, float(value))  # YAML's 1 for a float64 field
            elif isinstance(current, bytes) and isinstance(value, int):
                setattr(msg, name, bytes([value]))  # a byte field, as echo prints it
            elif isinstance(value, list) and value and isinstance(value[0], Mapping):
                setattr(msg, name, [set_fields(message_class(_element_type(fields[name]))(),
                                               v, f"{where}[{i}]") for i, v in enumerate(value)])
            else:
                setattr(msg, name, value)
        except FieldError:
            raise
        except (AssertionError, TypeError, ValueError) as exc:
            raise FieldError(f"{where}: {value!r} does not fit a {fields[name]} "
                             f"({' '.join(str(exc).split()) or type(exc).__name__})") from None
    return msg
