"""``workbench evaluate``: re-evaluate a drive frame by frame with the safety engines."""

from __future__ import annotations

import json
from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.table import Table

from workbench.cli.engines import ReachMethodOption, build_engines, parse_engines
from workbench.cli.progress import frame_progress
from workbench.cli.replay import open_log, window_ns
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from workbench.evaluate.violations import Violation

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
            f"{(v.start_ns - t0_ns) / 1e9:.2f}",
            " ".join(v.objects[:5]),
            f"{v.worst_margin:.2f}",
        )
    return table


def evaluate(
    log: Annotated[Path, typer.Argument(help="Drive: .mcap, .bag, rosbag2 dir, .xml, .saa.")],
    *,
    map_path: Annotated[Path | None, typer.Option("--map", help="Lane map file.")] = None,
    profile: Annotated[Path | None, typer.Option("--profile", help="TOML topic profile.")] = None,
    ego_id: Annotated[str | None, typer.Option("--ego-id", help="CommonRoad ego id.")] = None,
    engines: Annotated[
        str, typer.Option("--engines", help="Comma-separated: rss, unstructured, reachsets.")
    ] = "reachsets",
    reach_method: Annotated[
        ReachMethodOption, typer.Option("--reach-method", help="Reachable-set method.")
    ] = ReachMethodOption.turn,
    per_frame: Annotated[
        Path | None, typer.Option("--per-frame", help="Write one JSON line per frame here.")
    ] = None,
    violations: Annotated[
        Path | None, typer.Option("--violations", help="Write the violations (.json/.csv).")
    ] = None,
    start: Annotated[float | None, typer.Option("--start", help="Seconds from start.")] = None,
    end: Annotated[float | None, typer.Option("--end", help="Seconds from start.")] = None,
) -> None:
    """Re-evaluate every frame; print the violations, optionally write per-frame JSON lines."""
    from workbench.evaluate.pipeline import evaluate_frames  # noqa: PLC0415
    from workbench.evaluate.violations import (  # noqa: PLC0415
        detect_violations,
        write_violations,
    )

    names = parse_engines(engines)
    if not names:
        raise WorkbenchError("--engines: name at least one engine")
    drive = open_log(log, map_path=map_path, profile=profile, ego_id=ego_id)
    try:
        runners = build_engines(drive, names, reach_method.value)
        start_ns, end_ns = window_ns(drive, start, end)
        results = []
        sink = None
        if per_frame is not None:
            per_frame.parent.mkdir(parents=True, exist_ok=True)
            sink = per_frame.with_name(f".{per_frame.name}.tmp").open("w")
        try:
            with frame_progress() as bar:
                task = bar.add_task(f"evaluate {log.name}", total=drive.info.frame_count or None)
                frames = drive.frames(start_ns, end_ns)
                for _frame, result in evaluate_frames(frames, runners):
                    results.append(result)
                    if sink is not None:
                        sink.write(json.dumps(result.record()) + "\n")
                    bar.advance(task)
        finally:
            if sink is not None:
                sink.close()
        if per_frame is not None:
            per_frame.with_name(f".{per_frame.name}.tmp").replace(per_frame)
    finally:
        drive.close()
    t0_ns = drive.info.start_ns
    found = detect_violations(results, log.name)
    unsafe = sum(1 for r in results if not all(o.is_safe for o in r.outputs.values()))
    typer.echo(f"{len(results)} frames evaluated with {', '.join(names)}; {unsafe} unsafe")
    if found:
        Console().print(_summary_table(found, t0_ns))
    typer.echo(f"{len(found)} violation interval(s)")
    if violations is not None:
        violations.parent.mkdir(parents=True, exist_ok=True)
        write_violations(found, violations)
        typer.echo(f"wrote {violations}")
    if per_frame is not None:
        typer.echo(f"wrote {per_frame}")


def register(app: typer.Typer) -> None:
    """Add ``evaluate`` to the CLI."""
    app.command("evaluate")(evaluate)
