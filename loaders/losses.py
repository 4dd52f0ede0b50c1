"""Accounting of what a drive did not turn into frames: every dropped or ignored message.

The readers record counts in ``DriveInfo.notes`` under the keys of :data:`LOSS_NOTES`;
:func:`loss_summary` makes the one line the CLI prints after ``info``, ``evaluate`` and
``replay``, :func:`loss_details` the lines ``--verbose`` adds. :func:`count_frames` tells
exactly how many frames ``Drive.frames()`` will yield and fills the same loss notes
(``info`` and ``evaluate`` agree on both).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.message_logs.log_drive import LogDrive

if TYPE_CHECKING:
    from loaders.drive import Drive

__all__ = ["LOSS_NOTES", "count_frames", "loss_details", "loss_summary"]

#: Note key -> (what was left out, why); the note's value is a count or a list of topics.
LOSS_NOTES: dict[str, tuple[str, str]] = {
    "skipped_out_of_order_ego": (
        "ego messages dropped",
        (
            "time not after the previous ego message (equal log times; a profile with "
            'clock = "header" uses the header stamps instead)'
        ),
    ),
    "skipped_invalid_ego": ("ego messages dropped", "non-finite pose (invalid_ego = skip)"),
    "ego_messages_without_pose": (
        "ego-topic messages without an ego pose",
        (
            "/tf messages moving other frames only, or whose chain does not reach the map "
            "or odom frame; NavSatFix messages without a fix (status < 0)"
        ),
    ),
    "unused_object_messages": (
        "object messages used by no frame",
        (
            "replaced by a newer one before the next ego message, older than the match "
            "tolerance, or after the last ego message"
        ),
    ),
    "unused_plan_messages": (
        "plan messages used by no frame",
        "replaced by a newer plan before the next ego message, or after the last one",
    ),
    "ignored_markers": (
        "markers ignored",
        (
            "MarkerArray markers other than ADD/MODIFY cubes (text, arrows, lines, "
            "DELETE/DELETEALL): only boxes are objects"
        ),
    ),
    "first_detections_at_rest": (
        "first detections taken at rest",
        (
            "objects of a type without velocity seen for the first time whose next message "
            "came after the frame was emitted (or never): velocity 0 assumed"
        ),
    ),
    "ignored_service_channels": (
        "service-event channels ignored",
        "recorded service calls, never a drive topic",
    ),
}


def _count(value: str) -> int:
    return int(value) if value.isdigit() else len([v for v in value.split(",") if v.strip()])


def _singular(what: str) -> str:
    for plural in ("messages", "channels", "markers", "detections"):
        what = what.replace(plural, plural[:-1], 1)
    return what


def loss_summary(notes: dict[str, str]) -> str | None:
    """One line naming every kind of loss with its count, or ``None`` when nothing was lost."""
    parts = []
    for key, (what, _) in LOSS_NOTES.items():
        if key in notes:
            count = _count(notes[key])
            parts.append(f"{count} {_singular(what) if count == 1 else what}")
    if not parts:
        return None
    return "not in any frame: " + "; ".join(parts) + " (details: --verbose)"


def loss_details(notes: dict[str, str]) -> list[str]:
    """One line per kind of loss: what, the count or topics, and why."""
    return [
        f"{what}: {notes[key]} ({why})" for key, (what, why) in LOSS_NOTES.items() if key in notes
    ]


def count_frames(drive: Drive) -> int:
    """The exact number of frames ``drive.frames()`` yields over its open window.

    Message logs are counted by a pass over the role topics without the engines (the losses
    it finds are recorded in ``drive.info.notes``, the same ``evaluate`` reports); other
    drives know their count.

    Raises:
        LoaderError: The ego topic cannot be read to the end (after counting what could).
    """
    if isinstance(drive, LogDrive):
        return drive.count_frames()
    return drive.info.frame_count
