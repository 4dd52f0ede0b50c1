"""``workbench labels export|import``: labels as ASAM OpenLABEL 1.0 JSON."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.fleet import each_drive
from workbench.cli.incident_options import LogArgument, StoreOption, with_incidents

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport

__all__ = ["register"]

labels_app = typer.Typer(
    name="labels", help="Labels as ASAM OpenLABEL 1.0 JSON.", no_args_is_help=True
)


@with_incidents
def export(
    log: LogArgument,
    report: IncidentReport,
    *,
    out: Annotated[Path, typer.Option("--out", help="OpenLABEL JSON file to write.")],
    store: StoreOption = None,
) -> None:
    """Write a drive's incidents and their labels as OpenLABEL (incidents as actions)."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.annotations.attach import elsewhere_note, labels_for  # noqa: PLC0415
    from workbench.annotations.openlabel import export_openlabel, write_openlabel  # noqa: PLC0415

    with LabelStore(store or default_store_path()) as labels:
        stored = labels.labels(report.drive_hash)
    found = labels_for(report, stored)
    note = elsewhere_note(report, stored)
    if note:
        typer.echo(f"note: {note} (not in this file)", err=True)
    write_openlabel(export_openlabel(report, found), out)
    known = sum(i.id in found for i in report.incidents)
    typer.echo(f"wrote {out}: {log.name}, {len(report.incidents)} incident(s), {known} labelled")


labels_app.command("export")(
    each_drive(export, lambda out, stem: out / f"{stem}.openlabel.json", incidents_only=False)
)


@labels_app.command("import")
def import_(
    file: Annotated[Path, typer.Argument(help="OpenLABEL JSON written by `labels export`.")],
    *,
    store: StoreOption = None,
) -> None:
    """Write the labels of an OpenLABEL file into the store (importing twice changes nothing)."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.annotations.openlabel import import_openlabel  # noqa: PLC0415

    path = store or default_store_path()
    with LabelStore(path) as labels:
        written, kept = import_openlabel(file, labels)
    typer.echo(f"{file}: {written} label(s) written, {kept} already in {path}")


def register(app: typer.Typer) -> None:
    """Add the ``labels`` command group to the CLI."""
    app.add_typer(labels_app)
