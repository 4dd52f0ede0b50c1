"""The MCAP clip of each plan: the log's own messages, or the workbench's frame messages.

Message logs (MCAP, ROS 1 bag, rosbag2, bare ``.db3``) are cut with
:func:`loaders.clips.write_clips`: raw records copied, one pass for all clips. Drives that
are not message logs (CommonRoad, ScenarioArchitect) are first written as a ROS 2 MCAP of
the workbench's own frame messages over the clips' span
(:func:`workbench.samples.drive_mcap.write_drive_mcap`) and cut from there.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

from loaders.clips import ClipRequest, write_clips, write_ros1_bag
from loaders.message_logs.mapsource import sidecar_map
from loaders.open import is_rosbag2_dir
from workbench.outputs import atomic_output, json_text

if TYPE_CHECKING:
    from collections.abc import Callable, Collection, Sequence

    from loaders.clips import ClipOutcome, MapAttachment
    from workbench.export.plan import ClipPlan
    from workbench.incidents import IncidentReport

__all__ = ["MESSAGE_LOG_SUFFIXES", "map_attachment", "write_raw_clips", "write_ros1_bags"]

#: Inputs whose own messages are copied into the clips.
MESSAGE_LOG_SUFFIXES = frozenset({".mcap", ".bag", ".db3"})
_MEDIA_TYPES = {".osm": "application/vnd.openstreetmap.data+xml", ".xodr": "application/xml"}


def map_attachment(log: Path, explicit: Path | None) -> MapAttachment | None:
    """The map file given (``--map``) or lying beside the log, as an attachment.

    Its create time is the file's modification time, so that exporting the same files
    again gives the same bytes.
    """
    path = explicit or (sidecar_map(log) if log.exists() else None)
    if path is None or not path.is_file():
        return None
    media_type = _MEDIA_TYPES.get(path.suffix.lower(), "application/xml")
    return (path.name, media_type, path.read_bytes(), path.stat().st_mtime_ns)


def _requests(
    plans: Sequence[ClipPlan], out_dir: Path, report: IncidentReport
) -> list[ClipRequest]:
    drive = {
        "log": report.log.name,
        "drive_sha256": report.drive_hash,
        "settings": json_text(report.settings, sort_keys=True),
    }
    requests = []
    for p in plans:
        event = p.event()  # the event message and the metadata record carry the same pairs
        metadata = {"drive": drive, "incident": event} if event else {"drive": drive}
        span = None if p.incident is None else (p.incident.start_ns, p.incident.end_ns)
        requests.append(
            ClipRequest(out_dir / f"{p.stem}.mcap", p.start_ns, p.end_ns, event, metadata, span)
        )
    return requests


def write_raw_clips(
    report: IncidentReport,
    plans: Sequence[ClipPlan],
    out_dir: Path,
    *,
    map_path: Path | None,
    write_frames: Callable[[Path, int, int], None],
    topics: Collection[str] | None = None,
    on_message: Callable[[int], None] | None = None,
) -> list[ClipOutcome]:
    """Write ``<stem>.mcap`` for every plan into ``out_dir``.

    Args:
        report: The drive's incidents (log, content hash, settings).
        plans: The clips.
        out_dir: Output directory (exists).
        map_path: The ``--map`` file, attached to every clip (else the map beside the log).
        write_frames: For drives that are not message logs: ``write_frames(path, start_ns,
            end_ns)`` writes the drive's frames of that span as a ROS 2 MCAP at ``path``.
        topics: Topics to copy (``None``: all).
        on_message: Progress, with each copied message's size in bytes.

    Returns:
        One outcome per plan.
    """
    log = report.log
    requests = _requests(plans, out_dir, report)
    attachment = map_attachment(log, map_path)
    if log.suffix.lower() in MESSAGE_LOG_SUFFIXES or is_rosbag2_dir(log):
        return write_clips(log, requests, topics=topics, map_file=attachment, on_message=on_message)
    start = min(p.start_ns for p in plans)
    end = max(p.end_ns for p in plans)
    with tempfile.TemporaryDirectory(prefix=".frames-", dir=out_dir) as tmp:
        frames_log = Path(tmp) / f"{log.stem}.mcap"
        write_frames(frames_log, start, end)
        return write_clips(
            frames_log,
            requests,
            topics=topics,
            map_file=attachment,
            source_name=log.name,
            on_message=on_message,
        )


def write_ros1_bags(
    outcomes: Sequence[ClipOutcome], map_file: MapAttachment | None
) -> dict[Path, tuple[Path, Path | None]]:
    """``<stem>.bag`` beside every written ``ros1`` clip (rosbags reads no ROS 1 MCAP).

    A bag holds no attachment: the map is written beside it as ``<stem><map suffix>``
    (``<stem>.osm``), where the workbench looks for a log's map.

    Returns:
        The bag and its map file (``None``: no map) of each MCAP clip that has one.
    """
    bags: dict[Path, tuple[Path, Path | None]] = {}
    for outcome in outcomes:
        if outcome.written and outcome.profile == "ros1":
            clip = outcome.request.path
            bag = clip.with_suffix(".bag")
            write_ros1_bag(clip, bag)  # itself written as <bag>.part and renamed
            beside = None
            if map_file is not None:
                beside = clip.with_suffix(Path(map_file[0]).suffix or ".osm")
                with atomic_output(beside, "the clip's map") as part:
                    part.write_bytes(map_file[2])
            bags[clip] = (bag, beside)
    return bags
