"""``workbench info``: what a drive holds and how it will be read (formats, topics, roles)."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003 - typer resolves annotations at runtime
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.table import Table

from loaders.timebase import ns_to_s
from workbench.cli.losses import VerboseOption, echo_losses
from workbench.cli.options import EGO_TOPIC_HELP, RssProfileOption
from workbench.cli.tables import print_table
from workbench.drives import load_rss_params, rss_profile_line

if TYPE_CHECKING:
    from loaders.drive import Drive
    from loaders.errors import LoaderError
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
    log: Annotated[
        Path, typer.Argument(help="Drive: .mcap, .bag, rosbag2 dir or .db3, .osi, .xml, .saa/.scn")
    ],
    *,
    map_path: Annotated[
        Path | None, typer.Option("--map", help="Lane map file (Lanelet2 .osm)")
    ] = None,
    profile: Annotated[Path | None, typer.Option("--profile", help="TOML topic profile")] = None,
    ego_id: Annotated[str | None, typer.Option("--ego-id", help="CommonRoad ego obstacle")] = None,
    verbose: VerboseOption = False,
    ego_topic: Annotated[str | None, typer.Option("--ego-topic", help=EGO_TOPIC_HELP)] = None,
    rss_profile: RssProfileOption = None,
    rss_params: Annotated[
        Path | None,
        typer.Option("--rss-params", help="TOML with RSS dynamics and [scene] settings."),
    ] = None,
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
    from loaders import LoaderError, open_drive  # noqa: PLC0415 - keeps CLI start-up light
    from loaders.losses import count_frames  # noqa: PLC0415

    drive = open_drive(log, map=map_path, profile=profile, ego_id=ego_id, ego_topic=ego_topic)
    stopped: LoaderError | None = None
    try:
        params = load_rss_params(rss_params, rss_profile, drive.lane_map)
        try:
            frames: int | None = count_frames(drive)
        except LoaderError as err:
            frames, stopped = None, err
        console = Console(width=160)
        render_info(drive, console, frames)
        chosen = "auto -> " if rss_profile in {None, "auto"} and rss_params is None else ""
        console.print(f"rss profile {chosen}{rss_profile_line(params)}")
        if quality and stopped is None:
            stopped = _quality(drive, console)
    finally:
        drive.close()
    echo_losses(drive.info.notes, verbose=verbose)
    if stopped is not None:
        raise stopped


def register(app: typer.Typer) -> None:
    """Add the ``info`` command."""
    app.command("info")(info)
