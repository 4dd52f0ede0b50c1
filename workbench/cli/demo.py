"""``workbench demo``: re-evaluate and replay every sample log of a directory, then summarise."""

from __future__ import annotations

import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from workbench.cli.engines import build_engines, parse_engines
from workbench.cli.replay import default_output, open_log, run_with_progress
from workbench.errors import USER_ERRORS

__all__ = ["DemoRow", "demo", "find_sample_logs", "register"]

#: The log the closing hint suggests opening first.
_FEATURED = "highway_cut_in.mcap"

_LOG_SUFFIXES = (".mcap", ".bag", ".xml", ".saa", ".scn")


def _viewer_command() -> str:
    """``rerun``, or the venv's viewer path when the venv is not on PATH."""
    venv_viewer = Path(sys.executable).with_name("rerun")
    if shutil.which("rerun") is None and venv_viewer.exists():
        return str(venv_viewer)
    return "rerun"


def _drive_key(log: Path) -> str:
    """Name of the drive a log holds: ``x.mcap``, ``x.bag`` and ``x_rosbag2/`` hold drive ``x``."""
    return log.name.removesuffix(log.suffix).removesuffix("_rosbag2")


def primary_logs(logs: list[Path]) -> set[Path]:
    """One log per drive to evaluate: the ``.mcap`` if there is one, else a rosbag2, else a bag."""
    best: dict[str, Path] = {}
    for log in sorted(logs, key=lambda p: (_NAME_PRIORITY.get(p.suffix.lower(), 9), p.name)):
        best.setdefault(_drive_key(log), log)
    return set(best.values())


def _is_rosbag2_dir(path: Path) -> bool:
    return path.is_dir() and (path / "metadata.yaml").is_file()


def find_sample_logs(samples_dir: Path) -> list[Path]:
    """Drives directly in ``samples_dir``, sorted by name.

    Drives are ``*.mcap``, ``*.bag``, CommonRoad ``*.xml`` and ScenarioArchitect
    ``*.saa``/``*.scn`` files and rosbag2 directories (a directory holding ``metadata.yaml``).
    """
    found = [
        p
        for p in samples_dir.iterdir()
        if (p.is_file() and p.suffix.lower() in _LOG_SUFFIXES) or _is_rosbag2_dir(p)
    ]
    return sorted(found, key=lambda p: p.name)


#: Which log keeps the plain ``<stem>.rrd`` name when several share a stem (lowest first).
_NAME_PRIORITY = {".mcap": 0, "": 1, ".bag": 2, ".xml": 3}


def output_names(logs: list[Path]) -> dict[Path, str]:
    """``.rrd`` file name per log, never the same for two logs.

    A log gets ``<stem>.rrd``, or ``<stem>_<suffix>.rrd`` when its stem is already taken; an
    ``.mcap`` keeps the plain name first, then a rosbag2 directory, then a ``.bag``.
    """
    taken: set[str] = set()
    names: dict[Path, str] = {}
    for log in sorted(logs, key=lambda p: (_NAME_PRIORITY.get(p.suffix.lower(), 9), p.name)):
        stem = default_output(log, Path()).stem
        if stem in taken:
            stem = f"{stem}_{log.suffix.lstrip('.').lower() or 'dir'}"
        taken.add(stem)
        names[log] = f"{stem}.rrd"
    return names


@dataclass(frozen=True, slots=True)
class DemoRow:
    """One line of the summary table; ``error`` is set when the log could not be replayed."""

    log: str
    source_format: str = ""
    frames: int = 0
    actors: int = 0
    duration_s: float = 0.0
    frames_per_s: float = 0.0
    output: str = ""
    unsafe: dict[str, int] | None = None
    violations: int | None = None
    error: str = ""


def _replay_one(log: Path, target: Path, engine_names: list[str]) -> DemoRow:
    try:
        drive = open_log(log, map_path=None, profile=None, ego_id=None)
        try:
            engines = build_engines(drive, engine_names, "turn", full_geometry=True)
            s = run_with_progress(
                drive,
                label=f"evaluate + replay {log.name}",
                start_s=None,
                end_s=None,
                out=target,
                engines=engines,
            )
        finally:
            drive.close()
    except USER_ERRORS as err:
        return DemoRow(log=log.name, error=str(err))
    if s.stopped_by is not None:
        return DemoRow(
            log=log.name, error=f"{s.frames} frames kept in {target}, then: {s.stopped_by}"
        )
    return DemoRow(
        log=log.name,
        source_format=s.source_format,
        frames=s.frames,
        actors=s.actors_seen,
        duration_s=s.duration_s,
        frames_per_s=s.frames_per_s,
        output=target.name,
        unsafe=dict(s.unsafe_frames) if engine_names else None,
        violations=len(s.violations) if engine_names else None,
    )


#: Short engine names of the summary table.
_SHORT = {"reachsets": "reach", "rss": "rss", "unstructured": "unstr."}


def _unsafe_cell(unsafe: dict[str, int] | None) -> str:
    """``reach 120  rss 80  unstr. 0``, or ``-`` for a log that was not evaluated."""
    if unsafe is None:
        return "-"
    return "  ".join(f"{_SHORT.get(name, name)} {n}" for name, n in unsafe.items())


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
    *,
    out: Annotated[Path, typer.Option("--out", help="Directory for the .rrd files.")] = Path(
        "out/demo"
    ),
    engines: Annotated[
        str, typer.Option("--engines", help="Engines evaluated on every frame ('' for none).")
    ] = "reachsets,rss,unstructured",
) -> None:
    """Re-evaluate every sample log in SAMPLES_DIR, replay it into OUT/<name>.rrd, summarise."""
    from workbench.replay.run import ReplayError  # noqa: PLC0415

    if not samples_dir.is_dir():
        raise ReplayError(f"{samples_dir}: not a directory")
    logs = find_sample_logs(samples_dir)
    if not logs:
        raise ReplayError(f"{samples_dir}: no .mcap, .bag, rosbag2 directory or .xml found")
    names = output_names(logs)
    engine_names = parse_engines(engines)
    # The .bag and rosbag2 variants hold the same drive as the .mcap of that name: evaluate
    # one log per drive (the one keeping the plain name), replay the others only.
    primary = primary_logs(logs)
    rows = [
        _replay_one(log, out / names[log], engine_names if log in primary else []) for log in logs
    ]
    console = Console(width=max(Console().width, 120))
    console.print(_table(rows))
    for r in rows:
        if r.error:
            console.print(f"[red]failed:[/red] {r.error}", highlight=False, soft_wrap=True)
    done = [r for r in rows if not r.error]
    if done:
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
    app.command("demo")(demo)
