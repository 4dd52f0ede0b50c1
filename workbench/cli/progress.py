"""The one progress bar every long CLI command shows (on stderr, gone when done)."""

from __future__ import annotations

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

__all__ = ["STDERR", "frame_progress"]

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
