"""Evaluate one drive: frames through the engines, per-frame JSON lines, violation intervals."""

from __future__ import annotations

import contextlib
import json
from dataclasses import dataclass
from typing import TYPE_CHECKING

from loaders.errors import LoaderError
from workbench.evaluate.pipeline import evaluate_frames
from workbench.evaluate.violations import Violation, detect_violations

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from workbench.evaluate.pipeline import EngineRunner, FrameResult

__all__ = ["Evaluation", "evaluate_drive"]


@dataclass(frozen=True, slots=True)
class Evaluation:
    """What one evaluation produced.

    Attributes:
        results: Per-frame verdicts without geometry, in frame order.
        violations: Violation intervals over those frames.
        stopped_by: The loader error that ended a truncated or corrupted log early, if any;
            everything above covers the frames read before it.
    """

    results: tuple[FrameResult, ...]
    violations: tuple[Violation, ...]
    stopped_by: LoaderError | None = None

    @property
    def unsafe_frames(self) -> int:
        """Frames at least one engine rated unsafe."""
        return sum(1 for r in self.results if not all(o.is_safe for o in r.outputs.values()))


def evaluate_drive(
    drive: Drive,
    engines: Sequence[EngineRunner],
    *,
    start_ns: int | None = None,
    end_ns: int | None = None,
    per_frame: Path | None = None,
    progress: Callable[[], None] | None = None,
) -> Evaluation:
    """Run the engines over every frame of a drive.

    Args:
        drive: An opened drive; the caller closes it.
        engines: Engine runners, each carrying its own state from frame to frame.
        start_ns: Only frames at or after this time.
        end_ns: Only frames before this time.
        per_frame: Write one JSON line per frame here (pinned format of DESIGN.md); the
            file appears whole when the evaluation ends (written beside it, then renamed).
        progress: Called after each frame.

    Returns:
        The verdicts. A ``LoaderError`` raised while reading (truncated or corrupted log)
        does not lose the frames evaluated before it: it is returned in ``stopped_by``.
    """
    results: list[FrameResult] = []
    stopped_by: LoaderError | None = None
    tmp = None if per_frame is None else per_frame.with_name(f".{per_frame.name}.tmp")
    if tmp is not None:
        tmp.parent.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:
        sink = stack.enter_context(tmp.open("w")) if tmp is not None else None
        try:
            for _frame, result in evaluate_frames(drive.frames(start_ns, end_ns), engines):
                results.append(result.without_detail())
                if sink is not None:
                    sink.write(json.dumps(result.record()) + "\n")
                if progress is not None:
                    progress()
        except LoaderError as err:
            stopped_by = err
    if tmp is not None and per_frame is not None:
        tmp.replace(per_frame)
    violations = detect_violations(results, drive.info.path.name)
    return Evaluation(tuple(results), tuple(violations), stopped_by)
