"""``workbench label``: record a review verdict on one incident in the label store."""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer

from workbench.annotations.schema import ReviewVerdict  # noqa: TC001 - typer reads it
from workbench.cli.incident_options import LogArgument, StoreOption, with_incidents
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport

__all__ = ["register"]


@with_incidents
def label(
    log: LogArgument,
    report: IncidentReport,
    incident_id: Annotated[str, typer.Argument(help="Incident id (`workbench incidents LOG`).")],
    *,
    verdict: Annotated[ReviewVerdict, typer.Option("--verdict", help="Review verdict.")],
    tag: Annotated[
        list[str] | None, typer.Option("--tag", help="Tag (repeatable; replaces the tags).")
    ] = None,
    note: Annotated[str | None, typer.Option("--note", help="Note (replaces the note).")] = None,
    reviewer: Annotated[
        str | None, typer.Option("--reviewer", help="Reviewer name (default: login name).")
    ] = None,
    store: StoreOption = None,
) -> None:
    """Label one incident of a drive (found with the same settings as `workbench incidents`)."""
    from workbench.annotations import (  # noqa: PLC0415
        LabelStore,
        default_reviewer,
        default_store_path,
    )

    if report.find(incident_id) is None:
        msg = (
            f"{log}: no incident {incident_id!r} with these settings "
            f"({len(report.incidents)} found; `workbench incidents {log}` lists them)"
        )
        raise WorkbenchError(msg)
    path = store or default_store_path()
    with LabelStore(path) as labels:
        before = labels.label(report.drive_hash, incident_id)
        labels.put(
            report.drive_hash,
            incident_id,
            verdict,
            tags=tag if tag is not None else (before.tags if before else ()),
            note=note if note is not None else (before.note if before else ""),
            reviewer=reviewer or default_reviewer(),
            settings=report.settings,
            log_name=log.name,
        )
    typer.echo(f"{incident_id}: {verdict.value} (store {path})")


def register(app: typer.Typer) -> None:
    """Add ``label`` to the CLI."""
    app.command("label")(label)
