"""What an export needs from its log, checked before any clip is cut.

- ``--topics``: every topic named must be in the log (a misspelt topic would otherwise give
  clips of the other topics, or none, without a word).
- The map: a log whose map cannot be read although it is damaged (a truncated MCAP loses
  its map attachment, written at the end) would give clips whose incidents differ from the
  drive's. The export refuses it unless a map is given (``--map``) or the user asks to go on
  without one.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError
from workbench.export.raw import MESSAGE_LOG_SUFFIXES

if TYPE_CHECKING:
    from collections.abc import Collection

    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["check_inputs"]

#: Topics named in the error when listing what the log has.
_NAMED = 8


def check_inputs(
    report: IncidentReport,
    request: IncidentRequest,
    topics: Collection[str] | None,
    *,
    without_map: bool,
) -> str | None:
    """Check the chosen topics and the map of the log; say where the map comes from.

    Args:
        report: The drive's incidents (``stopped_by`` tells a damaged log).
        request: The drive and its settings.
        topics: The ``--topics`` chosen (``None``: all).
        without_map: Go on when the map of a damaged log cannot be read.

    Returns:
        Where the clips' map comes from (``None``: no map).

    Raises:
        WorkbenchError: An unknown topic, or a damaged log without a readable map.
        LoaderError: The drive cannot be opened.
    """
    drive = request.open_drive()
    try:
        info = drive.info
        has_map = drive.lane_map is not None
    finally:
        drive.close()
    log = report.log
    if topics and (log.is_dir() or log.suffix.lower() in MESSAGE_LOG_SUFFIXES):
        known = {t.topic for t in info.topics}
        unknown = sorted(set(topics) - known)
        if unknown:
            some = ", ".join(sorted(known)[:_NAMED]) + (", ..." if len(known) > _NAMED else "")
            msg = f"{log}: no topic {', '.join(unknown)} in the log (it has {some})"
            raise WorkbenchError(msg)
    if not has_map and report.stopped_by is not None and not without_map:
        msg = (
            f"{log}: no map could be read (the log is damaged: an MCAP's map attachment is "
            "written at its end); give it with --map FILE, or export without a map with "
            "--without-map"
        )
        raise WorkbenchError(msg)
    return info.map_source if has_map else None
