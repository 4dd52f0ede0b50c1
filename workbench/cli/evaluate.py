"""``workbench evaluate``: re-evaluate a drive frame by frame with the safety engines."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer
from rich.table import Table

from loaders.timebase import ns_to_s
from workbench.cli.losses import VerboseOption, echo_losses
from workbench.cli.options import LogArgument  # noqa: TC001 - typer reads it at run time
from workbench.cli.progress import frame_progress
from workbench.cli.request_options import RequestCommand
from workbench.cli.tables import print_table
from workbench.drives import window_ns

if TYPE_CHECKING:
    from workbench.incidents import IncidentRequest
    from workbench.sinks.violations import Violation

__all__ = ["register"]


def _summary_table(violations: list[Violation], t0_ns: int) -> Table:
    table = Table(title="violations (first 30)", show_lines=False)
    table.add_column("id", no_wrap=True)
    for column in ("engine", "frames", "start s", "objects", "worst margin"):
        table.add_column(column)
    for v in violations[:30]:
        table.add_row(
            v.id,
            v.engine,
            f"{v.start_frame}-{v.end_frame}",
            f"{ns_to_s(v.start_ns - t0_ns):.2f}",
            " ".join(v.objects[:5]),
            f"{v.worst_margin:.2f}",
        )
    return table


def evaluate(
    log: LogArgument,
    request: IncidentRequest,
    *,
    per_frame: Annotated[
        Path | None, typer.Option("--per-frame", help="Write one JSON line per frame here.")
    ] = None,
    violations: Annotated[
        Path | None, typer.Option("--violations", help="Write the violations (.json/.csv).")
    ] = None,
    start: Annotated[float | None, typer.Option("--start", help="Seconds from start.")] = None,
    end: Annotated[float | None, typer.Option("--end", help="Seconds from start.")] = None,
    verbose: VerboseOption = False,
) -> None:
    """Re-evaluate every frame; print the violations, optionally write per-frame JSON lines."""
    from workbench.driver.evaluate import evaluate_drive  # noqa: PLC0415 - keeps start-up light
    from workbench.sinks.violations import write_violations  # noqa: PLC0415

    names = request.engines
    drive = request.open_drive()
    try:
        runners, ego_size = request.engines_for(drive)
        start_ns, end_ns = window_ns(drive, start, end)
        with frame_progress() as bar:
            task = bar.add_task(f"evaluate {log.name}", total=drive.info.frame_count or None)
            done = evaluate_drive(
                drive,
                runners,
                start_ns=start_ns,
                end_ns=end_ns,
                per_frame=per_frame,
                progress=lambda done: bar.update(task, completed=done),
                ego_size=ego_size,
            )
    finally:
        drive.close()
    found = list(done.violations)
    profiles = "".join(f" ({n} profile {p})" for n, p in done.profiles.items())
    typer.echo(
        f"{done.frames} frames evaluated with {', '.join(names)}{profiles}; "
        f"{done.unsafe_frames} unsafe"
    )
    echo_losses(drive.info.notes, verbose=verbose)
    if found:
        print_table(_summary_table(found, drive.info.start_ns))
    typer.echo(f"{len(found)} violation interval(s)")
    if violations is not None:
        violations.parent.mkdir(parents=True, exist_ok=True)
        write_violations(found, violations)
        typer.echo(f"wrote {violations}")
    if per_frame is not None:
        typer.echo(f"wrote {per_frame}")
    if done.stopped_by is not None:
        typer.echo(f"stopped early: the outputs above cover the {done.frames} readable frames")
        raise done.stopped_by


def register(app: typer.Typer) -> None:
    """Add ``evaluate`` to the CLI."""
    app.command("evaluate")(RequestCommand(evaluate, inject="request"))
