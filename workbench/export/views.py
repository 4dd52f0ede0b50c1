"""What a reviewer opens of a clip: its ``.rrd`` with the review blueprint and a thumbnail.

Each clip's window is replayed with the same engines and settings as the incidents were
found with, numbered with the drive's frame numbers. The engines start warm: they evaluate
a lead-in of up to :data:`LEAD_IN_NS` before the window (not shown), so that their memory
(RSS responses) at the window's start is the drive's and the clip's incident is the drive's,
with its id and its verdict. The blueprint's time panel selects the incident's frames.
Thumbnails come from one headless viewer for the whole export
(:mod:`workbench.viewer.screenshot`): the scene view alone at the incident's worst frame, framed
on the ego and the incident's objects, highlighted (:mod:`workbench.export.thumbnail`); where
no viewer can run they are skipped with the reason. Both are written as ``<name>.part`` and
renamed.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError
from workbench.export.thumbnail import ThumbnailView, thumbnail_view
from workbench.outputs import part_path
from workbench.replay.blueprint import thumbnail_blueprint
from workbench.replay.highlight import CulpritBoxes
from workbench.replay.incidents import short_labels
from workbench.viewer.replay import replay_drive
from workbench.viewer.screenshot import ScreenshotUnavailableError, headless_viewer, screenshot

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = [
    "LEAD_IN_NS",
    "THUMBNAIL_SIZE",
    "incident_focus_m",
    "lead_in",
    "write_recordings",
    "write_thumbnails",
]


#: Thumbnail size ``(width, height)`` [px]: the scene view fills it.
THUMBNAIL_SIZE = (1280, 720)
#: Longest lead-in evaluated before a clip's window to warm the engines up [ns].
LEAD_IN_NS = 10_000_000_000


def incident_focus_m(
    report: IncidentReport, plan: ClipPlan
) -> tuple[tuple[float, float], list[tuple[float, float]]] | None:
    """Ego and incident objects' positions ``(x, y)`` [m] at the incident's first frame.

    ``None`` for a window without incident, or when the detector recorded no position.
    """
    incident = plan.incident
    if incident is None or incident.start_frame not in report.ego_at_start_m:
        return None
    objects = report.objects_at_start_m.get(incident.start_frame, {})
    ego = report.ego_at_start_m[incident.start_frame]
    return ego, [xy for oid, xy in sorted(objects.items()) if oid in incident.objects]


def lead_in(report: IncidentReport, start_ns: int) -> tuple[int, int]:
    """``(lead-in start [ns], drive frame number of its first frame)`` for a window start."""
    times = report.frame_times
    earliest = start_ns - LEAD_IN_NS
    first = next(((i, t) for i, t in times if t >= earliest), None)
    return (first[1], first[0]) if first is not None else (start_ns, 0)


def _record(path: Path, replay: Callable[..., object]) -> bool:
    """Run ``replay(out=part)``, rename the part into place; ``False``: it wrote nothing."""
    part = part_path(path)
    try:
        replay(out=part)
        if not part.is_file():  # no frame in the window
            return False
        part.replace(path)
    except OSError as err:
        part.unlink(missing_ok=True)
        msg = f"{path}: cannot write the clip's recording ({err.strerror})"
        raise WorkbenchError(msg) from err
    except BaseException:
        part.unlink(missing_ok=True)
        raise
    return True


def write_recordings(
    report: IncidentReport,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    request: IncidentRequest,
    on_clip: Callable[[], None] | None = None,
) -> dict[str, tuple[Path, ThumbnailView]]:
    """Write ``<stem>.rrd`` per plan; return ``{stem: (path, what its thumbnail shows)}``.

    Raises:
        LoaderError: The drive cannot be read.
        WorkbenchError: A recording cannot be written.
    """
    written: dict[str, tuple[Path, ThumbnailView]] = {}
    drive = request.open_drive()  # once: the map is read once for every window
    try:
        for plan in plans:
            incident = plan.incident
            selection = plan.frames or (0, 0)
            if incident is not None:
                selection = (incident.start_frame, incident.end_frame)
            runners, ego = request.engines_for(drive, full_geometry=True)
            lead_start_ns, offset = lead_in(report, plan.start_ns)
            label = plan.label
            verdicts = {} if incident is None or label is None else {incident.id: label.verdict}
            path = out_dir / f"{plan.stem}.rrd"
            culprits = CulpritBoxes()
            replay = functools.partial(
                replay_drive,
                drive,
                start_ns=lead_start_ns,
                end_ns=plan.end_ns + 1,
                engines=runners,
                ego_size=ego,
                incident_settings=request.settings,
                verdicts=verdicts,
                selection=selection,
                lead_in=(plan.start_ns, offset),
                focus_m=incident_focus_m(report, plan),
                culprits=culprits,
                labels=short_labels(report.incidents),
            )
            if _record(path, replay):
                written[plan.stem] = (path, thumbnail_view(report, plan, culprits))
            if on_clip is not None:
                on_clip()
    finally:
        drive.close()
    return written


def write_thumbnails(
    recordings: dict[str, tuple[Path, ThumbnailView]],
    on_clip: Callable[[], None] | None = None,
) -> tuple[dict[str, Path], str | None]:
    """``<stem>.png`` beside each recording: the scene at the incident's worst frame.

    Args:
        recordings: ``{stem: (rrd, thumbnail)}`` (:func:`write_recordings`).
        on_clip: Progress: called once per thumbnail.

    Returns:
        The thumbnails by stem, and why there are none (``None`` when rendered).
    """
    thumbnails: dict[str, Path] = {}
    if not recordings:
        return thumbnails, None
    try:
        with headless_viewer(THUMBNAIL_SIZE) as viewer:
            for stem, (rrd, view) in recordings.items():
                blueprint = None
                if view.eye is not None:
                    blueprint = thumbnail_blueprint(view.incident, view.eye)
                png = rrd.with_suffix(".png")
                part = png.with_name(f"{png.stem}.part.png")  # the viewer writes .png only
                try:
                    screenshot(viewer, rrd, part, view.frame, blueprint=blueprint)
                    part.replace(png)
                finally:
                    part.unlink(missing_ok=True)
                thumbnails[stem] = png
                if on_clip is not None:
                    on_clip()
    except ScreenshotUnavailableError as err:
        return thumbnails, str(err)
    return thumbnails, None
