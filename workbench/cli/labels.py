"""``workbench labels export|import``: labels as ASAM OpenLABEL 1.0 JSON."""

from __future__ import annotations

import enum
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


class PreferOption(enum.StrEnum):
    """``--prefer`` values (:class:`workbench.annotations.openlabel_import.Prefer`)."""

    newer = "newer"
    import_ = "import"
    store = "store"


@labels_app.command("import")
def import_(
    file: Annotated[
        Path, typer.Argument(help="OpenLABEL JSON of `labels export` or of a clip (`export`).")
    ],
    *,
    prefer: Annotated[
        PreferOption,
        typer.Option(
            "--prefer",
            help="Where the file and the store differ: the newer label, the file's or the store's.",
        ),
    ] = PreferOption.newer,
    store: StoreOption = None,
) -> None:
    """Write the labels of an OpenLABEL file into the store; report every label that differs."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.annotations.openlabel_import import Prefer, import_openlabel  # noqa: PLC0415

    path = store or default_store_path()
    with LabelStore(path) as labels:
        report = import_openlabel(file, labels, Prefer(prefer.value))
    for outcome in report.outcomes:
        if outcome.status in {"replaced", "kept", "conflicting"}:
            typer.echo(f"  {outcome.line()}")
    counts = ", ".join(
        f"{report.count(s)} {s}"
        for s in ("added", "replaced", "kept", "conflicting", "unchanged")
        if report.count(s)
    )
    drive = report.log_name or report.drive_hash[:12]
    typer.echo(
        f"{file}: {report.written} label(s) written to {path} for {drive} ({counts or 'none'})"
    )


def register(app: typer.Typer) -> None:
    """Add the ``labels`` command group to the CLI."""
    app.add_typer(labels_app)
