"""A clip of any stretch of a drive, incident or not: ``--window START:END``.

``START`` and ``END`` are seconds from the drive's first frame (``12.5:20``) or frame
numbers as ``workbench incidents`` and the viewer show them (``#250:#400``); both ends are
kept. The clip holds no incident event; its OpenLABEL holds the incidents it overlaps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s, s_to_ns
from workbench.errors import WorkbenchError
from workbench.export.plan import ClipPlan, safe_stem

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport

__all__ = ["Window", "parse_window", "plan_window"]


@dataclass(frozen=True, slots=True)
class Window:
    """A stretch of a drive as given.

    Attributes:
        start: First second (from the drive's first frame) or frame number.
        end: Last second or frame number (inclusive).
        frames: Whether ``start`` and ``end`` are frame numbers (else seconds).
    """

    start: float
    end: float
    frames: bool


def _bound(text: str, spec: str) -> tuple[float, bool]:
    frames = text.startswith("#")
    try:
        value = float(text[1:] if frames else text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or value < 0 or (frames and not value.is_integer()):
        unit = "a frame number" if frames else "seconds"
        msg = f"--window {spec}: {text!r} is not {unit} (e.g. 12.5:20 or #250:#400)"
        raise WorkbenchError(msg)
    return value, frames


def parse_window(spec: str) -> Window:
    """``START:END`` in seconds (``12.5:20``) or frames (``#250:#400``).

    Raises:
        WorkbenchError: Not two bounds of one unit, or the end before the start.
    """
    start_text, sep, end_text = spec.partition(":")
    if not sep:
        msg = f"--window {spec}: give START:END in seconds (12.5:20) or frames (#250:#400)"
        raise WorkbenchError(msg)
    (start, start_frames), (end, end_frames) = _bound(start_text, spec), _bound(end_text, spec)
    if start_frames != end_frames:
        msg = f"--window {spec}: both ends in seconds or both in frames (#250:#400)"
        raise WorkbenchError(msg)
    if end < start:
        raise WorkbenchError(f"--window {spec}: ends before it starts")
    return Window(start, end, start_frames)


def plan_window(report: IncidentReport, window: Window) -> ClipPlan:
    """The clip of ``window``: the drive's frames within it, at least one.

    Raises:
        WorkbenchError: No frame of the drive lies within the window.
    """
    times = report.frame_times
    t0 = times[0][1] if times else report.start_ns
    if window.frames:
        inside = [(i, t) for i, t in times if window.start <= i <= window.end]
    else:
        a, b = t0 + s_to_ns(window.start), t0 + s_to_ns(window.end)
        inside = [(i, t) for i, t in times if a <= t <= b]
    if not inside:
        last = f"#{times[-1][0]}, {ns_to_s(times[-1][1] - t0):.2f} s" if times else "no frame"
        msg = f"{report.log}: no frame within --window (the drive ends at {last})"
        raise WorkbenchError(msg)
    (first, start_ns), (last_frame, end_ns) = inside[0], inside[-1]
    stem = safe_stem(f"window_{first:06d}-{last_frame:06d}")
    return ClipPlan(None, None, stem, start_ns, end_ns, frames=(first, last_frame))
