"""``workbench info``: what a drive holds and how it will be read (formats, topics, roles)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.table import Table

from loaders.timebase import ns_to_s
from workbench.cli.losses import VerboseOption, echo_losses
from workbench.cli.options import LogArgument  # noqa: TC001 - typer reads it at run time
from workbench.cli.request_options import RequestCommand
from workbench.cli.tables import print_table

if TYPE_CHECKING:
    from loaders.drive import Drive
    from loaders.errors import LoaderError
    from workbench.incidents import IncidentRequest
    from workbench.quality import Finding

__all__ = ["info", "quality_table", "register", "render_info"]


def render_info(drive: Drive, console: Console, frames: int | None = None) -> None:
    """Print the drive summary and the topic table.

    Args:
        drive: The opened drive.
        console: Where to print.
        frames: The frames ``evaluate`` will produce (``loaders.losses.count_frames``), when
            counted; printed beside the index count when they differ.
    """
    info = drive.info
    console.print(f"[bold]{info.path}[/bold]")
    console.print(f"format      {info.source_format}")
    console.print(f"duration    {info.duration_s:.3f} s ({info.start_ns} .. {info.end_ns} ns)")
    if frames is None or frames == info.frame_count:
        console.print(f"frames      {info.frame_count}")
    else:
        console.print(f"frames      {frames} (of {info.frame_count} ego messages)")
    console.print(
        f"clock       {info.clock}, match tolerance {ns_to_s(info.match_tolerance_ns):.3f} s"
    )
    lane_map = drive.lane_map
    if lane_map is None:
        console.print("map         none")
    else:
        console.print(f"map         {info.map_source} ({len(lane_map.lanes)} lanes)")
    roles = info.roles
    if len(roles.ego_candidates) > 1:
        console.print(f"ego         {roles.ego} (rule: {roles.ego_rule})")
        console.print(f"candidates  {', '.join(roles.ego_candidates)}")
    for key, value in sorted(info.notes.items()):
        console.print(f"note        {key}: {value}")
    table = Table(title="topics")
    table.add_column("topic")
    table.add_column("type")
    table.add_column("count", justify="right")
    table.add_column("role")
    for topic in info.topics:
        table.add_row(topic.topic, topic.msgtype, str(topic.count), topic.role or "")
    print_table(table, console)


def quality_table(findings: tuple[Finding, ...], title: str) -> Table:
    """Rich table of a drive's data-quality findings: one row per object and kind, worst first."""
    from workbench.quality.summary import summarize  # noqa: PLC0415 - only with --quality

    table = Table(title=title)
    for column in ("object", "kind", "runs", "frames", "first-last", "worst", "bound", "unit"):
        table.add_column(column, justify="right" if column in {"runs", "frames"} else "left")
    for row in summarize(findings):
        worst = row.worst
        table.add_row(
            row.object_id,
            str(row.kind),
            str(row.runs),
            str(row.frames),
            f"{row.first_frame}-{row.last_frame}",
            f"{worst.value:.2f} (frame {worst.start_frame}-{worst.end_frame})",
            f"{worst.bound:.2f}",
            worst.unit,
        )
    return table


def _quality(drive: Drive, console: Console) -> LoaderError | None:
    """Read every frame, check the objects' data and print the table (docs/data_quality.md)."""
    from loaders import LoaderError  # noqa: PLC0415
    from workbench.quality import TrackCollector, check_tracks  # noqa: PLC0415
    from workbench.quality.summary import kind_counts  # noqa: PLC0415

    collector = TrackCollector()
    stopped: LoaderError | None = None
    try:
        collector.add(drive.frames())
    except LoaderError as err:
        stopped = err
    tracks = collector.tracks()
    findings = check_tracks(tracks)
    objects = len({f.object_id for f in findings})
    title = f"data quality: {len(findings)} finding(s) on {objects} of {len(tracks.ids)} objects"
    if findings:
        console.print(quality_table(findings, title))
    else:
        console.print(title)
    counts = ", ".join(f"{kind} {n}" for kind, n in kind_counts(findings).items())
    console.print(f"findings per kind: {counts}")
    return stopped


def info(
    log: LogArgument,
    request: IncidentRequest,
    *,
    verbose: VerboseOption = False,
    quality: Annotated[
        bool,
        typer.Option(
            "--quality",
            help="Check every object's data (speed vs positions, acceleration, jerk, heading, "
            "jumps) and list the findings per object and kind.",
        ),
    ] = False,
) -> None:
    """Show format, duration, frame count, topics with types, counts and roles, and the map.

    The frame count is what ``evaluate`` will produce: the role topics are read once,
    without the engines, to count the frames and the messages that make none (printed on
    the same line ``evaluate`` prints; ``--verbose`` details them). A damaged log ends the
    command with its error after the summary. ``--quality`` reads every frame once more and
    lists the implausible data per object and kind (docs/data_quality.md).
    """
    from loaders import LoaderError  # noqa: PLC0415 - keeps CLI start-up light
    from loaders.losses import count_frames  # noqa: PLC0415

    del log  # the request's
    drive = request.open_drive()
    stopped: LoaderError | None = None
    try:
        lines = _engine_lines(request, drive)
        try:
            frames: int | None = count_frames(drive)
        except LoaderError as err:
            frames, stopped = None, err
        console = Console(width=160)
        render_info(drive, console, frames)
        for line in lines:
            console.print(line)
        if quality and stopped is None:
            stopped = _quality(drive, console)
    finally:
        drive.close()
    echo_losses(drive.info.notes, verbose=verbose)
    if stopped is not None:
        raise stopped


def _engine_lines(request: IncidentRequest, drive: Drive) -> list[str]:
    """What each engine that describes its options says about them for this drive."""
    from workbench.engines.registry import engine, names  # noqa: PLC0415

    lines: list[str] = []
    for name in names():
        describe = engine(name).describe
        line = None if describe is None else describe(drive.lane_map, request.options_of(name))
        if line is not None and line not in lines:
            lines.append(line)
    return lines


def register(app: typer.Typer) -> None:
    """Add the ``info`` command."""
    app.command("info")(RequestCommand(info, inject="request", engines=None, need_engines=False))
