"""What a reviewer opens of a clip: its ``.rrd`` with the review blueprint and a thumbnail.

Each clip's window is cut from one pass over the drive with the same engines and settings
as the incidents were found with (:mod:`workbench.export.recordings`): the engines are warm
from the drive's start, the frames numbered as in the drive, so the clip's incident is the
drive's, with its id and its verdict. The blueprint's time panel selects the incident's frames.
Thumbnails come from one headless viewer for the whole export
(:mod:`workbench.viewer.screenshot`): the scene view alone at the incident's worst frame, framed
on the ego and the incident's objects, highlighted (:mod:`workbench.export.thumbnail`); where
no viewer can run they are skipped with the reason. Both are written as ``<name>.part`` and
renamed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.driver.run import DriveRun
from workbench.errors import WorkbenchError
from workbench.export.recordings import ClipRecording
from workbench.export.thumbnail import ThumbnailView, thumbnail_view
from workbench.replay.blueprint import thumbnail_blueprint
from workbench.viewer.screenshot import ScreenshotUnavailableError, headless_viewer, screenshot

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = [
    "THUMBNAIL_SIZE",
    "write_recordings",
    "write_thumbnails",
]


#: Thumbnail size ``(width, height)`` [px]: the scene view fills it.
THUMBNAIL_SIZE = (1280, 720)


def write_recordings(
    report: IncidentReport,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    request: IncidentRequest,
    on_clip: Callable[[], None] | None = None,
) -> dict[str, tuple[Path, ThumbnailView]]:
    """Write ``<stem>.rrd`` per plan; return ``{stem: (path, what its thumbnail shows)}``.

    One pass evaluates the drive from its first frame to the end of the last clip with the
    request's engines (:mod:`workbench.export.recordings`): each clip's engines are warm from
    the drive's start, its frames numbered as in the drive.

    Raises:
        LoaderError: The drive cannot be read.
        WorkbenchError: A recording cannot be written.
    """
    if not plans:
        return {}
    drive = request.open_drive()
    clips: list[ClipRecording] = []
    try:
        runners, ego = request.engines_for(drive, full_geometry=True)
        specs = [r.spec for r in runners]
        for plan in plans:
            path = out_dir / f"{plan.stem}.rrd"
            clips.append(
                ClipRecording(
                    plan,
                    path,
                    drive,
                    report=report,
                    engines=specs,
                    incident_settings=request.settings,
                )
            )
        end_ns = max(plan.end_ns for plan in plans) + 1
        written = _cut(clips, DriveRun(drive, runners, end_ns=end_ns, ego_size=ego), on_clip)
    except OSError as err:
        for clip in clips:
            clip.abandon()
        msg = f"{out_dir}: cannot write the clips' recordings ({err.strerror})"
        raise WorkbenchError(msg) from err
    except BaseException:
        for clip in clips:
            clip.abandon()
        raise
    finally:
        drive.close()
    return {
        clip.plan.stem: (clip.path, thumbnail_view(report, clip.plan, clip.feed.culprits))
        for clip in written
    }


def _cut(
    clips: Sequence[ClipRecording], run: DriveRun, on_clip: Callable[[], None] | None
) -> list[ClipRecording]:
    """Feed each chunk of the one pass to the clips; finish each once the pass is past it."""
    open_clips = sorted(clips, key=lambda c: c.plan.end_ns)
    written = []
    for chunk in run:
        for clip in open_clips:
            clip.add_chunk(chunk)
        past = chunk.frames[-1].t_ns
        while open_clips and open_clips[0].plan.end_ns <= past:
            written += _finish(open_clips.pop(0), on_clip)
    for clip in open_clips:
        written += _finish(clip, on_clip)
    return written


def _finish(clip: ClipRecording, on_clip: Callable[[], None] | None) -> list[ClipRecording]:
    done = clip.finish()
    if on_clip is not None:
        on_clip()
    return [clip] if done else []


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
