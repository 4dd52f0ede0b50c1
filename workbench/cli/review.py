"""``workbench review``: walk a drive's incidents worst first and record verdicts."""

from __future__ import annotations

import getpass
from typing import Annotated

import typer

from workbench.cli.incident_options import (
    EgoIdOption,
    EgoTopicOption,
    EnginesOption,
    LogArgument,
    MapOption,
    MergeGapOption,
    MinDurationOption,
    ProfileOption,
    ReachOption,
    RssParamsOption,
    StoreOption,
    find_with_progress,
)
from workbench.cli.options import ReachMethodOption
from workbench.drives import ego_size, load_rss_params, open_log
from workbench.errors import WorkbenchError

__all__ = ["register"]


def _login() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "unknown"


def review(
    log: LogArgument,
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
    grpc_port: Annotated[int, typer.Option("--grpc-port", help="--serve: gRPC port.")] = 9876,
    web_port: Annotated[int, typer.Option("--web-port", help="--serve: web page port.")] = 9090,
    engines: EnginesOption = "",
    map_path: MapOption = None,
    profile: ProfileOption = None,
    ego_id: EgoIdOption = None,
    ego_topic: EgoTopicOption = None,
    reach_method: ReachOption = ReachMethodOption.turn,
    rss_params: RssParamsOption = None,
    min_duration: MinDurationOption = 0.0,
    merge_gap: MergeGapOption = 0.0,
) -> None:
    """Review a drive's incidents in a terminal UI (keys: c f u t n z j k q)."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.engines import EngineSettings, build_runners  # noqa: PLC0415
    from workbench.incidents import IncidentSettings  # noqa: PLC0415
    from workbench.review import ReviewSession  # noqa: PLC0415
    from workbench.review.loop import review_in_viewer, run_review  # noqa: PLC0415

    if sum((spawn, serve, connect is not None)) > 1:
        raise WorkbenchError("--spawn, --serve and --connect are mutually exclusive")
    report = find_with_progress(
        log,
        engines=engines,
        map_path=map_path,
        profile=profile,
        ego_id=ego_id,
        ego_topic=ego_topic,
        reach_method=reach_method,
        rss_params=rss_params,
        min_duration=min_duration,
        merge_gap=merge_gap,
    )
    path = store or default_store_path()
    with LabelStore(path) as labels:
        session = ReviewSession(report, labels, reviewer or _login())
        if not (spawn or serve or connect):
            run_review(session)
        else:
            params = load_rss_params(rss_params)
            drive = open_log(
                log, map_path=map_path, profile=profile, ego_id=ego_id, ego_topic=ego_topic
            )
            try:
                settings = EngineSettings(
                    rss_params=params, reach_method=reach_method.value, full_geometry=True
                )
                names = list(report.settings["engines"])
                review_in_viewer(
                    session,
                    drive,
                    build_runners(names, drive.lane_map, settings),
                    serve=serve,
                    connect=connect,
                    bind=bind,
                    ports=(grpc_port, web_port),
                    incident_settings=IncidentSettings(min_duration, merge_gap),
                    ego=ego_size(params),
                    announce=lambda url: typer.echo(f"viewer: {url}"),
                )
            finally:
                drive.close()
        typer.echo(
            f"{session.reviewed} of {len(session.incidents)} incident(s) reviewed (store {path})"
        )


def register(app: typer.Typer) -> None:
    """Add ``review`` to the CLI."""
    app.command("review")(review)
