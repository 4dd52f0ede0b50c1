"""Which incidents become clips, over which windows, under which file names."""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from workbench.errors import WorkbenchError
from workbench.outputs import finite, json_text

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from workbench.annotations import Label
    from workbench.incidents import Incident, IncidentReport

__all__ = ["ClipPlan", "Selection", "plan_clips", "safe_stem"]

#: Longest file stem written (characters).
_MAX_STEM = 96
_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")


def safe_stem(text: str) -> str:
    """``text`` as a portable file stem: ``[A-Za-z0-9._-]`` only, no leading dot, bounded.

    Path separators, ``..``, control and shell characters all become ``_``; an empty result
    becomes ``clip``.
    """
    stem = _UNSAFE.sub("_", re.sub(r"\.{2,}", "_", text))
    stem = re.sub(r"_{2,}", "_", stem).strip("._-")[:_MAX_STEM].rstrip("._-")
    return stem or "clip"


@dataclass(frozen=True, slots=True)
class Selection:
    """Which incidents to export.

    Attributes:
        ids: These incident ids (each must exist).
        verdict: Incidents whose review label has this verdict.
        all: Every incident.
        window: A stretch of the drive, incident or not (``--window``,
            :mod:`workbench.export.window`).
    """

    ids: tuple[str, ...] = ()
    verdict: str | None = None
    all: bool = False
    window: str | None = None

    def check(self) -> None:
        """Exactly one way of choosing.

        Raises:
            WorkbenchError: None or several were given.
        """
        given = sum((bool(self.ids), self.verdict is not None, self.all, self.window is not None))
        if given != 1:
            msg = "choose the clips with exactly one of --incident, --verdict, --all or --window"
            raise WorkbenchError(msg)


@dataclass(frozen=True, slots=True)
class ClipPlan:
    """One clip to write.

    Attributes:
        incident: The incident (``None``: a window of the drive, ``--window``).
        label: Its review label, if any.
        stem: File stem of the clip's files (unique within the export).
        start_ns: First log time of the clip (incident start minus margin, within the drive).
        end_ns: Last log time of the clip (incident end plus margin, within the drive).
        frames: First and last frame of a window without incident (``None``: an incident's).
    """

    incident: Incident | None
    label: Label | None
    stem: str
    start_ns: int
    end_ns: int
    frames: tuple[int, int] | None = None

    def event(self) -> dict[str, str]:
        """The incident and its label as the clip's event key/value pairs (``{}``: a window).

        Lists (``objects``, ``tags``) are JSON arrays: an id or a tag may hold a comma.
        """
        i, label = self.incident, self.label
        if i is None:
            return {}
        pairs = {
            "incident_id": i.id,
            "engine": i.engine,
            "objects": json_text(list(i.objects)),
            "cause": i.cause,
            "start_ns": str(i.start_ns),
            "end_ns": str(i.end_ns),
            "start_frame": str(i.start_frame),
            "end_frame": str(i.end_frame),
        }
        for name, value in finite(i.severity.record()).items():
            pairs[f"severity.{name}"] = "" if value is None else str(value)
        if label is not None:
            pairs |= {
                "verdict": label.verdict,
                "tags": json_text(list(label.tags)),
                "note": label.note,
                "reviewer": label.reviewer,
                "labelled_ns": str(label.labelled_ns),
            }
        return pairs

    def record(self) -> dict[str, Any]:
        """JSON-ready summary for the export index."""
        label = self.label
        if self.incident is not None:
            facts = self.incident.record()
        else:
            first, last = self.frames or (0, 0)
            facts = {"id": None, "objects": [], "start_frame": first, "end_frame": last}
            facts |= {"start_ns": self.start_ns, "end_ns": self.end_ns, "severity": {}}
        return {
            **facts,
            "verdict": None if label is None else label.verdict,
            "tags": [] if label is None else list(label.tags),
            "note": "" if label is None else label.note,
            "reviewer": None if label is None else label.reviewer,
            "labelled_ns": None if label is None else label.labelled_ns,
            "clip_start_ns": self.start_ns,
            "clip_end_ns": self.end_ns,
        }


def _chosen(
    report: IncidentReport, labels: Mapping[str, Label], selection: Selection
) -> list[Incident]:
    selection.check()
    if selection.all:
        return list(report.incidents)
    if selection.verdict is not None:
        return [
            i
            for i in report.incidents
            if (label := labels.get(i.id)) is not None and label.verdict == selection.verdict
        ]
    unknown = [i for i in selection.ids if report.find(i) is None]
    if unknown:
        msg = (
            f"{report.log}: no incident {', '.join(unknown)} with these settings "
            "(list them with `workbench incidents`)"
        )
        raise WorkbenchError(msg)
    return [i for i in report.incidents if i.id in selection.ids]


def plan_clips(
    report: IncidentReport,
    labels: Mapping[str, Label],
    selection: Selection,
    margin_ns: int,
) -> list[ClipPlan]:
    """The clips of the chosen incidents, worst first, windows clamped to the drive.

    Raises:
        WorkbenchError: An unknown incident id, or not exactly one way of choosing.
    """
    times: Sequence[tuple[int, int]] = report.frame_times
    first_ns = times[0][1] if times else report.start_ns
    last_ns = times[-1][1] if times else report.start_ns
    plans = []
    used: set[str] = set()
    for rank, incident in enumerate(_chosen(report, labels, selection), start=1):
        stem = safe_stem(f"{rank:03d}_{incident.id}")
        while stem in used:
            stem = safe_stem(f"{stem}_{rank}")
        used.add(stem)
        plans.append(
            ClipPlan(
                incident,
                labels.get(incident.id),
                stem,
                max(first_ns, incident.start_ns - margin_ns),
                min(last_ns, incident.end_ns + margin_ns),
            )
        )
    return plans
