"""``export_clips``: every file of every clip, and the export's index.

Per clip, into the output directory: ``<stem>.mcap`` (the window's messages, the incident
event, the map), ``<stem>.openlabel.json`` (ASAM OpenLABEL 1.0 of the incident and its
label), ``<stem>.rrd`` (the window replayed with the review blueprint) and ``<stem>.png``
(thumbnail at the incident's first frame). ``clips.json`` and ``clips.csv`` index them.
Index files are written atomically (temporary file, then rename).
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from workbench.annotations.openlabel import export_openlabel, write_openlabel
from workbench.errors import WorkbenchError
from workbench.export.raw import write_raw_clips, write_ros1_bags
from workbench.export.views import write_recordings, write_thumbnails
from workbench.outputs import write_json, write_text

if TYPE_CHECKING:
    from collections.abc import Callable, Collection, Sequence
    from pathlib import Path

    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["ExportSummary", "ExportedClip", "export_clips"]

_CSV_FIELDS = (
    "stem",
    "id",
    "engine",
    "objects",
    "cause",
    "verdict",
    "start_ns",
    "end_ns",
    "clip_start_ns",
    "clip_end_ns",
    "messages",
    "mcap",
    "bag",
    "openlabel",
    "rrd",
    "png",
    "problem",
)


@dataclass(frozen=True, slots=True)
class ExportedClip:
    """The files of one clip (``None``: not written, see ``problem``; ``bag``: ROS 1 logs)."""

    plan: ClipPlan
    mcap: Path | None
    bag: Path | None
    openlabel: Path
    rrd: Path | None
    png: Path | None
    messages: int
    per_topic: dict[str, int]
    problem: str | None

    def record(self) -> dict[str, Any]:
        """The clip's entry in ``clips.json`` (file names relative to the directory)."""
        files = {
            "mcap": self.mcap,
            "bag": self.bag,
            "openlabel": self.openlabel,
            "rrd": self.rrd,
            "png": self.png,
        }
        return {
            "stem": self.plan.stem,
            **self.plan.record(),
            "messages": self.messages,
            "messages_per_topic": dict(sorted(self.per_topic.items())),
            "files": {k: None if v is None else v.name for k, v in files.items()},
            "problem": self.problem,
        }


@dataclass(frozen=True, slots=True)
class ExportSummary:
    """What an export wrote.

    Attributes:
        clips: Per plan, in order (worst first).
        index_json: ``clips.json``.
        index_csv: ``clips.csv``.
        thumbnails_skipped: Why no thumbnails were rendered (``None``: rendered or not asked).
    """

    clips: tuple[ExportedClip, ...]
    index_json: Path
    index_csv: Path
    thumbnails_skipped: str | None

    @property
    def bytes_written(self) -> int:
        """Size of every file written."""
        paths = [p for c in self.clips for p in (c.mcap, c.bag, c.openlabel, c.rrd, c.png) if p]
        return sum(p.stat().st_size for p in paths if p.is_file())


def _frames_writer(request: IncidentRequest) -> Callable[[Path, int, int], None]:
    def write(path: Path, start_ns: int, end_ns: int) -> None:
        from workbench.samples.drive_mcap import write_drive_mcap  # noqa: PLC0415 - on demand

        drive = request.open_drive()
        try:
            name = None if request.map_path is None else request.map_path.name
            write_drive_mcap(drive, path, map_name=name, window=(start_ns, end_ns + 1))
        finally:
            drive.close()

    return write


def _write_index(out_dir: Path, clips: Sequence[ExportedClip]) -> tuple[Path, Path]:
    records = [c.record() for c in clips]
    rows = io.StringIO()
    writer = csv.DictWriter(rows, fieldnames=_CSV_FIELDS, extrasaction="ignore")
    writer.writeheader()
    for record in records:
        writer.writerow(
            {
                **record,
                **{k: v or "" for k, v in record["files"].items()},
                "objects": " ".join(record["objects"]),
                "problem": record["problem"] or "",
            }
        )
    write_json(out_dir / "clips.json", records, "the clip index")
    write_text(out_dir / "clips.csv", rows.getvalue(), "the clip index")
    return out_dir / "clips.json", out_dir / "clips.csv"


def export_clips(
    report: IncidentReport,
    request: IncidentRequest,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    *,
    topics: Collection[str] | None = None,
    recordings: bool = True,
    thumbnails: bool = True,
    on_bytes: Callable[[int], None] | None = None,
    on_clip: Callable[[], None] | None = None,
) -> ExportSummary:
    """Write every clip of ``plans`` into ``out_dir`` and index them.

    Args:
        report: The drive's incidents, as found with ``request``.
        request: The drive and settings (re-used to replay the windows).
        plans: The clips (:func:`workbench.export.plan.plan_clips`).
        out_dir: Output directory (created).
        topics: Topics copied into the MCAP clips (``None``: all).
        recordings: Write the ``.rrd`` of each clip.
        thumbnails: Render a PNG per ``.rrd`` (needs a Vulkan driver; skipped with the reason).
        on_bytes: Progress: bytes of each message copied.
        on_clip: Progress: called once per clip and step (MCAP pass, ``.rrd``, thumbnail).

    Raises:
        WorkbenchError: The directory or the index cannot be written.
        LoaderError: The drive cannot be opened at all.
    """
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        msg = f"{out_dir}: cannot create the export directory ({err.strerror})"
        raise WorkbenchError(msg) from err
    raw = write_raw_clips(
        report,
        plans,
        out_dir,
        map_path=request.map_path,
        write_frames=_frames_writer(request),
        topics=topics,
        on_message=on_bytes,
    )
    bags = write_ros1_bags(raw)
    readable = [p for p, outcome in zip(plans, raw, strict=True) if outcome.written]
    if on_clip is not None:
        for _ in plans:
            on_clip()
    rrds = write_recordings(report, readable, out_dir, request, on_clip) if recordings else {}
    pngs, skipped = write_thumbnails(rrds, on_clip) if thumbnails else ({}, None)
    clips = []
    for plan, outcome in zip(plans, raw, strict=True):
        labels = {} if plan.label is None else {plan.incident.id: plan.label}
        doc = export_openlabel(replace(report, incidents=(plan.incident,)), labels)
        openlabel = out_dir / f"{plan.stem}.openlabel.json"
        write_openlabel(doc, openlabel)
        rrd = rrds.get(plan.stem)
        clips.append(
            ExportedClip(
                plan,
                outcome.request.path if outcome.written else None,
                bags.get(outcome.request.path),
                openlabel,
                None if rrd is None else rrd[0],
                pngs.get(plan.stem),
                outcome.messages,
                outcome.per_topic,
                outcome.reason,
            )
        )
    index_json, index_csv = _write_index(out_dir, clips)
    return ExportSummary(tuple(clips), index_json, index_csv, skipped)
