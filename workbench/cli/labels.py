"""``workbench labels export|import``: labels as ASAM OpenLABEL 1.0 JSON."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
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

__all__ = ["register"]

labels_app = typer.Typer(
    name="labels", help="Labels as ASAM OpenLABEL 1.0 JSON.", no_args_is_help=True
)


@labels_app.command("export")
def export(
    log: LogArgument,
    *,
    out: Annotated[Path, typer.Option("--out", help="OpenLABEL JSON file to write.")],
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
    """Write a drive's incidents and their labels as OpenLABEL (incidents as actions)."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.annotations.openlabel import export_openlabel, write_openlabel  # noqa: PLC0415

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
    with LabelStore(store or default_store_path()) as labels:
        found = labels.labels(report.drive_hash)
    write_openlabel(export_openlabel(report, found), out)
    known = sum(i.id in found for i in report.incidents)
    typer.echo(f"wrote {out}: {len(report.incidents)} incident(s), {known} labelled")


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
