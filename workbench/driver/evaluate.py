"""Evaluate one drive: the driver's chunks into per-frame JSON lines and violation intervals."""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from workbench.driver.run import DriveRun, EgoSize
from workbench.sinks.per_frame import PerFrameJsonl
from workbench.sinks.violations import Violation, ViolationDetector

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.errors import LoaderError
    from workbench.engines.base import BoundRunner

__all__ = ["Evaluation", "evaluate_drive"]


@dataclass(frozen=True, slots=True)
class Evaluation:
    """What one evaluation produced.

    Attributes:
        frames: Frames evaluated.
        unsafe_frames: Frames at least one engine rated unsafe.
        unsafe_per_engine: Unsafe frames per engine, in the order the engines ran.
        violations: Violation intervals over those frames.
        stopped_by: The loader error that ended a truncated or corrupted log early, if any;
            everything above covers the frames read before it.
        profiles: The parameter profile each engine's verdicts named (RSS: e.g.
            ``highway``), for the engines whose verdicts name one.
    """

    frames: int
    unsafe_frames: int
    violations: tuple[Violation, ...]
    unsafe_per_engine: Mapping[str, int] = field(default_factory=dict)
    stopped_by: LoaderError | None = None
    profiles: Mapping[str, str] = field(default_factory=dict)


def evaluate_drive(
    drive: Drive,
    engines: Sequence[BoundRunner],
    *,
    start_ns: int | None = None,
    end_ns: int | None = None,
    per_frame: Path | None = None,
    progress: Callable[[int], None] | None = None,
    ego_size: EgoSize | None = None,
) -> Evaluation:
    """Run the engines over every frame of a drive.

    Args:
        drive: An opened drive; the caller closes it.
        engines: Engine runners, each carrying its own state from frame to frame.
        start_ns: Only frames at or after this time.
        end_ns: Only frames before this time.
        per_frame: Write one JSON line per frame here (pinned format of DESIGN.md); the
            file appears whole when the evaluation ends (written beside it, then renamed).
        progress: Called with the number of frames evaluated after each chunk.
        ego_size: The user's ego size for every engine (``--ego-size``).

    Returns:
        The verdicts. A ``LoaderError`` raised while reading (truncated or corrupted log)
        does not lose the frames evaluated before it: it is returned in ``stopped_by``.
    """
    run = DriveRun(drive, engines, start_ns=start_ns, end_ns=end_ns, ego_size=ego_size)
    detector = ViolationDetector(drive.info.path.name)
    with contextlib.ExitStack() as stack:
        lines = stack.enter_context(PerFrameJsonl(per_frame)) if per_frame else None
        for chunk in run:
            if lines is not None:
                lines.add_chunk(chunk)
            detector.add_chunk(chunk)
            if progress is not None:
                progress(detector.frames)
    return Evaluation(
        frames=detector.frames,
        unsafe_frames=detector.unsafe_frames,
        violations=tuple(detector.violations()),
        unsafe_per_engine={n: detector.unsafe_per_engine.get(n, 0) for n in run.engine_names},
        stopped_by=run.stopped_by,
        profiles={n: p for n, p in detector.profiles.items() if p},
    )
