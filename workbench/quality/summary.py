"""A drive's findings summed up: per object and kind, and per kind (reports, incidents output)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from workbench.quality.checks import Kind

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from workbench.quality.checks import Finding

__all__ = ["ObjectKindSummary", "kind_counts", "quality_record", "summarize"]


@dataclass(frozen=True, slots=True)
class ObjectKindSummary:
    """Every finding of one object and kind.

    Attributes:
        object_id: The object.
        kind: What is implausible.
        runs: Findings (runs of consecutive flagged observations).
        frames: Observations flagged, over all runs.
        first_frame: First frame of the first run.
        last_frame: Last frame of the last run.
        worst: The finding with the worst value (farthest beyond its bound).
    """

    object_id: str
    kind: Kind
    runs: int
    frames: int
    first_frame: int
    last_frame: int
    worst: Finding


def summarize(findings: Iterable[Finding]) -> list[ObjectKindSummary]:
    """One row per object and kind, worst (farthest beyond its bound) first."""
    groups: dict[tuple[str, Kind], list[Finding]] = {}
    for f in findings:
        groups.setdefault((f.object_id, f.kind), []).append(f)
    rows = [
        ObjectKindSummary(
            object_id=obj,
            kind=kind,
            runs=len(group),
            frames=sum(f.frames for f in group),
            first_frame=min(f.start_frame for f in group),
            last_frame=max(f.end_frame for f in group),
            worst=max(group, key=lambda f: f.excess),
        )
        for (obj, kind), group in groups.items()
    ]
    return sorted(rows, key=lambda r: (-r.worst.excess, r.object_id, r.kind))


def kind_counts(findings: Iterable[Finding]) -> dict[str, int]:
    """Findings per kind, every kind listed (0 where none)."""
    counts = dict.fromkeys((str(k) for k in Kind), 0)
    for f in findings:
        counts[str(f.kind)] += 1
    return counts


def quality_record(findings: Sequence[Finding]) -> dict[str, Any]:
    """The ``data_quality`` section of a drive's outputs (JSON-ready, finite numbers only).

    ``counts``: findings per kind; ``objects``: objects with a finding; ``findings``: each
    finding (:meth:`Finding.record`).
    """
    return {
        "counts": kind_counts(findings),
        "objects": sorted({f.object_id for f in findings}),
        "findings": [f.record() for f in findings],
    }
