"""Compare two batches: which incidents are new, vanished or changed, with their labels.

Incidents are matched per drive (content hash), engine and objects, by overlapping time
interval, one to one, largest overlap first. A matched pair is ``changed`` when the cause
differs or a severity fact differs beyond the tolerance (numbers: ``|a - b| > atol + rtol *
max(|a|, |b|)``; other values: not equal). Facts that echo a setting or are derived from the
others (:data:`UNCOMPARED_FACTS`) are not compared. Only drives evaluated in both
batches (status other than ``failed``) are compared; the others are counted apart.

The order is the one a reviewer needs: an incident **confirmed** in A that vanished in B
first, then the other vanished ones, the new ones, the changed ones; worst first within each.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from workbench.batch.queue import load_queue, read_table
from workbench.outputs import json_text

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable
    from pathlib import Path

    from workbench.batch.queue import FleetIncident

__all__ = [
    "KINDS",
    "UNCOMPARED_FACTS",
    "Change",
    "DiffResult",
    "Tolerance",
    "diff_results",
]

#: Change kinds, in report order (``vanished-confirmed`` is a vanished one labelled confirmed).
KINDS = ("vanished-confirmed", "vanished", "new", "changed")
#: Severity facts not compared: the profile's name (differs whenever the settings do) and the
#: sort key built from the other facts.
UNCOMPARED_FACTS = frozenset({"profile", "severity_rank"})


@dataclass(frozen=True, slots=True)
class Tolerance:
    """How far two numeric facts may differ and still be the same.

    Attributes:
        rtol: Relative tolerance (of the larger magnitude).
        atol: Absolute tolerance, in the fact's unit.
    """

    rtol: float = 0.05
    atol: float = 1e-6

    def same(self, a: Any, b: Any) -> bool:
        """Whether two fact values are the same within the tolerance."""
        if isinstance(a, list | tuple) and isinstance(b, list | tuple):
            return len(a) == len(b) and all(self.same(x, y) for x, y in zip(a, b, strict=True))
        numbers = (int, float)
        if isinstance(a, numbers) and isinstance(b, numbers) and not isinstance(a, bool):
            fa, fb = float(a), float(b)
            if not (math.isfinite(fa) and math.isfinite(fb)):
                return fa == fb
            return abs(fa - fb) <= self.atol + self.rtol * max(abs(fa), abs(fb))
        return bool(a == b)


@dataclass(frozen=True, slots=True)
class Change:
    """One difference between batch A and batch B.

    Attributes:
        kind: One of :data:`KINDS`.
        a: The incident in A (``None`` for new ones).
        b: The incident in B (``None`` for vanished ones).
        differences: Fact (or ``cause``) -> ``(value in A, value in B)`` of a changed pair.
        verdict: The label of A's incident (B's for new ones), if any.
    """

    kind: str
    a: FleetIncident | None
    b: FleetIncident | None
    differences: dict[str, tuple[Any, Any]] = field(default_factory=dict)
    verdict: str | None = None

    @property
    def either(self) -> FleetIncident:
        """A's incident, else B's."""
        found = self.a or self.b
        assert found is not None  # a change has at least one side
        return found

    def record(self) -> dict[str, Any]:
        """JSON-ready: the kind, the label, the drive and both sides' rows."""
        item = self.either
        return {
            "kind": self.kind,
            "verdict": self.verdict,
            "drive_path": item.drive_path,
            "drive_hash": item.drive_hash,
            "engine": item.incident.engine,
            "objects": list(item.incident.objects),
            "a": None if self.a is None else self.a.row,
            "b": None if self.b is None else self.b.row,
            "differences": {k: list(v) for k, v in self.differences.items()},
        }


@dataclass(frozen=True, slots=True)
class DiffResult:
    """The changes from A to B and what was compared.

    Attributes:
        changes: In report order.
        matched: Incident pairs found in both batches (changed or not).
        drives: Drives (content hashes) compared.
        only_a: Drives evaluated in A only (not compared).
        only_b: Drives evaluated in B only (not compared).
    """

    changes: list[Change]
    matched: int
    drives: int
    only_a: int
    only_b: int

    def count(self, kind: str) -> int:
        """How many changes of ``kind`` (``vanished`` counts the confirmed ones too)."""
        if kind == "vanished":
            return sum(c.kind in {"vanished", "vanished-confirmed"} for c in self.changes)
        return sum(c.kind == kind for c in self.changes)


def _evaluated(results: Path) -> set[str]:
    return {
        d["content_hash"]
        for d in read_table(results, "drives.parquet")
        if d["status"] != "failed" and d["content_hash"]
    }


def _overlap(a: FleetIncident, b: FleetIncident) -> int:
    ia, ib = a.incident, b.incident
    return min(ia.end_ns, ib.end_ns) - max(ia.start_ns, ib.start_ns)


def _key(item: FleetIncident) -> tuple[str, str, tuple[str, ...]]:
    return (item.drive_hash, item.incident.engine, item.incident.objects)


def _match(
    side_a: list[FleetIncident], side_b: list[FleetIncident]
) -> list[tuple[FleetIncident, FleetIncident]]:
    """One-to-one pairs of overlapping incidents of the same drive, engine and objects."""
    groups: dict[tuple[str, str, tuple[str, ...]], list[FleetIncident]] = {}
    for item in side_b:
        groups.setdefault(_key(item), []).append(item)
    candidates = [
        (_overlap(a, b), ia, ib, a, b)
        for ia, a in enumerate(side_a)
        for ib, b in enumerate(groups.get(_key(a), []))
        if _overlap(a, b) >= 0
    ]
    candidates.sort(key=lambda c: (-c[0], c[3].incident.start_ns, c[4].incident.start_ns))
    used_a: set[int] = set()
    used_b: set[int] = set()
    pairs = []
    for _, _, _, a, b in candidates:
        if id(a) in used_a or id(b) in used_b:
            continue
        used_a.add(id(a))
        used_b.add(id(b))
        pairs.append((a, b))
    return pairs


def _differences(a: FleetIncident, b: FleetIncident, tol: Tolerance) -> dict[str, tuple[Any, Any]]:
    out: dict[str, tuple[Any, Any]] = {}
    if a.incident.cause != b.incident.cause:
        out["cause"] = (a.incident.cause, b.incident.cause)
    sa, sb = a.incident.severity.record(), b.incident.severity.record()
    for name in sorted((set(sa) | set(sb)) - UNCOMPARED_FACTS):
        va, vb = sa.get(name), sb.get(name)
        if (va is None) != (vb is None) or (va is not None and not tol.same(va, vb)):
            out[name] = (va, vb)
    return out


def diff_results(
    results_a: Path,
    results_b: Path,
    *,
    tolerance: Tolerance | None = None,
    verdict_of: Callable[[str, str], str | None] | None = None,
) -> DiffResult:
    """The incidents new, vanished and changed from batch A to batch B.

    Args:
        results_a: The results directory of the first batch (the baseline).
        results_b: The results directory of the second.
        tolerance: How far facts may differ (default :class:`Tolerance`).
        verdict_of: ``(drive_hash, incident_id) -> verdict`` of the label store, if any.

    Raises:
        BatchError: A batch's tables cannot be read.
    """
    tol = tolerance or Tolerance()
    evaluated_a, evaluated_b = _evaluated(results_a), _evaluated(results_b)
    both = evaluated_a & evaluated_b
    side_a = [i for i in load_queue(results_a) if i.drive_hash in both]
    side_b = [i for i in load_queue(results_b) if i.drive_hash in both]
    pairs = _match(side_a, side_b)
    matched_a = {id(a) for a, _ in pairs}
    matched_b = {id(b) for _, b in pairs}

    def verdict(item: FleetIncident) -> str | None:
        return None if verdict_of is None else verdict_of(item.drive_hash, item.incident.id)

    changes: list[Change] = []
    for a in side_a:
        if id(a) not in matched_a:
            label = verdict(a)
            kind = "vanished-confirmed" if label == "confirmed" else "vanished"
            changes.append(Change(kind, a, None, verdict=label))
    changes.extend(
        Change("new", None, b, verdict=verdict(b)) for b in side_b if id(b) not in matched_b
    )
    for a, b in pairs:
        found = _differences(a, b, tol)
        if found:
            changes.append(Change("changed", a, b, found, verdict(a)))
    changes.sort(key=lambda c: (KINDS.index(c.kind), c.either.rank_key()))
    return DiffResult(
        changes=changes,
        matched=len(pairs),
        drives=len(both),
        only_a=len(evaluated_a - evaluated_b),
        only_b=len(evaluated_b - evaluated_a),
    )


def rows(changes: Iterable[Change]) -> list[dict[str, Any]]:
    """Flat rows of the changes (``diff.parquet``): both sides' id, cause and interval."""
    out = []
    for change in changes:
        rec = change.record()
        a, b = rec.pop("a") or {}, rec.pop("b") or {}
        rec["differences"] = json_text(rec["differences"], sort_keys=True, default=str)
        for side, row in (("a", a), ("b", b)):
            for name in ("id", "cause", "start_ns", "end_ns", "severity.worst_margin"):
                rec[f"{side}.{name}"] = row.get(name)
        out.append(rec)
    return out
