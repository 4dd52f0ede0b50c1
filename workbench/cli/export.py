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

from loaders.timebase import s_to_ns
from workbench.cli.incident_options import LogArgument, StoreOption, with_checked_incidents
from workbench.cli.progress import STDERR
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from workbench.export import ExportSummary
    from workbench.incidents import IncidentReport

__all__ = ["register"]

#: Largest --margin (s): a day, beyond any drive.
_MAX_MARGIN_S = 86_400.0


def _summary_lines(summary: ExportSummary) -> list[str]:
    lines = []
    for clip in summary.clips:
        files = [p.name for p in clip.files.values() if p]
        state = "ok" if clip.problem is None else f"NOT WRITTEN: {clip.problem}"
        lines.append(
            f"  {clip.plan.stem}: {clip.messages} message(s) {state}  [{', '.join(files)}]"
        )
    return lines


def _check(
    *,
    incident: list[str] | None,
    verdict: str | None,
    all_: bool,
    window: str | None,
    margin: float,
    **_: object,
) -> None:
    """The choice of clips and the margin, checked before the drive is evaluated."""
    from workbench.annotations import VERDICTS  # noqa: PLC0415 - light start-up
    from workbench.export import Selection  # noqa: PLC0415
    from workbench.export.window import parse_window  # noqa: PLC0415

    if verdict is not None and verdict not in VERDICTS:
        msg = f"--verdict {verdict!r}: choose one of {', '.join(VERDICTS)}"
        raise WorkbenchError(msg)
    if not 0.0 <= margin <= _MAX_MARGIN_S:  # also NaN
        msg = f"--margin {margin}: give a number of seconds from 0 to {_MAX_MARGIN_S:.0f}"
        raise WorkbenchError(msg)
    Selection(tuple(incident or ()), verdict, all_, window).check()
    if window is not None:
        parse_window(window)


@with_checked_incidents(_check)
def export(
    log: LogArgument,
    report: IncidentReport,
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
    window: Annotated[
        str | None,
        typer.Option(
            "--window",
            help="One clip of START:END, incident or not: seconds (12.5:20) or frames (#250:#400).",
        ),
    ] = None,
    margin: Annotated[
        float,
        typer.Option("--margin", help="Seconds kept before and after each incident."),
    ] = 3.0,
    topics: Annotated[
        str | None, typer.Option("--topics", help="Comma-separated topics to copy (all if unset).")
    ] = None,
    rrd: Annotated[bool, typer.Option("--rrd/--no-rrd", help="Write an .rrd per clip.")] = True,
    thumbnails: Annotated[
        bool, typer.Option("--thumbnails/--no-thumbnails", help="Render a PNG per clip.")
    ] = True,
    force: Annotated[
        bool, typer.Option("--force", help="Replace an earlier export in --out.")
    ] = False,
    without_map: Annotated[
        bool,
        typer.Option(
            "--without-map", help="Export a damaged log whose map cannot be read, without one."
        ),
    ] = False,
    store: StoreOption = None,
) -> None:
    """Write a clip per incident: MCAP of the window's messages, OpenLABEL, .rrd, PNG."""
    from workbench.annotations import LabelStore, default_store_path  # noqa: PLC0415
    from workbench.annotations.attach import elsewhere_note, labels_for  # noqa: PLC0415
    from workbench.export import Selection, export_clips, plan_clips  # noqa: PLC0415
    from workbench.export.inputs import check_inputs  # noqa: PLC0415
    from workbench.export.window import parse_window, plan_window  # noqa: PLC0415

    request = report.request
    if request is None:
        raise WorkbenchError(f"{log}: the incidents carry no request to replay")
    with LabelStore(store or default_store_path()) as labels:
        stored = labels.labels(report.drive_hash)
    found = labels_for(report, stored)
    note = elsewhere_note(report, stored)
    if note:
        typer.echo(f"note: {note}", err=True)
    if window is not None:
        plans = [plan_window(report, parse_window(window))]
    else:
        selection = Selection(tuple(incident or ()), verdict, all_)
        plans = plan_clips(report, found, selection, s_to_ns(margin))
    chosen = [t.strip() for t in topics.split(",") if t.strip()] if topics else None
    if not plans:
        check_inputs(report, request, chosen, without_map=without_map)  # export_clips does too
        typer.echo(f"{log}: no incident to export ({len(report.incidents)} found, none chosen)")
        if report.stopped_by is not None:
            raise report.stopped_by
        return
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
            force=force,
            without_map=without_map,
            labels=found,
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
    """Add ``export`` to the CLI (a batch's RESULTS_DIR: clips of every drive, DIR/<drive>/)."""
    from workbench.cli.fleet import each_drive  # noqa: PLC0415

    app.command("export")(each_drive(export, lambda out, stem: out / stem, incidents_only=True))
