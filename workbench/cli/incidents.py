"""``workbench incidents``: a drive's incidents, worst first, as a table or a file."""

from __future__ import annotations

import math
from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer
from rich.table import Table

from workbench.cli.incident_options import (
    CauseFilter,
    EngineFilter,
    LogArgument,
    MarginFilter,
    ObjectFilter,
    with_incidents,
)
from workbench.cli.tables import print_table

if TYPE_CHECKING:
    from workbench.incidents import Incident, IncidentReport

__all__ = ["incident_table", "register"]


#: Object ids longer than this are shortened in the table.
_SHORT_ID = 12


def _short(object_id: str) -> str:
    """Long (UUID-like) object ids shortened for the table; files keep them whole."""
    return object_id if len(object_id) <= _SHORT_ID else f"{object_id[:4]}…{object_id[-6:]}"


def incident_table(incidents: list[Incident], t0_ns: int, title: str) -> Table:
    """Rich table of incidents in the given order."""
    table = Table(title=title)
    table.add_column("id", no_wrap=True)
    for column in ("engine", "object", "cause", "frames", "start s", "dur s", "unsafe", "margin"):
        table.add_column(column)
    for i in incidents:
        margin = i.severity.worst_margin
        table.add_row(
            i.id,
            i.engine,
            " ".join(_short(o) for o in i.objects) or "-",
            i.cause,
            f"{i.start_frame}-{i.end_frame}",
            f"{(i.start_ns - t0_ns) / 1e9:.2f}",
            f"{i.duration_s:.2f}",
            str(i.severity.unsafe_frames),
            f"{margin:.2f}" if math.isfinite(margin) else "-",
        )
    return table


@with_incidents
def incidents(
    log: LogArgument,
    report: IncidentReport,
    *,
    engine: EngineFilter = None,
    obj: ObjectFilter = None,
    cause: CauseFilter = None,
    max_margin: MarginFilter = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Write them (.json, .csv or .parquet).")
    ] = None,
) -> None:
    """List a drive's incidents (unsafe runs per engine, object and cause), worst first."""
    from workbench.incidents import filter_incidents, write_incidents  # noqa: PLC0415
    from workbench.quality.output import write_quality  # noqa: PLC0415

    found = filter_incidents(
        report.incidents,
        engines=engine or (),
        objects=obj or (),
        causes=cause or (),
        max_margin=max_margin,
    )
    title = f"{log.name}: {len(found)} of {len(report.incidents)} incident(s), worst first"
    print_table(incident_table(found, report.start_ns, title))
    if out is not None:
        write_incidents(found, out)
        typer.echo(f"wrote {out}")
        typer.echo(f"wrote {write_quality(report.findings, found, out)} (data quality)")
    if report.stopped_by is not None:
        typer.echo(f"stopped early: the incidents cover {len(report.frame_times)} frames")
        raise report.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``incidents`` to the CLI (a batch's RESULTS_DIR lists every drive's incidents)."""
    from workbench.cli.fleet import fleet_incidents, on_results  # noqa: PLC0415

    app.command("incidents")(on_results(fleet_incidents)(incidents))
