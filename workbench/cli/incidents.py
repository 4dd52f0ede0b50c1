"""``workbench incidents``: a drive's events or incidents, most severe first, as a table or a file.

The order is :func:`workbench.incidents.order.severity_key` (docs/review.md, "Severity order").
"""

from __future__ import annotations

import math
from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer
from rich.table import Table

from loaders.timebase import ns_to_s
from workbench.cli.incident_options import (
    ByOption,
    CauseFilter,
    EngineFilter,
    Listing,
    LogArgument,
    MarginFilter,
    ObjectFilter,
    with_incidents,
)
from workbench.cli.tables import print_table

if TYPE_CHECKING:
    from workbench.incidents import Event, Incident, IncidentReport

__all__ = ["event_table", "incident_table", "register"]


#: Object ids longer than this are shortened in the table.
_SHORT_ID = 12


def _short(object_id: str) -> str:
    """Long (UUID-like) object ids shortened for the table; files keep them whole."""
    return object_id if len(object_id) <= _SHORT_ID else f"{object_id[:4]}…{object_id[-6:]}"


#: The physical columns of both tables: heading and fact name.
_PHYSICAL = (
    ("crit", "criticality"),
    ("gap m", "gap_min_m"),
    ("ttc s", "path_ttc_min_s"),
    ("close m/s", "closing_speed_max_mps"),
)


def _physical(incident: Incident) -> list[str]:
    from workbench.incidents.order import rank  # noqa: PLC0415 - light start-up

    facts = {**incident.severity.facts, **rank(incident)}
    cells = []
    for _, name in _PHYSICAL:
        value = facts.get(name)
        cells.append(f"{value:.2f}" if isinstance(value, int | float) else "-")
    if incident.data_suspect:
        cells[0] += " suspect"
    return cells


def incident_table(incidents: list[Incident], t0_ns: int, title: str) -> Table:
    """Rich table of incidents in the given order."""
    table = Table(title=title)
    table.add_column("id", no_wrap=True)
    for column in ("engine", "object", "cause", "frames", "start s", "dur s", "unsafe", "margin"):
        table.add_column(column)
    for heading, _ in _PHYSICAL:
        table.add_column(heading)
    for i in incidents:
        margin = i.severity.worst_margin
        table.add_row(
            i.id,
            i.engine,
            " ".join(_short(o) for o in i.objects) or "-",
            i.cause,
            f"{i.start_frame}-{i.end_frame}",
            f"{ns_to_s(i.start_ns - t0_ns):.2f}",
            f"{i.duration_s:.2f}",
            str(i.severity.unsafe_frames),
            f"{margin:.2f}" if math.isfinite(margin) else "-",
            *_physical(i),
        )
    return table


def event_table(events: list[Event], t0_ns: int, title: str) -> Table:
    """Rich table of events in the given order (facts: the most severe incident's)."""
    table = Table(title=title)
    table.add_column("event", no_wrap=True)
    for column in ("engines", "object", "frames", "start s", "dur s", "incidents"):
        table.add_column(column)
    for heading, _ in _PHYSICAL:
        table.add_column(heading)
    for e in events:
        table.add_row(
            e.id,
            "+".join(e.engines),
            " ".join(_short(o) for o in e.objects) or "-",
            f"{e.start_frame}-{e.end_frame}",
            f"{ns_to_s(e.start_ns - t0_ns):.2f}",
            f"{ns_to_s(e.end_ns - e.start_ns):.2f}",
            str(len(e.incidents)),
            *_physical(e.lead),
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
    by: ByOption = Listing.event,
    out: Annotated[
        Path | None, typer.Option("--out", help="Write them (.json, .csv or .parquet).")
    ] = None,
) -> None:
    """List a drive's events (one per danger) or incidents (--by incident), worst first.

    ``--out`` writes the incidents (events: grouped by event, each with its ``event`` id).
    """
    from workbench.incidents import (  # noqa: PLC0415
        filter_incidents,
        group_events,
        write_incidents,
    )
    from workbench.quality.output import write_quality  # noqa: PLC0415

    found = filter_incidents(
        report.incidents,
        engines=engine or (),
        objects=obj or (),
        causes=cause or (),
        max_margin=max_margin,
    )
    events = None
    counts = f"{len(found)} of {len(report.incidents)} incident(s), worst first"
    if by is Listing.incident:
        print_table(incident_table(found, report.start_ns, f"{log.name}: {counts}"))
    else:
        grouped = group_events(found)
        found = [i for e in grouped for i in e.incidents]
        events = {i.id: e.id for e in grouped for i in e.incidents}
        title = f"{log.name}: {len(grouped)} event(s) of {counts}"
        print_table(event_table(grouped, report.start_ns, title))
    if out is not None:
        write_incidents(found, out, events)
        typer.echo(f"wrote {out}")
        typer.echo(f"wrote {write_quality(report.findings, found, out)} (data quality)")
    if report.stopped_by is not None:
        typer.echo(f"stopped early: the incidents cover {len(report.frame_times)} frames")
        raise report.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``incidents`` to the CLI (a batch's RESULTS_DIR lists every drive's incidents)."""
    from workbench.cli.fleet import fleet_incidents, on_results  # noqa: PLC0415

    app.command("incidents")(on_results(fleet_incidents)(incidents))
