"""``workbench review``: walk a drive's incidents worst first and record verdicts."""

from __future__ import annotations

import contextlib
import dataclasses
import functools
from typing import TYPE_CHECKING, Annotated, Any

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
from workbench.cli.request_options import find_with_progress
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator, Sequence
    from pathlib import Path

    from workbench.annotations import LabelStore
    from workbench.incidents import Incident, IncidentReport, IncidentRequest
    from workbench.replay.short_labels import ShortLabels
    from workbench.review.loop import LiveReplay
    from workbench.review.session import ReviewSession
    from workbench.viewer.outputs import Destination

__all__ = ["register"]


@functools.partial(with_incidents, find=False)
def review(
    log: LogArgument,
    report: IncidentReport | IncidentRequest,
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
    from workbench.incidents import IncidentReport  # noqa: PLC0415
    from workbench.review.loop import run_review  # noqa: PLC0415

    destination = _destination(
        spawn=spawn,
        serve=serve,
        connect=connect,
        bind=bind,
        grpc_port=grpc_port,
        web_port=web_port,
    )
    path = store or default_store_path()
    with LabelStore(path) as labels, contextlib.ExitStack() as viewer:
        session_of = functools.partial(
            _session,
            store=labels,
            reviewer=reviewer or default_reviewer(),
            by_event=by is Listing.event,
            chosen=_chooser(engine, obj, cause, max_margin),
        )
        if destination is None:
            found = report if isinstance(report, IncidentReport) else find_with_progress(report)
            session = session_of(found, None)
            run_review(session)
        else:
            live = viewer.enter_context(_replay(report, destination))
            if live.served is not None:
                typer.echo(f"viewer: {live.served}")
            session = session_of(live.report, live.labels)
            live.review(session)
        typer.echo(
            f"{log.name}: {session.reviewed} of {len(session.incidents)} {session.unit}(s) reviewed"
            f" (store {path})"
        )


def _chooser(
    engine: Sequence[str] | None,
    obj: Sequence[str] | None,
    cause: Sequence[str] | None,
    max_margin: float | None,
) -> Callable[[Sequence[Incident]], Sequence[Incident]]:
    """The filter of the command's --engine, --object, --cause and --max-margin."""
    from workbench.incidents import filter_incidents  # noqa: PLC0415

    return functools.partial(
        filter_incidents,
        engines=engine or (),
        objects=obj or (),
        causes=cause or (),
        max_margin=max_margin,
    )


def _session(
    report: IncidentReport,
    labels: ShortLabels | None,
    *,
    store: LabelStore,
    reviewer: str,
    by_event: bool,
    chosen: Callable[[Sequence[Incident]], Sequence[Incident]],
) -> ReviewSession:
    """The review session of the drive's incidents that pass the filters (a note first)."""
    from workbench.annotations.attach import elsewhere_note  # noqa: PLC0415
    from workbench.review import ReviewSession  # noqa: PLC0415

    note = elsewhere_note(report, store.labels(report.drive_hash))  # before the filters
    if note:
        typer.echo(f"note: {note}", err=True)
    report = dataclasses.replace(report, incidents=tuple(chosen(report.incidents)))
    return ReviewSession(report, store, reviewer, by_event=by_event, labels=labels)


@contextlib.contextmanager
def _replay(
    source: IncidentReport | IncidentRequest, destination: Destination
) -> Iterator[LiveReplay]:
    """:func:`workbench.review.loop.replayed` with a progress bar while the drive is evaluated."""
    from workbench.cli.progress import frame_progress  # noqa: PLC0415
    from workbench.review.loop import replayed  # noqa: PLC0415

    with contextlib.ExitStack() as stack:
        with frame_progress() as bar:
            task = bar.add_task(f"review {source.log.name}", total=None)
            live = stack.enter_context(
                replayed(source, destination, lambda done: bar.update(task, completed=done))
            )
        yield live


def fleet_review(
    *,
    log: Path,
    store: Path | None = None,
    reviewer: str | None = None,
    engine: list[str] | None = None,
    obj: list[str] | None = None,
    cause: list[str] | None = None,
    max_margin: float | None = None,
    by: Listing = Listing.event,
    **viewer_options: Any,
) -> None:
    """``workbench review RESULTS_DIR``: one queue over every drive's incidents, worst first.

    The incidents are the batch's (nothing is evaluated again); with a viewer, each drive
    is drawn into it when the first of its rows comes up.
    """
    from workbench.annotations import (  # noqa: PLC0415
        LabelStore,
        default_reviewer,
        default_store_path,
    )
    from workbench.batch.reports import drive_reports  # noqa: PLC0415
    from workbench.replay.incidents import short_labels  # noqa: PLC0415
    from workbench.review.fleet import FleetSession, FleetViewer  # noqa: PLC0415
    from workbench.review.loop import drive_link, run_review  # noqa: PLC0415

    if viewer_options.get("serve"):
        msg = (
            f"{log}: --serve restarts its web server per drive, so a results directory is"
            " reviewed with --spawn or --connect"
        )
        raise WorkbenchError(msg)
    destination = _destination(**viewer_options)
    copies = contextlib.ExitStack()  # local copies of URL drives, for the whole review
    reports = {str(r.log): r for r in drive_reports(log, with_incidents_only=True, copies=copies)}
    if not reports:
        typer.echo(f"{log.name}: no incidents in any drive")
        return
    path = store or default_store_path()
    with copies, LabelStore(path) as labels:
        sessions = [
            _session(
                report,
                short_labels(report.incidents),  # as the viewer numbers the drive's objects
                store=labels,
                reviewer=reviewer or default_reviewer(),
                by_event=by is Listing.event,
                chosen=_chooser(engine, obj, cause, max_margin),
            )
            for report in reports.values()
        ]
        fleet = FleetSession(sessions)
        viewer = None
        if destination is not None:
            viewer = FleetViewer(
                fleet,
                lambda s: drive_link(reports[str(s.report.log)], s, destination),
            )
        try:
            run_review(fleet, viewer)
        finally:
            if viewer is not None:
                viewer.close()
        typer.echo(
            f"{log.name}: {fleet.reviewed} of {len(fleet.incidents)} {fleet.unit}(s) reviewed"
            f" in {len(sessions)} drive(s) (store {path})"
        )


def _destination(
    *,
    spawn: bool = False,
    serve: bool = False,
    connect: str | None = None,
    bind: str = "127.0.0.1",
    grpc_port: int = 9876,
    web_port: int = 9090,
    **_settings: Any,
) -> Destination | None:
    """The viewer the options name (``None``: the UI alone)."""
    from workbench.viewer.outputs import Destination  # noqa: PLC0415

    if sum((spawn, serve, connect is not None)) > 1:
        raise WorkbenchError("--spawn, --serve and --connect are mutually exclusive")
    if not (spawn or serve or connect):
        return None
    from workbench.viewer.web_cursor import WebCursor  # noqa: PLC0415

    return Destination(
        spawn=spawn,
        serve=serve,
        connect=connect,
        bind=bind,
        ports=(grpc_port, web_port),
        web_cursor=WebCursor() if serve else None,
    )


def register(app: typer.Typer) -> None:
    """Add ``review`` to the CLI (a batch's RESULTS_DIR: one queue, worst first)."""
    from workbench.cli.fleet import on_results  # noqa: PLC0415

    app.command("review")(on_results(fleet_review)(review))
