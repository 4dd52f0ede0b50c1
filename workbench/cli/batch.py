"""``workbench batch``: evaluate many drives into one results directory (docs/fleet.md)."""

from __future__ import annotations

from collections.abc import Callable  # noqa: TC003 - typer reads the annotations at run time
from pathlib import Path  # noqa: TC003 - typer reads the annotations at run time
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TextColumn,
    TimeRemainingColumn,
)
from rich.table import Table
from rich.text import Text

from loaders.timebase import ns_to_s
from workbench.batch.executors import BatchError
from workbench.batch.results import is_results_dir
from workbench.cli.incident_options import StoreOption, with_requests
from workbench.cli.progress import STDERR

if TYPE_CHECKING:
    from workbench.batch.diff import DiffResult
    from workbench.batch.run import BatchSummary
    from workbench.incidents import IncidentRequest

__all__ = ["register"]

CLUSTER_HELP = (
    "Run on tcp://HOST:PORT (a Dask scheduler), dask-local:N, ray://HOST:PORT or ray-local:N"
    " (default: a local process pool)."
)


class _Rate(ProgressColumn):
    """Logs per second so far."""

    def render(self, task: Task) -> Text:
        """``1.23 logs/s``."""
        elapsed = task.elapsed or 0.0
        rate = task.completed / elapsed if elapsed > 0 else 0.0
        return Text(f"{rate:.2f} logs/s")


def _progress() -> Progress:
    return Progress(
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        _Rate(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=STDERR,
        transient=True,
    )


def _summary(summary: BatchSummary, out: Path) -> None:
    counts = {
        s: sum(d["status"] == s for d in summary.drives)
        for s in ("ok", "partial", "empty", "failed")
    }
    incidents = sum(int(d["incidents"]) for d in summary.drives)
    typer.echo(
        f"{len(summary.drives)} log(s) on {summary.executor}: {summary.evaluated} evaluated,"
        f" {summary.skipped} kept from an earlier run; "
        + ", ".join(f"{n} {s}" for s, n in counts.items())
        + f"; {incidents} incident(s) -> {out}"
    )
    for drive in summary.drives:
        if drive["status"] in {"failed", "partial"}:
            lost = f"{drive['path']}: {drive['frames_lost']} ego message(s) not made frames"
            typer.echo(f"{drive['status']}: {drive['error'] or lost}")
    other = [d["path"] for d in summary.drives if d["engine_versions"] != summary.versions]
    if other:
        typer.secho(
            f"warning: {len(other)} log(s) evaluated by workers running other code than this"
            f" command (engine versions differ), e.g. {other[0]}",
            err=True,
            fg=typer.colors.YELLOW,
        )


@with_requests
def batch(
    logs: Annotated[
        list[str],
        typer.Argument(
            help="Drives, directories (searched), glob patterns or fsspec URLs (s3://b/d/*.mcap)."
        ),
    ],
    requests: Callable[[Path], IncidentRequest],
    *,
    out: Annotated[Path, typer.Option("--out", help="Results directory (resumable).")],
    jobs: Annotated[
        int | None,
        typer.Option("--jobs", min=1, help="Local worker processes (default: CPU count)."),
    ] = None,
    cluster: Annotated[str | None, typer.Option("--cluster", help=CLUSTER_HELP)] = None,
) -> None:
    """Evaluate many drives (one task each) into RESULTS: incidents, drives, batch.json."""
    from workbench.batch.executors import open_pool  # noqa: PLC0415 - light start-up
    from workbench.batch.run import expand_logs, request_of, run_batch  # noqa: PLC0415

    chosen = [request_of(log, requests) for log in expand_logs(logs)]
    with _progress() as bar, open_pool(cluster, jobs) as pool:
        task = bar.add_task("batch", total=len(chosen))

        def started(todo: int, kept: int) -> None:
            bar.update(task, total=todo, description=f"batch ({kept} kept)" if kept else "batch")

        def done(_record: dict[str, Any]) -> None:
            bar.advance(task)

        summary = run_batch(chosen, out, pool, on_start=started, on_done=done)
    _summary(summary, out)


_KIND_STYLE = {
    "vanished-confirmed": "bold white on red",
    "vanished": "red",
    "new": "yellow",
    "changed": "cyan",
}


def _diff_table(result: DiffResult, title: str) -> Table:
    from workbench.batch.queue import drive_name  # noqa: PLC0415

    table = Table(title=title)
    for column in ("change", "label", "drive", "engine", "object", "id (A / B)", "what"):
        table.add_column(column, no_wrap=column in {"change", "id (A / B)"})
    for change in result.changes:
        item = change.either
        ids = " / ".join(s.incident.id if s else "-" for s in (change.a, change.b))
        what = "; ".join(f"{k}: {_fmt(a)} -> {_fmt(b)}" for k, (a, b) in change.differences.items())
        if not what:
            i = item.incident
            start_s = ns_to_s(i.start_ns - item.drive_start_ns)
            what = f"{i.cause}, {start_s:.2f} s + {i.duration_s:.2f} s"
        table.add_row(
            Text(change.kind, style=_KIND_STYLE[change.kind]),
            change.verdict or "-",
            drive_name(item.drive_path),
            item.incident.engine,
            " ".join(item.incident.objects) or "-",
            ids,
            what,
        )
    return table


def _fmt(value: object) -> str:
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    return f"{value:.3g}" if isinstance(value, float) else str(value)


def _write_diff(result: DiffResult, path: Path, header: dict[str, Any]) -> None:
    from workbench.batch.diff import rows  # noqa: PLC0415
    from workbench.outputs import finite, json_text, write_text  # noqa: PLC0415

    if path.suffix == ".json":
        body = {**header, "changes": [c.record() for c in result.changes]}
        write_text(path, json_text(body, indent=2) + "\n", "the diff")
    elif path.suffix == ".parquet":
        import pyarrow as pa  # noqa: PLC0415
        import pyarrow.parquet as pq  # noqa: PLC0415

        table = pa.Table.from_pylist(finite(rows(result.changes)))
        pq.write_table(table, path)
    else:
        raise BatchError(f"{path}: diff output must end in .json or .parquet")


def _verdicts(store: Path | None) -> Callable[[str, str], str | None] | None:
    from workbench.annotations.paths import default_store_path  # noqa: PLC0415
    from workbench.annotations.store import LabelStore  # noqa: PLC0415

    path = store or default_store_path()
    if not path.is_file():
        return None
    labels = LabelStore(path)

    def verdict(drive_hash: str, incident_id: str) -> str | None:
        label = labels.label(drive_hash, incident_id)
        return None if label is None else label.verdict

    return verdict


def diff(
    results_a: Annotated[Path, typer.Argument(help="Baseline results directory.")],
    results_b: Annotated[Path, typer.Argument(help="Results directory to compare.")],
    *,
    out: Annotated[
        list[Path] | None, typer.Option("--out", help="Write .json or .parquet (repeatable).")
    ] = None,
    fail_on: Annotated[
        str,
        typer.Option(
            "--fail-on", help="Exit 1 on these: new, vanished, vanished-confirmed, changed."
        ),
    ] = "",
    tolerance: Annotated[
        float, typer.Option("--tolerance", min=0.0, help="Relative tolerance of facts.")
    ] = 0.05,
    store: StoreOption = None,
) -> None:
    """Incidents new, vanished and changed from batch A to batch B, labels joined."""
    from workbench.batch.diff import KINDS, Tolerance, diff_results  # noqa: PLC0415

    wanted = [k.strip() for k in fail_on.split(",") if k.strip()]
    unknown = sorted(set(wanted) - set(KINDS))
    if unknown:
        raise BatchError(f"--fail-on {', '.join(unknown)}: expected some of {', '.join(KINDS)}")
    for path in (results_a, results_b):
        if not is_results_dir(path):
            raise BatchError(f"{path}: not a batch results directory (no batch.json)")
    result = diff_results(
        results_a, results_b, tolerance=Tolerance(rtol=tolerance), verdict_of=_verdicts(store)
    )
    counts = {k: result.count(k) for k in ("new", "vanished", "vanished-confirmed", "changed")}
    line = (
        f"{result.drives} drive(s) compared, {result.matched} incident(s) in both: "
        f"{counts['new']} new, {counts['vanished']} vanished "
        f"({counts['vanished-confirmed']} confirmed), {counts['changed']} changed"
    )
    if result.only_a or result.only_b:
        line += f"; not compared: {result.only_a} drive(s) only in A, {result.only_b} only in B"
    Console().print(_diff_table(result, f"{results_a.name} -> {results_b.name}"))
    typer.echo(line)
    header = {"a": str(results_a), "b": str(results_b), "counts": counts, "tolerance": tolerance}
    for path in out or []:
        _write_diff(result, path, header)
        typer.echo(f"wrote {path}")
    failing = [k for k in wanted if counts[k]]
    if failing:
        typer.secho(f"failing: {', '.join(failing)}", err=True, fg=typer.colors.RED)
        raise typer.Exit(1)


def register(app: typer.Typer) -> None:
    """Add ``batch`` and ``diff`` to the CLI."""
    app.command("batch")(batch)
    app.command("diff")(diff)
