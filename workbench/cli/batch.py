"""``workbench batch``: evaluate many drives into one results directory (docs/fleet.md)."""

from __future__ import annotations

from collections.abc import Callable  # noqa: TC003 - typer reads the annotations at run time
from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TextColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from workbench.cli.incident_options import with_requests
from workbench.cli.progress import STDERR

if TYPE_CHECKING:
    from workbench.batch.run import BatchSummary
    from workbench.incidents import IncidentRequest

__all__ = ["register"]

CLUSTER_HELP = (
    "Run on tcp://HOST:PORT (a Dask scheduler), dask-local:N, ray://HOST:PORT or ray-local:N"
    " (default: a local process pool)."
)


class _Rate(ProgressColumn):
    """Logs per second so far."""

    def render(self, task: Task) -> Text:
        """``1.23 logs/s``."""
        elapsed = task.elapsed or 0.0
        rate = task.completed / elapsed if elapsed > 0 else 0.0
        return Text(f"{rate:.2f} logs/s")


def _progress() -> Progress:
    return Progress(
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        _Rate(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=STDERR,
        transient=True,
    )


def _summary(summary: BatchSummary, out: Path) -> None:
    counts = {
        s: sum(d["status"] == s for d in summary.drives)
        for s in ("ok", "partial", "empty", "failed")
    }
    incidents = sum(int(d["incidents"]) for d in summary.drives)
    typer.echo(
        f"{len(summary.drives)} log(s) on {summary.executor}: {summary.evaluated} evaluated,"
        f" {summary.skipped} kept from an earlier run; "
        + ", ".join(f"{n} {s}" for s, n in counts.items())
        + f"; {incidents} incident(s) -> {out}"
    )
    for drive in summary.drives:
        if drive["status"] in {"failed", "partial"}:
            typer.echo(f"{drive['status']}: {drive['error'] or drive['path']}")


@with_requests
def batch(
    logs: Annotated[
        list[str], typer.Argument(help="Drives, directories (searched) or glob patterns.")
    ],
    request: Callable[[Path], IncidentRequest],
    *,
    out: Annotated[Path, typer.Option("--out", help="Results directory (resumable).")],
    jobs: Annotated[
        int | None,
        typer.Option("--jobs", min=1, help="Local worker processes (default: CPU count)."),
    ] = None,
    cluster: Annotated[str | None, typer.Option("--cluster", help=CLUSTER_HELP)] = None,
) -> None:
    """Evaluate many drives (one task each) into RESULTS: incidents, drives, batch.json."""
    from workbench.batch.executors import open_pool  # noqa: PLC0415 - light start-up
    from workbench.batch.run import expand_logs, run_batch  # noqa: PLC0415

    paths = expand_logs(logs)
    requests = [request(path) for path in paths]
    with _progress() as bar, open_pool(cluster, jobs) as pool:
        task = bar.add_task("batch", total=len(requests))

        def started(todo: int, kept: int) -> None:
            bar.update(task, total=todo, description=f"batch ({kept} kept)" if kept else "batch")

        def done(_record: dict[str, Any]) -> None:
            bar.advance(task)

        summary = run_batch(requests, out, pool, on_start=started, on_done=done)
    _summary(summary, out)


def register(app: typer.Typer) -> None:
    """Add ``batch`` to the CLI."""
    app.command("batch")(batch)
