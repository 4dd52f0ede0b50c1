"""``workbench replay``: send a drive to Rerun (``.rrd`` file, native viewer or local server)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.losses import VerboseOption, echo_losses
from workbench.cli.options import GrpcPortOption, LogArgument, WebPortOption  # noqa: TC001
from workbench.cli.progress import run_with_progress
from workbench.cli.request_options import RequestCommand
from workbench.drives import default_output

if TYPE_CHECKING:
    from workbench.incidents import IncidentRequest

__all__ = ["register", "replay"]


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
    log: LogArgument,
    request: IncidentRequest,
    *,
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
    grpc_port: GrpcPortOption = 9876,
    web_port: WebPortOption = 9090,
    start: Annotated[
        float | None, typer.Option("--start", help="Seconds from the drive start.")
    ] = None,
    end: Annotated[
        float | None, typer.Option("--end", help="Seconds from the drive start.")
    ] = None,
    verbose: VerboseOption = False,
) -> None:
    """Replay a drive into Rerun: map, ego, actors, plan and plots on timelines frame/log_time."""
    from workbench.viewer.outputs import ReplayError  # noqa: PLC0415

    if sum((out is not None, spawn, serve)) > 1:
        raise ReplayError("--out, --spawn and --serve are mutually exclusive")
    target = out if (out is not None or spawn or serve) else default_output(log, out_dir)
    drive = request.open_drive()
    try:
        runners, ego_size = request.engines_for(drive, full_geometry=True)
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
            ports=(grpc_port, web_port),
            ego_size=ego_size,
        )
    finally:
        drive.close()
    typer.echo(
        f"{summary.frames} frames, {summary.actors_seen} actors, {summary.duration_s:.1f} s of "
        f"drive in {summary.elapsed_s:.2f} s ({summary.frames_per_s:.0f} frames/s)"
    )
    echo_losses(drive.info.notes, verbose=verbose)
    for name, unsafe in summary.unsafe_frames.items():
        count = sum(1 for v in summary.violations if v.engine == name)
        typer.echo(f"{name}: {unsafe} unsafe frames in {count} violation interval(s)")
    if target is not None and (summary.frames or summary.stopped_by is None):
        typer.echo(f"wrote {target}")
        typer.echo(f"open it with: rerun {target}")
    if summary.stopped_by is not None:
        typer.echo(f"stopped early: the recording holds the {summary.frames} readable frames")
        raise summary.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``replay`` to the CLI."""
    app.command("replay")(
        RequestCommand(replay, inject="request", engines="none", need_engines=False)
    )
