"""What a reviewer opens of a clip: its ``.rrd`` with the review blueprint and a thumbnail.

Each clip's window is replayed with the same engines and settings as the incidents were
found with; the blueprint's time panel selects the incident's frames. Thumbnails come from
one headless viewer for the whole export (:mod:`workbench.viewer.screenshot`), at the
incident's first frame; where no viewer can run they are skipped with the reason.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.viewer.replay import replay_drive
from workbench.viewer.screenshot import ScreenshotUnavailableError, headless_viewer, screenshot

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["write_recordings", "write_thumbnails"]


def _selection(plan: ClipPlan, report: IncidentReport, first_index: int) -> tuple[int, int]:
    """The incident's frames in the numbering of the clip's replay."""
    times = [t for _, t in report.frame_times if t >= plan.start_ns]
    before_start = sum(1 for t in times if t < plan.incident.start_ns)
    before_end = sum(1 for t in times if t <= plan.incident.end_ns)
    return first_index + before_start, first_index + max(before_start, before_end - 1)


def write_recordings(
    report: IncidentReport,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    request: IncidentRequest,
    on_clip: Callable[[], None] | None = None,
) -> dict[str, tuple[Path, tuple[int, int]]]:
    """Write ``<stem>.rrd`` per plan; return ``{stem: (path, incident frames)}``.

    Raises:
        LoaderError: The drive cannot be read.
    """
    written: dict[str, tuple[Path, tuple[int, int]]] = {}
    drive = request.open_drive()  # once: the map is read once for every window
    try:
        for plan in plans:
            first = next(iter(drive.frames(plan.start_ns, plan.end_ns + 1)), None)
            if first is not None:
                selection = _selection(plan, report, first.index)
                path = out_dir / f"{plan.stem}.rrd"
                runners, ego = request.engines_for(drive, full_geometry=True)
                replay_drive(
                    drive,
                    out=path,
                    start_ns=plan.start_ns,
                    end_ns=plan.end_ns + 1,
                    engines=runners,
                    ego_size=ego,
                    incident_settings=request.settings,
                    verdicts={} if plan.label is None else {plan.incident.id: plan.label.verdict},
                    selection=selection,
                )
                if path.is_file():
                    written[plan.stem] = (path, selection)
            if on_clip is not None:
                on_clip()
    finally:
        drive.close()
    return written


def write_thumbnails(
    recordings: dict[str, tuple[Path, tuple[int, int]]],
    on_clip: Callable[[], None] | None = None,
) -> tuple[dict[str, Path], str | None]:
    """``<stem>.png`` beside each recording at the incident's first frame.

    Returns:
        The thumbnails by stem, and why there are none (``None`` when rendered).
    """
    thumbnails: dict[str, Path] = {}
    if not recordings:
        return thumbnails, None
    try:
        with headless_viewer((1280, 720)) as viewer:
            for stem, (rrd, (first, _)) in recordings.items():
                png = rrd.with_suffix(".png")
                screenshot(viewer, rrd, png, first)
                thumbnails[stem] = png
                if on_clip is not None:
                    on_clip()
    except ScreenshotUnavailableError as err:
        return thumbnails, str(err)
    return thumbnails, None
