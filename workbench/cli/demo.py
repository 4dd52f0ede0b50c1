"""``workbench demo``: re-evaluate and replay every sample log of a directory, then summarise."""

from __future__ import annotations

import dataclasses
import shutil
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.table import Table

from workbench.cli.progress import run_with_progress
from workbench.cli.request_options import RequestCommand
from workbench.demo import find_sample_logs, output_names, primary_logs, replay_one
from workbench.engines.registry import cli_options, engine
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from loaders.drive import Drive
    from workbench.demo import DemoRow
    from workbench.driver.run import EgoSize
    from workbench.engines.base import BoundRunner
    from workbench.incidents import IncidentRequest
    from workbench.viewer.replay import ReplaySummary

__all__ = ["demo", "register"]

#: The log the closing hint suggests opening first.
_FEATURED = "highway_cut_in.mcap"


def _viewer_command() -> str:
    """``rerun``, or the venv's viewer path when the venv is not on PATH."""
    venv_viewer = Path(sys.executable).with_name("rerun")
    if shutil.which("rerun") is None and venv_viewer.exists():
        return str(venv_viewer)
    return "rerun"


def _replay(
    drive: Drive, target: Path, runners: Sequence[BoundRunner], ego_size: EgoSize | None
) -> ReplaySummary:
    return run_with_progress(
        drive,
        label=f"evaluate + replay {drive.info.path.name}",
        start_s=None,
        end_s=None,
        out=target,
        engines=runners,
        ego_size=ego_size,
    )


def _unsafe_cell(unsafe: dict[str, int] | None) -> str:
    """``reach 120  rss 80  unstr. 0``, or ``-`` for a log that was not evaluated."""
    if unsafe is None:
        return "-"
    return "  ".join(f"{engine(name).short} {n}" for name, n in unsafe.items())


def _options_line(request: IncidentRequest) -> str:
    """``reach_method turn, ..., rss_profile auto`` (``auto``: per drive, docs/rss.md)."""
    record = request.record()
    return ", ".join(f"{key} {record[key]}" for key in cli_options() if record.get(key) is not None)


def _table(rows: list[DemoRow]) -> Table:
    table = Table(title="workbench demo", title_justify="left")
    numeric = {"frames", "actors", "unsafe", "violations", "frames/s"}
    columns = ("log", "format", "frames", "actors", "duration", "unsafe frames", "violations")
    for name in (*columns, "frames/s", "output"):
        table.add_column(name, justify="right" if name in numeric else "left", overflow="fold")
    for r in rows:
        if r.error:
            table.add_row(r.log, "[red]failed[/red]", *[""] * 7)
            continue
        table.add_row(
            r.log,
            r.source_format,
            str(r.frames),
            str(r.actors),
            f"{r.duration_s:.1f} s",
            _unsafe_cell(r.unsafe),
            "-" if r.violations is None else str(r.violations),
            f"{r.frames_per_s:.0f}",
            r.output,
        )
    return table


def demo(
    samples_dir: Annotated[Path, typer.Argument(help="Directory of sample logs.")],
    requests: Callable[[Path], IncidentRequest],
    *,
    out: Annotated[Path, typer.Option("--out", help="Directory for the .rrd files.")] = Path(
        "out/demo"
    ),
) -> None:
    """Re-evaluate every sample log in SAMPLES_DIR, replay it into OUT/<name>.rrd, summarise."""
    if not samples_dir.is_dir():
        raise WorkbenchError(f"{samples_dir}: not a directory")
    logs = find_sample_logs(samples_dir)
    if not logs:
        raise WorkbenchError(f"{samples_dir}: no .mcap, .bag, rosbag2 directory or .xml found")
    names = output_names(logs)
    # The .bag and rosbag2 variants hold the same drive as the .mcap of that name: evaluate
    # one log per drive (the one keeping the plain name), replay the others only.
    primary = primary_logs(logs)
    chosen = [requests(log) for log in logs]
    engine_names = chosen[0].engines
    rows = [
        replay_one(
            r if r.log in primary else dataclasses.replace(r, engines=()),
            out / names[r.log],
            _replay,
        )
        for r in chosen
    ]
    console = Console(width=max(Console().width, 120))
    console.print(_table(rows))
    for r in rows:
        if r.error:
            console.print(f"[red]failed:[/red] {r.error}", highlight=False, soft_wrap=True)
    done = [r for r in rows if not r.error]
    if done:
        console.print(f"engine options: {_options_line(chosen[0])}", highlight=False)
        console.print(f"{len(done)} of {len(rows)} logs written to {out.resolve()}/")
        if engine_names:
            console.print(
                f"unsafe frames and violation intervals: {', '.join(engine_names)}, evaluated "
                "once per drive ('-': another format of a drive already evaluated)"
            )
        first = next((r for r in done if r.output == names.get(samples_dir / _FEATURED)), done[0])
        console.print("open one in the Rerun viewer with:")
        # never wrapped: the line must stay one command a user can copy, however long the path
        command = f"  {_viewer_command()} {out / first.output}"
        console.print(command, highlight=False, soft_wrap=True)
    if not done:
        raise typer.Exit(1)


def register(app: typer.Typer) -> None:
    """Add ``demo`` to the CLI."""
    app.command("demo")(RequestCommand(demo, inject="requests", drive=False, need_engines=False))
