"""``workbench replay``: send a drive to Rerun (``.rrd`` file, native viewer or local server)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.engines import (
    ReachMethodOption,
    build_engines,
    load_rss_params,
    parse_engines,
)
from workbench.cli.progress import frame_progress

if TYPE_CHECKING:
    from loaders.drive import Drive
    from workbench.replay.run import ReplaySummary

__all__ = ["default_output", "open_log", "register", "replay", "window_ns"]


def default_output(log: Path, out_dir: Path) -> Path:
    """``<out_dir>/<log stem>.rrd``; a rosbag2 directory keeps its whole name."""
    stem = log.name if log.is_dir() else log.stem
    return out_dir / f"{stem}.rrd"


def window_ns(
    drive: Drive, start_s: float | None, end_s: float | None
) -> tuple[int | None, int | None]:
    """Turn ``--start``/``--end`` seconds from the drive start into absolute nanoseconds."""
    t0 = drive.info.start_ns
    start = None if start_s is None else t0 + round(start_s * 1e9)
    end = None if end_s is None else t0 + round(end_s * 1e9)
    return start, end


def open_log(
    log: Path, *, map_path: Path | None, profile: Path | None, ego_id: str | None
) -> Drive:
    """Open a drive with ``loaders.open_drive``, turning a missing path into a one-line error."""
    from workbench.replay.run import ReplayError  # noqa: PLC0415 - keeps CLI start-up light

    if not log.exists():
        raise ReplayError(f"{log}: no such file or directory")
    try:
        from loaders import open_drive  # type: ignore[attr-defined,unused-ignore]  # noqa: PLC0415
    except ImportError as err:
        raise ReplayError("loaders.open_drive is not available in this build") from err
    drive: Drive = open_drive(log, map=map_path, profile=profile, ego_id=ego_id)
    return drive


def run_with_progress(
    drive: Drive,
    *,
    label: str,
    start_s: float | None,
    end_s: float | None,
    **targets: object,
) -> ReplaySummary:
    """Replay ``drive`` with a rich progress bar on stderr; ``targets`` go to ``replay_drive``."""
    from workbench.replay.run import replay_drive  # noqa: PLC0415

    start_ns, end_ns = window_ns(drive, start_s, end_s)
    total = drive.info.frame_count or None
    with frame_progress() as bar:
        task = bar.add_task(label, total=total)
        return replay_drive(
            drive,
            start_ns=start_ns,
            end_ns=end_ns,
            progress=lambda done: bar.update(task, completed=done),
            **targets,  # type: ignore[arg-type]
        )


def _wait_for_ctrl_c(url: str) -> None:
    typer.echo(f"open {url}")
    typer.echo(
        "the data (gRPC) is served on 127.0.0.1 only; the web viewer page itself is served "
        "on every interface by rerun 0.41 (it holds no data)"
    )
    typer.echo("press Ctrl-C to stop")
    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        typer.echo("stopped")


def replay(
    log: Annotated[
        Path, typer.Argument(help="Drive: .mcap, .bag, rosbag2 directory or CommonRoad .xml.")
    ],
    *,
    map_path: Annotated[
        Path | None,
        typer.Option("--map", help="Lane map file (Lanelet2, CommonRoad, OpenDRIVE)."),
    ] = None,
    profile: Annotated[
        Path | None, typer.Option("--profile", help="TOML profile overriding topic roles.")
    ] = None,
    ego_id: Annotated[
        str | None, typer.Option("--ego-id", help="CommonRoad: obstacle id promoted to ego.")
    ] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Write this .rrd file.")] = None,
    out_dir: Annotated[
        Path, typer.Option("--out-dir", help="Directory for the default <log stem>.rrd.")
    ] = Path("out"),
    spawn: Annotated[bool, typer.Option("--spawn", help="Stream to a new native viewer.")] = False,
    serve: Annotated[
        bool, typer.Option("--serve", help="Serve gRPC + web viewer (on 127.0.0.1 by default).")
    ] = False,
    bind: Annotated[
        str,
        typer.Option("--bind", help="Address --serve listens on; 0.0.0.0 exposes it to the LAN."),
    ] = "127.0.0.1",
    start: Annotated[
        float | None, typer.Option("--start", help="Seconds from the drive start.")
    ] = None,
    end: Annotated[
        float | None, typer.Option("--end", help="Seconds from the drive start.")
    ] = None,
    engines: Annotated[
        str,
        typer.Option("--engines", help="Also evaluate and show these engines, e.g. reachsets."),
    ] = "",
    reach_method: Annotated[
        ReachMethodOption, typer.Option("--reach-method", help="Reachable-set method.")
    ] = ReachMethodOption.turn,
    rss_params: Annotated[
        Path | None,
        typer.Option("--rss-params", help="TOML with RSS dynamics and [scene] settings."),
    ] = None,
) -> None:
    """Replay a drive into Rerun: map, ego, actors, plan and plots on timelines frame/log_time."""
    from workbench.replay.run import ReplayError  # noqa: PLC0415

    if sum((out is not None, spawn, serve)) > 1:
        raise ReplayError("--out, --spawn and --serve are mutually exclusive")
    target = out if (out is not None or spawn or serve) else default_output(log, out_dir)
    drive = open_log(log, map_path=map_path, profile=profile, ego_id=ego_id)
    try:
        runners = build_engines(
            drive,
            parse_engines(engines),
            reach_method.value,
            full_geometry=True,
            rss_params=load_rss_params(rss_params),
        )
        summary = run_with_progress(
            drive,
            label=f"replay {log.name}",
            start_s=start,
            end_s=end,
            out=target,
            spawn=spawn,
            serve=serve,
            on_served=_wait_for_ctrl_c,
            engines=runners,
            bind=bind,
        )
    finally:
        drive.close()
    typer.echo(
        f"{summary.frames} frames, {summary.actors_seen} actors, {summary.duration_s:.1f} s of "
        f"drive in {summary.elapsed_s:.2f} s ({summary.frames_per_s:.0f} frames/s)"
    )
    for name, unsafe in summary.unsafe_frames.items():
        count = sum(1 for v in summary.violations if v.engine == name)
        typer.echo(f"{name}: {unsafe} unsafe frames in {count} violation interval(s)")
    if target is not None:
        typer.echo(f"wrote {target}")
        typer.echo(f"open it with: rerun {target}")
    if summary.stopped_by is not None:
        typer.echo(f"stopped early: the recording holds the {summary.frames} readable frames")
        raise summary.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``replay`` to the CLI."""
    app.command("replay")(replay)
