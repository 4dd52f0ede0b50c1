"""``export_clips``: every file of every clip, and the export's index.

Per clip, into the output directory: ``<stem>.mcap`` (the window's messages, the incident
event, the map), ``<stem>.openlabel.json`` (ASAM OpenLABEL 1.0 of the incident and its
label), ``<stem>.rrd`` (the window replayed with the review blueprint) and ``<stem>.png``
(thumbnail at the incident's worst frame); ``<stem>.bag`` and ``<stem>.osm`` beside the
clips of ROS 1 logs. ``clips.json`` and ``clips.csv`` index them. Every file is written as
``<name>.part`` and renamed when complete.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from workbench.annotations.openlabel import export_openlabel, write_openlabel
from workbench.export.index import clear_directory, write_index
from workbench.export.inputs import check_inputs
from workbench.export.raw import map_attachment, write_raw_clips, write_ros1_bags
from workbench.export.views import write_recordings, write_thumbnails

if TYPE_CHECKING:
    from collections.abc import Callable, Collection, Mapping, Sequence
    from pathlib import Path

    from workbench.annotations import Label
    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["ExportSummary", "ExportedClip", "export_clips"]


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
    map_file: Path | None = None

    @property
    def files(self) -> dict[str, Path | None]:
        """Every file of the clip by kind (``None``: not written)."""
        return {
            "mcap": self.mcap,
            "bag": self.bag,
            "map": self.map_file,
            "openlabel": self.openlabel,
            "rrd": self.rrd,
            "png": self.png,
        }

    def record(self, report: IncidentReport) -> dict[str, Any]:
        """The clip's entry in ``clips.json`` (file names relative to the directory)."""
        return {
            "stem": self.plan.stem,
            **self.plan.record(),
            "source": str(report.log) if report.request is None else report.request.location,
            "drive_sha256": report.drive_hash,
            "messages": self.messages,
            "messages_per_topic": dict(sorted(self.per_topic.items())),
            "files": {k: None if v is None else v.name for k, v in self.files.items()},
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
        paths = [p for c in self.clips for p in c.files.values() if p]
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


def _openlabel(
    report: IncidentReport, plan: ClipPlan, windows_labels: Mapping[str, Label]
) -> dict[str, Any]:
    """The clip's OpenLABEL: its incident and label, naming the source drive and the window.

    ``labels import`` of it attaches the label to the source drive (``drive_sha256``).
    """
    if plan.incident is None:  # a window: the incidents it overlaps, with their labels
        held = tuple(
            i for i in report.incidents if i.end_ns >= plan.start_ns and i.start_ns <= plan.end_ns
        )
        labels = {i.id: label for i in held if (label := windows_labels.get(i.id)) is not None}
    else:
        held = (plan.incident,)
        labels = {} if plan.label is None else {plan.incident.id: plan.label}
    doc = export_openlabel(replace(report, incidents=held), labels)
    doc["openlabel"]["metadata"]["clip"] = {
        "incident_id": None if plan.incident is None else plan.incident.id,
        "stem": plan.stem,
        "source": report.log.name,
        "start_ns": plan.start_ns,
        "end_ns": plan.end_ns,
    }
    return doc


def export_clips(
    report: IncidentReport,
    request: IncidentRequest,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    *,
    topics: Collection[str] | None = None,
    recordings: bool = True,
    thumbnails: bool = True,
    force: bool = False,
    without_map: bool = False,
    labels: Mapping[str, Label] | None = None,
    on_bytes: Callable[[int], None] | None = None,
    on_clip: Callable[[], None] | None = None,
) -> ExportSummary:
    """Write every clip of ``plans`` into ``out_dir`` and index them.

    Every file is written as ``<name>.part`` and renamed when complete.

    Args:
        report: The drive's incidents, as found with ``request``.
        request: The drive and settings (re-used to replay the windows).
        plans: The clips (:func:`workbench.export.plan.plan_clips`).
        out_dir: Output directory (created).
        topics: Topics copied into the MCAP clips (``None``: all; each must be in the log).
        recordings: Write the ``.rrd`` of each clip.
        thumbnails: Render a PNG per ``.rrd`` (needs a Vulkan driver; skipped with the reason).
        force: Replace an earlier export in ``out_dir`` (else refuse).
        without_map: Export a damaged log whose map cannot be read (else refuse).
        labels: The drive's labels by incident id, for the OpenLABEL of a window
            (``--window``), which holds the incidents it overlaps.
        on_bytes: Progress: bytes of each message copied.
        on_clip: Progress: called once per clip and step (MCAP pass, ``.rrd``, thumbnail).

    Raises:
        WorkbenchError: An unknown topic, a damaged log without its map, a directory that
            holds an earlier export (without ``force``) or cannot be written.
        LoaderError: The drive cannot be opened at all.
    """
    labels = labels or {}
    check_inputs(report, request, topics, without_map=without_map)
    clear_directory(out_dir, force=force)
    raw = write_raw_clips(
        report,
        plans,
        out_dir,
        map_path=request.map_path,
        write_frames=_frames_writer(request),
        topics=topics,
        on_message=on_bytes,
    )
    bags = write_ros1_bags(raw, map_attachment(report.log, request.map_path))
    readable = [p for p, outcome in zip(plans, raw, strict=True) if outcome.written]
    if on_clip is not None:
        for _ in plans:
            on_clip()
    rrds = write_recordings(report, readable, out_dir, request, on_clip) if recordings else {}
    pngs, skipped = write_thumbnails(rrds, on_clip) if thumbnails else ({}, None)
    clips = []
    for plan, outcome in zip(plans, raw, strict=True):
        openlabel = out_dir / f"{plan.stem}.openlabel.json"
        write_openlabel(_openlabel(report, plan, labels), openlabel)
        rrd = rrds.get(plan.stem)
        bag, beside = bags.get(outcome.request.path, (None, None))
        clips.append(
            ExportedClip(
                plan,
                outcome.request.path if outcome.written else None,
                bag,
                openlabel,
                None if rrd is None else rrd[0],
                pngs.get(plan.stem),
                outcome.messages,
                outcome.per_topic,
                outcome.reason,
                beside,
            )
        )
    index_json, index_csv = write_index(out_dir, [c.record(report) for c in clips])
    return ExportSummary(tuple(clips), index_json, index_csv, skipped)
