"""Options shared by the incident commands (incidents, label, labels export, review).

Every one of them finds the drive's incidents the same way, so the options that decide the
incidents (and with them the ids) are declared once here.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.options import EGO_TOPIC_HELP, ReachMethodOption
from workbench.cli.progress import frame_progress
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = [
    "EgoIdOption",
    "EgoTopicOption",
    "EnginesOption",
    "LogArgument",
    "MapOption",
    "MergeGapOption",
    "MinDurationOption",
    "ProfileOption",
    "ReachOption",
    "RssParamsOption",
    "StoreOption",
    "find_request_with_progress",
    "find_with_progress",
    "incident_request",
]

LogArgument = Annotated[
    Path, typer.Argument(help="Drive: .mcap, .bag, rosbag2 dir or .db3, .xml, .saa.")
]
MapOption = Annotated[Path | None, typer.Option("--map", help="Lane map file.")]
ProfileOption = Annotated[Path | None, typer.Option("--profile", help="TOML topic profile.")]
EgoIdOption = Annotated[str | None, typer.Option("--ego-id", help="CommonRoad ego id.")]
EgoTopicOption = Annotated[str | None, typer.Option("--ego-topic", help=EGO_TOPIC_HELP)]
EnginesOption = Annotated[
    str, typer.Option("--engines", help="Comma-separated (default: every registered engine).")
]
ReachOption = Annotated[
    ReachMethodOption, typer.Option("--reach-method", help="Reachable-set method.")
]
RssParamsOption = Annotated[
    Path | None, typer.Option("--rss-params", help="TOML with RSS dynamics and [scene] settings.")
]
MinDurationOption = Annotated[
    float, typer.Option("--min-duration", help="Drop incidents shorter than this [s].", min=0.0)
]
MergeGapOption = Annotated[
    float,
    typer.Option("--merge-gap", help="Bridge safe stretches of at most this long [s].", min=0.0),
]
StoreOption = Annotated[
    Path | None,
    typer.Option(
        "--store", help="Label store (default: $XDG_DATA_HOME/rss-workbench/labels.sqlite)."
    ),
]


def incident_request(
    log: Path,
    *,
    engines: str,
    map_path: Path | None,
    profile: Path | None,
    ego_id: str | None,
    ego_topic: str | None,
    reach_method: ReachMethodOption,
    rss_params: Path | None,
    min_duration: float,
    merge_gap: float,
) -> IncidentRequest:
    """The request the incident options describe.

    Raises:
        WorkbenchError: Unknown engine, or none.
    """
    from workbench.engines import names, parse_engines  # noqa: PLC0415 - light start-up
    from workbench.incidents import IncidentRequest, IncidentSettings  # noqa: PLC0415

    chosen = parse_engines(engines) if engines.strip() else list(names())
    if not chosen:
        raise WorkbenchError("--engines: name at least one engine")
    return IncidentRequest(
        log=log,
        engines=tuple(chosen),
        map_path=map_path,
        profile=profile,
        ego_id=ego_id,
        ego_topic=ego_topic,
        reach_method=reach_method.value,
        rss_params=rss_params,
        settings=IncidentSettings(min_duration_s=min_duration, merge_gap_s=merge_gap),
    )


def find_request_with_progress(request: IncidentRequest) -> IncidentReport:
    """Find the request's incidents with a progress bar on stderr."""
    from workbench.incidents import find_incidents  # noqa: PLC0415 - light start-up

    with frame_progress() as bar:
        task = bar.add_task(f"incidents {request.log.name}", total=None)
        return find_incidents(request, progress=lambda done: bar.update(task, completed=done))


def find_with_progress(
    log: Path,
    *,
    engines: str,
    map_path: Path | None,
    profile: Path | None,
    ego_id: str | None,
    ego_topic: str | None,
    reach_method: ReachMethodOption,
    rss_params: Path | None,
    min_duration: float,
    merge_gap: float,
) -> IncidentReport:
    """Find the drive's incidents with a progress bar on stderr."""
    request = incident_request(
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
    return find_request_with_progress(request)
