"""``workbench label``: record a review verdict on one incident in the label store."""

from __future__ import annotations

import enum
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
from workbench.errors import WorkbenchError

__all__ = ["ReviewVerdictOption", "register"]


class ReviewVerdictOption(enum.StrEnum):
    """``--verdict`` values (the store's verdicts)."""

    confirmed = "confirmed"
    false_positive = "false_positive"
    follow_up = "follow_up"


def _reviewer() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "unknown"


def label(
    log: LogArgument,
    incident_id: Annotated[str, typer.Argument(help="Incident id (`workbench incidents LOG`).")],
    *,
    verdict: Annotated[ReviewVerdictOption, typer.Option("--verdict", help="Review verdict.")],
    tag: Annotated[
        list[str] | None, typer.Option("--tag", help="Tag (repeatable; replaces the tags).")
    ] = None,
    note: Annotated[str | None, typer.Option("--note", help="Note (replaces the note).")] = None,
    reviewer: Annotated[
        str | None, typer.Option("--reviewer", help="Reviewer name (default: login name).")
    ] = None,
    store: StoreOption = None,
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
    """Label one incident of a drive (found with the same settings as `workbench incidents`)."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415

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
            verdict.value,
            tags=tag if tag is not None else (before.tags if before else ()),
            note=note if note is not None else (before.note if before else ""),
            reviewer=reviewer or _reviewer(),
            settings=report.settings,
            log_name=log.name,
        )
    typer.echo(f"{incident_id}: {verdict.value} (store {path})")


def register(app: typer.Typer) -> None:
    """Add ``label`` to the CLI."""
    app.command("label")(label)
