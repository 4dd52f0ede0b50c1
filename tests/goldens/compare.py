"""Per-frame records compared with a documented float tolerance, and what changed, summarised.

Equality (:func:`first_difference`):

* ``bool``, ``int``, ``str`` and ``None`` exactly, and of the same type (``True`` is not
  ``1``, ``2`` is not ``2.0``: either would change the ``--per-frame`` text);
* lists element by element (same length), objects key by key (same keys, same order: the
  records pin their key order);
* floats within ``|a - b| <= ABS_TOL + REL_TOL * max(|a|, |b|)``. The records round their
  floats to :data:`RECORD_QUANTUM` (``json_number``, ``round(x, 6)``), so a last-bit
  difference of an upstream value (another CPU, another SIMD path) vanishes there, except
  at a rounding tie, where it moves the value by one quantum: the absolute tolerance is one
  quantum plus 1e-9, the relative one 1e-9 (for a plugin's unrounded floats). Nothing
  smaller than the records' own resolution can fail a golden; any discrete change does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from tests.goldens.golden_file import FrameRecord

__all__ = [
    "ABS_TOL",
    "RECORD_QUANTUM",
    "REL_TOL",
    "Changes",
    "compare",
    "first_difference",
    "spans",
]

#: The resolution the engines' records round their floats to.
RECORD_QUANTUM = 1e-6
#: Absolute float tolerance: one record quantum (a rounding tie moved) plus 1e-9.
ABS_TOL = RECORD_QUANTUM + 1e-9
#: Relative float tolerance.
REL_TOL = 1e-9
#: How many changed frames a summary lists as spans before it elides the rest.
_SHOWN_SPANS = 8


def _close(a: float, b: float) -> bool:
    if not (math.isfinite(a) and math.isfinite(b)):
        return a == b
    return abs(a - b) <= ABS_TOL + REL_TOL * max(abs(a), abs(b))


def _show(where: str, expected: Any, got: Any) -> str:
    return f"{where or '.'}: {expected!r} -> {got!r}"


def _dict_difference(expected: dict[str, Any], got: dict[str, Any], where: str) -> str | None:
    for key in [*expected, *(k for k in got if k not in expected)]:
        if key not in expected or key not in got:
            absent = "(absent)"
            return _show(f"{where}.{key}", expected.get(key, absent), got.get(key, absent))
        found = first_difference(expected[key], got[key], f"{where}.{key}")
        if found:
            return found
    if list(expected) != list(got):
        return _show(f"{where} key order", list(expected), list(got))
    return None


def _list_difference(expected: list[Any], got: list[Any], where: str) -> str | None:
    if len(expected) != len(got):
        return _show(where, expected, got) + f" ({len(expected)} -> {len(got)} items)"
    for k, (e, g) in enumerate(zip(expected, got, strict=True)):
        found = first_difference(e, g, f"{where}[{k}]")
        if found:
            return found
    return None


def first_difference(expected: Any, got: Any, where: str = "") -> str | None:
    """The first place where ``got`` differs from ``expected`` (None: equal within tolerance).

    Returns:
        ``"<path>: <expected> -> <got>"``, the path in ``.a.b[2]`` notation (``.``: the whole).
    """
    if type(expected) is not type(got):
        found: str | None = _show(where, expected, got)
    elif isinstance(expected, dict):
        found = _dict_difference(expected, got, where)
    elif isinstance(expected, list):
        found = _list_difference(expected, got, where)
    elif isinstance(expected, float):
        found = None if _close(expected, got) else _show(where, expected, got)
    else:
        found = None if expected == got else _show(where, expected, got)
    return found


def spans(frames: Iterable[int]) -> str:
    """Frame numbers as short ranges: ``"3-7, 12, 40-41"`` (the first few, then ``…``)."""
    runs: list[list[int]] = []
    for f in sorted(frames):
        if runs and f == runs[-1][1] + 1:
            runs[-1][1] = f
        else:
            runs.append([f, f])
    text = [str(a) if a == b else f"{a}-{b}" for a, b in runs[:_SHOWN_SPANS]]
    more = len(runs) - _SHOWN_SPANS
    return ", ".join(text) + (f", … ({more} more)" if more > 0 else "")


@dataclass
class Changes:
    """What differs between the golden frames and the evaluated ones."""

    frames: int
    changed: list[int] = field(default_factory=list)
    added: list[int] = field(default_factory=list)
    removed: list[int] = field(default_factory=list)
    keys: dict[str, int] = field(default_factory=dict)
    safe_to_unsafe: int = 0
    unsafe_to_safe: int = 0
    first: str | None = None

    def __bool__(self) -> bool:
        """Whether anything differs beyond the tolerance."""
        return bool(self.changed or self.added or self.removed)

    def summary(self) -> str:
        """A few lines: which frames changed, in which keys, which verdicts flipped."""
        lines = [f"{len(self.changed)} of {self.frames} frames changed: {spans(self.changed)}"]
        if self.added or self.removed:
            lines.append(f"frames added: {spans(self.added)}; removed: {spans(self.removed)}")
        if self.keys:
            lines.append("keys: " + ", ".join(f"{k} ({n})" for k, n in self.keys.items()))
        if self.safe_to_unsafe or self.unsafe_to_safe:
            flips = f"safe -> unsafe {self.safe_to_unsafe}, unsafe -> safe {self.unsafe_to_safe}"
            lines.append(f"is_safe: {flips}")
        if self.first:
            lines.append(f"first: {self.first}")
        return "\n".join(lines)


def _note(changes: Changes, frame: int, expected: FrameRecord, got: FrameRecord) -> None:
    changes.changed.append(frame)
    old: Any = {"t_ns": expected.t_ns, "record": expected.record}
    new: Any = {"t_ns": got.t_ns, "record": got.record}
    if isinstance(expected.record, dict) and isinstance(got.record, dict):
        old = {"t_ns": expected.t_ns, **expected.record}
        new = {"t_ns": got.t_ns, **got.record}
    for key in [*old, *(k for k in new if k not in old)]:
        if key not in old or key not in new or first_difference(old[key], new[key]):
            changes.keys[key] = changes.keys.get(key, 0) + 1
    was, now = old.get("is_safe"), new.get("is_safe")
    changes.safe_to_unsafe += was is True and now is False
    changes.unsafe_to_safe += was is False and now is True
    if changes.first is None:
        changes.first = f"frame {frame}: {str(first_difference(old, new)).lstrip('.')}"


def compare(expected: Sequence[FrameRecord], got: Sequence[FrameRecord]) -> Changes:
    """Frame by frame (matched by frame number): what differs beyond the tolerance."""
    old = {f.frame: f for f in expected}
    new = {f.frame: f for f in got}
    changes = Changes(frames=len(got))
    changes.added = sorted(new.keys() - old.keys())
    changes.removed = sorted(old.keys() - new.keys())
    for frame in sorted(old.keys() & new.keys()):
        e, g = old[frame], new[frame]
        if e.t_ns != g.t_ns or first_difference(e.record, g.record):
            _note(changes, frame, e, g)
    return changes
