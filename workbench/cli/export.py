"""``workbench export``: labeled incident clips (MCAP, OpenLABEL, .rrd, thumbnail) into DIR."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer
from rich.progress import (
    BarColumn,
    DownloadColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
)

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
    find_request_with_progress,
    incident_request,
)
from workbench.cli.options import ReachMethodOption
from workbench.cli.progress import STDERR

if TYPE_CHECKING:
    from workbench.export import ExportSummary

__all__ = ["register"]


def _summary_lines(summary: ExportSummary) -> list[str]:
    lines = []
    for clip in summary.clips:
        files = [p.name for p in (clip.mcap, clip.bag, clip.openlabel, clip.rrd, clip.png) if p]
        state = "ok" if clip.problem is None else f"NOT WRITTEN: {clip.problem}"
        lines.append(
            f"  {clip.plan.stem}: {clip.messages} message(s) {state}  [{', '.join(files)}]"
        )
    return lines


def export(
    log: LogArgument,
    *,
    out: Annotated[Path, typer.Option("--out", help="Directory for the clips and their index.")],
    incident: Annotated[
        list[str] | None, typer.Option("--incident", help="Export this incident id (repeatable).")
    ] = None,
    verdict: Annotated[
        str | None,
        typer.Option("--verdict", help="Export the incidents labelled so (confirmed, ...)."),
    ] = None,
    all_: Annotated[bool, typer.Option("--all", help="Export every incident.")] = False,
    margin: Annotated[
        float,
        typer.Option("--margin", help="Seconds kept before and after each incident.", min=0.0),
    ] = 3.0,
    topics: Annotated[
        str | None, typer.Option("--topics", help="Comma-separated topics to copy (default: all).")
    ] = None,
    rrd: Annotated[bool, typer.Option("--rrd/--no-rrd", help="Write an .rrd per clip.")] = True,
    thumbnails: Annotated[
        bool, typer.Option("--thumbnails/--no-thumbnails", help="Render a PNG per clip.")
    ] = True,
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
    """Write a clip per incident: MCAP of the window's messages, OpenLABEL, .rrd, PNG."""
    from workbench.annotations import VERDICTS, LabelStore, default_store_path  # noqa: PLC0415
    from workbench.errors import WorkbenchError  # noqa: PLC0415
    from workbench.export import Selection, export_clips, plan_clips  # noqa: PLC0415

    if verdict is not None and verdict not in VERDICTS:
        msg = f"--verdict {verdict!r}: choose one of {', '.join(VERDICTS)}"
        raise WorkbenchError(msg)
    selection = Selection(tuple(incident or ()), verdict, all_)
    selection.check()
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
    report = find_request_with_progress(request)
    with LabelStore(store or default_store_path()) as labels:
        found = labels.labels(report.drive_hash)
    plans = plan_clips(report, found, selection, round(margin * 1e9))
    if not plans:
        typer.echo(f"{log}: no incident to export ({len(report.incidents)} found, none chosen)")
        return
    chosen = [t.strip() for t in topics.split(",") if t.strip()] if topics else None
    steps = len(plans) * (1 + int(rrd) + int(rrd and thumbnails))
    with Progress(
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        DownloadColumn(),
        TimeElapsedColumn(),
        console=STDERR,
        transient=True,
    ) as bar:
        clips = bar.add_task(f"clips {log.name}", total=steps)
        copied = bar.add_task("copied", total=None)
        summary = export_clips(
            report,
            request,
            plans,
            out,
            topics=chosen,
            recordings=rrd,
            thumbnails=thumbnails,
            on_bytes=lambda n: bar.advance(copied, n),
            on_clip=lambda: bar.advance(clips),
        )
    written = sum(c.problem is None for c in summary.clips)
    typer.echo(
        f"wrote {written} of {len(summary.clips)} clip(s) to {out} "
        f"({summary.bytes_written / 2**20:.1f} MiB; index {summary.index_json.name}, "
        f"{summary.index_csv.name})"
    )
    for line in _summary_lines(summary):
        typer.echo(line)
    if summary.thumbnails_skipped is not None:
        typer.echo(f"thumbnails skipped: {summary.thumbnails_skipped}")
    if report.stopped_by is not None:
        typer.echo("stopped early: the clips cover the log up to where it breaks off")
        raise report.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``export`` to the CLI."""
    app.command("export")(export)
