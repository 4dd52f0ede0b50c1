"""Options shared by the incident commands (incidents, label, labels export, review).

Every one of them finds the drive's incidents the same way, so the options that decide the
incidents (and with them the ids) are declared once here.
"""

from __future__ import annotations

import enum
import functools
import inspect
import typing
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from workbench.cli.options import (
    EGO_TOPIC_HELP,
    REACH_RULES_HELP,
    REACH_TRAJECTORY_HELP,
    ReachMethodOption,
    ReachRulesOption,
    ReachTrajectoryOption,
    RssProfileOption,
)
from workbench.cli.progress import frame_progress
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable

    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = [
    "ByOption",
    "CauseFilter",
    "EgoIdOption",
    "EgoTopicOption",
    "EngineFilter",
    "EnginesOption",
    "Listing",
    "LogArgument",
    "MapOption",
    "MarginFilter",
    "MergeGapOption",
    "MinDurationOption",
    "ObjectFilter",
    "ProfileOption",
    "ReachOption",
    "RssParamsOption",
    "StoreOption",
    "find_with_progress",
    "incident_request",
    "with_checked_incidents",
    "with_incidents",
    "with_requests",
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
ReachRulesArg = Annotated[ReachRulesOption, typer.Option("--reach-rules", help=REACH_RULES_HELP)]
ReachTrajectoryArg = Annotated[
    ReachTrajectoryOption, typer.Option("--reach-trajectory", help=REACH_TRAJECTORY_HELP)
]
MinDurationOption = Annotated[
    float,
    typer.Option("--min-duration", help="Drop incidents shorter than this many seconds.", min=0.0),
]
MergeGapOption = Annotated[
    float,
    typer.Option(
        "--merge-gap", help="Bridge safe stretches of at most this many seconds.", min=0.0
    ),
]
EngineFilter = Annotated[
    list[str] | None, typer.Option("--engine", help="Only this engine (repeatable).")
]
ObjectFilter = Annotated[
    list[str] | None, typer.Option("--object", help="Only this object id (repeatable).")
]
CauseFilter = Annotated[
    list[str] | None, typer.Option("--cause", help="Cause contains this (repeatable).")
]
MarginFilter = Annotated[
    float | None, typer.Option("--max-margin", help="Worst margin at most this.")
]


class Listing(enum.StrEnum):
    """``--by``: events (one per danger, all engines on one object) or incidents."""

    event = "event"
    incident = "incident"


ByOption = Annotated[
    Listing,
    typer.Option("--by", help="List events (one per danger, all engines) or incidents."),
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
    reach_rules: ReachRulesOption,
    reach_trajectory: ReachTrajectoryOption,
    rss_params: Path | None,
    rss_profile: str | None,
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
        rss_profile=rss_profile,
        reach_rules=reach_rules.setting,
        reach_trajectory=reach_trajectory.value,
    )


def find_with_progress(request: IncidentRequest) -> IncidentReport:
    """Find the request's incidents with a progress bar on stderr."""
    from workbench.incidents import find_incidents  # noqa: PLC0415 - light start-up

    with frame_progress() as bar:
        task = bar.add_task(f"incidents {request.log.name}", total=None)
        return find_incidents(request, progress=lambda done: bar.update(task, completed=done))


def _option(name: str, annotation: Any, default: object) -> inspect.Parameter:
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=annotation
    )


#: The options that decide a drive's incidents (and so their ids), in help order.
_SHARED = (
    _option("engines", EnginesOption, ""),
    _option("map_path", MapOption, None),
    _option("profile", ProfileOption, None),
    _option("ego_id", EgoIdOption, None),
    _option("ego_topic", EgoTopicOption, None),
    _option("reach_method", ReachOption, ReachMethodOption.turn),
    _option("reach_rules", ReachRulesArg, ReachRulesOption.public_road),
    _option("reach_trajectory", ReachTrajectoryArg, ReachTrajectoryOption.auto),
    _option("rss_params", RssParamsOption, None),
    _option("rss_profile", RssProfileOption, None),
    _option("min_duration", MinDurationOption, 0.0),
    _option("merge_gap", MergeGapOption, 0.0),
)


def _own(command: Callable[..., None], injected: str) -> list[inspect.Parameter]:
    """The command's own CLI parameters (annotations resolved), without ``injected``."""
    hints = typing.get_type_hints(
        command, include_extras=True, localns={"IncidentReport": Any, "IncidentRequest": Any}
    )
    return [
        p.replace(annotation=hints.get(p.name, p.annotation))
        for p in inspect.signature(command).parameters.values()
        if p.name not in {injected, "return"}
    ]


def _signed(run: Callable[..., None], own: list[inspect.Parameter]) -> Callable[..., None]:
    """``run`` with the signature typer reads: the command's options, then the shared ones."""
    params = [*own, *_SHARED]
    run.__signature__ = inspect.Signature(params)  # type: ignore[attr-defined]
    run.__annotations__ = {p.name: p.annotation for p in params}
    return run


def with_incidents(
    command: Callable[..., None],
    *,
    check: Callable[..., None] | None = None,
    find: bool = True,
) -> Callable[..., None]:
    """Give a command the incident options; it gets the drive's ``report`` found with them.

    The command declares ``log`` and ``report`` (not a CLI parameter) and its own options; the
    returned function's signature (what typer reads) has ``log``, the command's options and
    the shared ones, so every incident command finds incidents, and so ids, the same way.
    ``check`` (see :func:`with_checked_incidents`) sees the command's own options first, so a
    bad choice fails before the drive is evaluated. ``find=False``: ``report`` is the
    ``IncidentRequest`` and the command finds the incidents in a pass of its own
    (``review`` with a viewer: one pass streams the drive and finds them).
    """
    own = _own(command, "report")

    @functools.wraps(command)
    def run(**kwargs: Any) -> None:
        shared = {p.name: kwargs.pop(p.name) for p in _SHARED}
        if check is not None:
            check(**kwargs)
        request = incident_request(kwargs["log"], **shared)
        command(report=find_with_progress(request) if find else request, **kwargs)

    return _signed(run, own)


def with_requests(command: Callable[..., None]) -> Callable[..., None]:
    """Give a command the incident options as ``request``: drive path -> ``IncidentRequest``.

    Like :func:`with_incidents`, but nothing is evaluated: the command (``workbench batch``)
    builds one request per drive, each with the same settings.
    """
    own = _own(command, "request")

    @functools.wraps(command)
    def run(**kwargs: Any) -> None:
        shared = {p.name: kwargs.pop(p.name) for p in _SHARED}
        command(request=functools.partial(incident_request, **shared), **kwargs)

    return _signed(run, own)


def with_checked_incidents(
    check: Callable[..., None],
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """:func:`with_incidents` whose ``check`` validates the command's options first."""
    return functools.partial(with_incidents, check=check)
