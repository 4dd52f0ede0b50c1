"""The one progress bar every long CLI command shows (on stderr, gone when done)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from workbench.drives import window_ns

if TYPE_CHECKING:
    from loaders.drive import Drive
    from workbench.viewer.replay import ReplaySummary

__all__ = ["STDERR", "frame_progress", "run_with_progress"]

#: Progress and diagnostics go to stderr so stdout stays machine-readable.
STDERR = Console(stderr=True)


def frame_progress() -> Progress:
    """A transient ``description  bar  done/total  elapsed`` progress display."""
    return Progress(
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=STDERR,
        transient=True,
    )


def run_with_progress(
    drive: Drive,
    *,
    label: str,
    start_s: float | None,
    end_s: float | None,
    **targets: object,
) -> ReplaySummary:
    """Replay ``drive`` with a progress bar on stderr; ``targets`` go to ``replay_drive``."""
    from workbench.viewer.replay import replay_drive  # noqa: PLC0415 - keeps start-up light

    start_ns, end_ns = window_ns(drive, start_s, end_s)
    total = drive.info.frame_count or None
    with frame_progress() as bar:
        task = bar.add_task(label, total=total)
        return replay_drive(
            drive,
            start_ns=start_ns,
            end_ns=end_ns,
            progress=lambda done: bar.update(task, completed=done),
            **targets,  # type: ignore[arg-type]
        )
