"""Snapshots of simulation state: flat dictionaries of numpy arrays, saved as .npz.

A dynamics process of a sharded ``run --fast`` saves its boats' state every simulated second;
when it dies, the process started in its place resumes from the last snapshot and rejoins the
step barrier (:mod:`boat_dynamics.ros.barrier`). The state is a handful of frozen dataclasses
of arrays and numbers (:class:`~boat_dynamics.physics.core.system.FleetState`, the sensors'
noise states), so a snapshot is their fields flattened under dotted keys: no pickle, and a
file that is not one is refused with a :class:`SnapshotError` that says what is wrong.
"""

from __future__ import annotations

import dataclasses
import os
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["SnapshotError", "flatten", "load", "restore", "save"]


class SnapshotError(ValueError):
    """A snapshot that cannot be read, or that does not fit what it should restore."""


def flatten(obj: Any, prefix: str) -> dict[str, np.ndarray]:
    """The fields of a flat dataclass as ``{prefix + field: array}``; None fields are left out.

    Args:
        obj: a dataclass instance whose fields are numbers, booleans, strings, arrays or None.
        prefix: put before each field's name (``state.``).

    Raises:
        TypeError: a field holds something else (a nested object).
    """
    out = {}
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        if value is None:
            continue
        if not isinstance(value, (np.ndarray, int, float, bool, str, np.number)):
            raise TypeError(f"{type(obj).__name__}.{f.name}: a {type(value).__name__} cannot "
                            "go into a snapshot (numbers, strings and arrays only)")
        out[prefix + f.name] = np.asarray(value)
    return out


def restore(like: Any, arrays: dict[str, np.ndarray], prefix: str) -> Any:
    """A copy of ``like`` with the fields a snapshot holds under ``prefix``.

    A field absent from the snapshot becomes None; a number keeps the type it has in
    ``like``; an array must have the shape ``like``'s has (when ``like`` has one).

    Args:
        like: an instance of the dataclass to restore (its fields give types and shapes).
        arrays: the snapshot (:func:`load`).
        prefix: as given to :func:`flatten`.

    Raises:
        SnapshotError: an array's shape or kind differs from ``like``'s.
    """
    values = {}
    for f in dataclasses.fields(like):
        key, current = prefix + f.name, getattr(like, f.name)
        if key not in arrays:
            values[f.name] = None
            continue
        arr = arrays[key]
        if isinstance(current, np.ndarray):
            if arr.shape != current.shape or arr.dtype.kind != current.dtype.kind:
                raise SnapshotError(f"{key}: {arr.dtype.kind}{list(arr.shape)} in the snapshot, "
                                    f"{current.dtype.kind}{list(current.shape)} expected")
            values[f.name] = arr.copy()
        elif current is None:
            values[f.name] = arr.copy()
        else:
            if arr.shape != ():
                raise SnapshotError(f"{key}: an array of shape {list(arr.shape)} in the "
                                    "snapshot, a number expected")
            values[f.name] = type(current)(arr.item())
    return dataclasses.replace(like, **values)


def save(path: str | Path, arrays: dict[str, np.ndarray]) -> None:
    """Write a snapshot atomically: readers see the previous one or this one, whole.

    Args:
        path: the .npz file (replaced).
        arrays: what to save.
    """
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as f:
        np.savez(f, **arrays)
    os.replace(tmp, path)


def load(path: str | Path) -> dict[str, np.ndarray]:
    """A snapshot's arrays.

    Raises:
        SnapshotError: the file is missing or not a snapshot (it names the file and why).
    """
    try:
        with np.load(path, allow_pickle=False) as data:
            return {k: data[k] for k in data.files}
    except FileNotFoundError as exc:
        raise SnapshotError(f"{path}: no snapshot there") from exc
    except (OSError, ValueError, zipfile.BadZipFile, EOFError) as exc:
        raise SnapshotError(f"{path}: not a boatsim snapshot ({exc})") from exc
