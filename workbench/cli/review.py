"""``workbench review``: walk a drive's incidents worst first and record verdicts."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.incident_options import (
    ByOption,
    CauseFilter,
    EngineFilter,
    Listing,
    LogArgument,
    MarginFilter,
    ObjectFilter,
    StoreOption,
    with_incidents,
)
from workbench.cli.options import GrpcPortOption, WebPortOption  # noqa: TC001 - typer reads them
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport

__all__ = ["register"]


@with_incidents
def review(
    log: LogArgument,
    report: IncidentReport,
    *,
    store: StoreOption = None,
    reviewer: Annotated[
        str | None, typer.Option("--reviewer", help="Reviewer name (default: login name).")
    ] = None,
    spawn: Annotated[
        bool, typer.Option("--spawn", help="Replay into a native viewer that follows.")
    ] = False,
    serve: Annotated[
        bool, typer.Option("--serve", help="Replay into a web viewer (127.0.0.1 unless --bind).")
    ] = False,
    connect: Annotated[
        str | None,
        typer.Option("--connect", help="Use a running viewer: rerun+http://HOST:PORT/proxy."),
    ] = None,
    bind: Annotated[
        str, typer.Option("--bind", help="Address --serve listens on (0.0.0.0: the LAN).")
    ] = "127.0.0.1",
    engine: EngineFilter = None,
    obj: ObjectFilter = None,
    cause: CauseFilter = None,
    max_margin: MarginFilter = None,
    by: ByOption = Listing.event,
    grpc_port: GrpcPortOption = 9876,
    web_port: WebPortOption = 9090,
) -> None:
    """Review a drive's events (or incidents) in a terminal UI (keys: c f u t n z j k q).

    A verdict on an event labels each of its incidents.
    """
    from workbench.annotations import (  # noqa: PLC0415
        LabelStore,
        default_reviewer,
        default_store_path,
    )
    from workbench.annotations.attach import elsewhere_note  # noqa: PLC0415
    from workbench.incidents import filter_incidents  # noqa: PLC0415
    from workbench.review import ReviewSession  # noqa: PLC0415
    from workbench.review.loop import review_in_viewer, run_review  # noqa: PLC0415

    if sum((spawn, serve, connect is not None)) > 1:
        raise WorkbenchError("--spawn, --serve and --connect are mutually exclusive")
    chosen = filter_incidents(
        report.incidents,
        engines=engine or (),
        objects=obj or (),
        causes=cause or (),
        max_margin=max_margin,
    )
    path = store or default_store_path()
    with LabelStore(path) as labels:
        note = elsewhere_note(report, labels.labels(report.drive_hash))  # before the filters
        if note:
            typer.echo(f"note: {note}", err=True)
        report = dataclasses.replace(report, incidents=tuple(chosen))
        by_event = by is Listing.event
        session = ReviewSession(report, labels, reviewer or default_reviewer(), by_event=by_event)
        if not (spawn or serve or connect):
            run_review(session)
        else:
            review_in_viewer(
                session,
                serve=serve,
                connect=connect,
                bind=bind,
                ports=(grpc_port, web_port),
                announce=lambda url: typer.echo(f"viewer: {url}"),
            )
        typer.echo(
            f"{log.name}: {session.reviewed} of {len(session.incidents)} {session.unit}(s) reviewed"
            f" (store {path})"
        )


def register(app: typer.Typer) -> None:
    """Add ``review`` to the CLI (a batch's RESULTS_DIR: drive after drive, worst first)."""
    from workbench.cli.fleet import each_drive  # noqa: PLC0415

    app.command("review")(each_drive(review, None, incidents_only=True, worst_first=True))
