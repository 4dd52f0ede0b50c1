"""Every file the workbench writes: whole or not at all, and JSON without NaN or Infinity.

:func:`atomic_output` yields ``<name>.part`` beside the target and renames it into place when
the block completes (removed when it fails), so a killed or failed run never leaves a file
under its final name that is not whole. :func:`json_text` is the one JSON encoder of the
project: non-finite numbers become ``null`` (browsers' ``JSON.parse`` rejects ``Infinity``)
and numpy scalars become plain numbers; :func:`write_json` puts both together.
"""

from __future__ import annotations

import contextlib
import json
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator
    from pathlib import Path

__all__ = [
    "PART_SUFFIX",
    "atomic_output",
    "finite",
    "json_text",
    "part_path",
    "write_json",
    "write_text",
]

#: Suffix of a file being written (renamed away when complete).
PART_SUFFIX = ".part"


def finite(value: Any) -> Any:
    """``value`` with every non-finite float replaced by ``None``, numpy scalars made plain.

    Dicts, lists and tuples are copied recursively (tuples become lists, as JSON has them).
    """
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [finite(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def json_text(
    value: Any,
    *,
    indent: int | None = None,
    sort_keys: bool = False,
    compact: bool = False,
    default: Callable[[Any], Any] | None = None,
) -> str:
    """``value`` as strict JSON text (non-finite numbers as ``null``; :func:`finite`).

    Args:
        value: Dicts, lists, strings, numbers, booleans, ``None`` (numpy scalars too).
        indent: Indentation of nested values (``None``: one line).
        sort_keys: Sort the keys of every object.
        compact: No blanks after ``,`` and ``:``.
        default: Turns a value JSON cannot hold into one it can (e.g. ``str`` for paths).
    """
    separators = (",", ":") if compact else None
    if default is None:
        # Already strict JSON (the usual case): written as is, without the walk that
        # replaces non-finite numbers -- the same text, as ``finite`` changes nothing then
        # (a float subclass such as numpy.float64 is written by float's own repr).
        # Anything else (NaN, numpy ints and bools) is refused and takes the walk.
        try:
            return json.dumps(
                value, indent=indent, sort_keys=sort_keys, separators=separators, allow_nan=False
            )
        except (ValueError, TypeError):
            pass
    return json.dumps(
        finite(value),
        indent=indent,
        sort_keys=sort_keys,
        separators=separators,
        allow_nan=False,
        default=default,
    )


def part_path(path: Path) -> Path:
    """Where ``path`` is written before it is complete: ``<name>.part`` beside it."""
    return path.with_name(path.name + PART_SUFFIX)


@contextlib.contextmanager
def atomic_output(path: Path, what: str) -> Iterator[Path]:
    """Yield ``<path>.part`` to write; rename it to ``path`` when the block completes.

    The parent directory is created. When the block raises, the part file is removed and the
    error passes on; an ``OSError`` becomes one line naming the file.

    Args:
        path: The final file.
        what: What the file is, for the error (``"the clip index"``, ``"OpenLABEL"``).

    Raises:
        WorkbenchError: The file cannot be written (permissions, read-only, a directory).
    """
    part = part_path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        yield part
        part.replace(path)
    except OSError as err:
        with contextlib.suppress(OSError):
            part.unlink(missing_ok=True)
        reason = err.strerror or type(err).__name__
        msg = f"{path}: cannot write {what} ({reason})"
        raise WorkbenchError(msg) from err
    except BaseException:
        with contextlib.suppress(OSError):
            part.unlink(missing_ok=True)
        raise


def write_text(path: Path, text: str, what: str) -> None:
    """Write ``text`` to ``path`` atomically (:func:`atomic_output`)."""
    with atomic_output(path, what) as part:
        part.write_text(text, encoding="utf-8")


def write_json(path: Path, value: Any, what: str, *, indent: int | None = 2) -> None:
    """Write ``value`` as strict JSON (:func:`json_text`) to ``path``, atomically.

    Raises:
        WorkbenchError: The file cannot be written.
    """
    write_text(path, json_text(value, indent=indent) + "\n", what)
