"""RESULTS_DIR for the single-drive commands: the hook and the fleet listing of ``incidents``.

A command registered through :func:`on_results` takes a batch's results directory wherever
it takes a drive; its fleet variant reads the batch's tables and never evaluates again.
"""

from __future__ import annotations

import functools
import inspect
import math
from typing import TYPE_CHECKING, Any

import typer
from rich.console import Console
from rich.table import Table

from loaders.timebase import ns_to_s
from workbench.batch.results import is_results_dir

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

    from workbench.batch.queue import FleetIncident

__all__ = ["each_drive", "fleet_incidents", "fleet_table", "on_results"]


def on_results(
    fleet: Callable[..., None],
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Route a command to ``fleet`` (same keyword arguments) when ``log`` is a results dir."""

    def wrap(command: Callable[..., None]) -> Callable[..., None]:
        @functools.wraps(command)
        def run(**kwargs: Any) -> None:
            if is_results_dir(kwargs["log"]):
                fleet(**kwargs)
            else:
                command(**kwargs)

        return run

    return wrap


def fleet_table(queue: list[FleetIncident], title: str) -> Table:
    """Rich table of a batch's incidents in the given order, with their drives."""
    from workbench.batch.queue import drive_name  # noqa: PLC0415

    table = Table(title=title)
    table.add_column("drive", no_wrap=True, max_width=20, overflow="ellipsis")
    table.add_column("id", no_wrap=True)
    table.add_column("engine", no_wrap=True)
    table.add_column("object", no_wrap=True, max_width=10, overflow="ellipsis")
    table.add_column("cause", ratio=1, min_width=10)
    for column in ("start s", "dur s", "margin"):
        table.add_column(column, no_wrap=True, justify="right")
    for item in queue:
        i = item.incident
        margin = i.severity.worst_margin
        table.add_row(
            drive_name(item.drive_path),
            i.id,
            i.engine,
            " ".join(i.objects) or "-",
            i.cause,
            f"{ns_to_s(i.start_ns - item.drive_start_ns):.2f}",
            f"{i.duration_s:.2f}",
            f"{margin:.2f}" if math.isfinite(margin) else "-",
        )
    return table


def fleet_incidents(
    *,
    log: Path,
    engine: list[str] | None = None,
    obj: list[str] | None = None,
    cause: list[str] | None = None,
    max_margin: float | None = None,
    out: Path | None = None,
    **_settings: Any,
) -> None:
    """``workbench incidents RESULTS_DIR``: every drive's incidents, worst first."""
    from workbench.batch.queue import load_queue, write_queue  # noqa: PLC0415
    from workbench.incidents import filter_incidents  # noqa: PLC0415

    queue = load_queue(log)
    kept = {
        id(i)
        for i in filter_incidents(
            [f.incident for f in queue],
            engines=engine or (),
            objects=obj or (),
            causes=cause or (),
            max_margin=max_margin,
        )
    }
    found = [f for f in queue if id(f.incident) in kept]
    drives = len({f.drive_path for f in found})
    title = (
        f"{log.name}: {len(found)} of {len(queue)} incident(s) in {drives} drive(s), worst first"
    )
    Console().print(fleet_table(found, title))
    if out is not None:
        write_queue(found, out)
        typer.echo(f"wrote {out}")


def each_drive(
    command: Callable[..., None],
    out_for: Callable[[Path, str], Path] | None,
    *,
    incidents_only: bool,
) -> Callable[..., None]:
    """``command`` (made by ``with_incidents``) taking RESULTS_DIR too: run once per drive.

    For a results directory the command's own function runs on each drive's report read
    back from the batch (nothing is evaluated again), with ``--out`` replaced by
    ``out_for(out, drive stem)``; the incident options are the batch's.

    Args:
        command: The decorated command (its ``__wrapped__`` is the command's own function).
        out_for: Where one drive's output goes, from ``--out`` and a portable drive stem
            (``None``: the command has no ``--out``).
        incidents_only: Skip drives without incidents.
    """
    own = command.__wrapped__  # type: ignore[attr-defined]
    names = set(inspect.signature(own).parameters) - {"log", "report"}

    def fleet(**kwargs: Any) -> None:
        from workbench.batch.reports import drive_reports  # noqa: PLC0415
        from workbench.export.plan import safe_stem  # noqa: PLC0415

        base = {name: kwargs[name] for name in names}
        reports = drive_reports(kwargs["log"], with_incidents_only=incidents_only)
        for report in reports:
            if out_for is not None:
                stem = f"{safe_stem(report.log.name)}-{report.drive_hash[:8]}"
                base["out"] = out_for(kwargs["out"], stem)
            own(log=report.log, report=report, **base)

    return on_results(fleet)(command)
