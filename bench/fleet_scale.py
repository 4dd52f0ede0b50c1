"""The fleet section's second half: cost versus drive length, and what 1 000 nodes need.

Every number is derived from the run's measurements (:mod:`bench.bench_fleet`); the 1 h
drive is measured (a quick run fits it linearly from the shorter ones, labelled so).
"""

from __future__ import annotations

from typing import Any

__all__ = ["NODE_CORES", "fit", "scale_lines"]

#: Cores per node assumed for the 1 000-node estimate (a common cloud node; not measured).
NODE_CORES = 32
_HOUR_FRAMES = 3600 * 20 + 1
_NODES = 1000
_FLEET = 1_000_000


def fit(points: list[tuple[float, float]]) -> tuple[float, float]:
    """Least-squares ``(a, b)`` of ``y = a + b * x`` over ``(x, y)`` points (two or more)."""
    n = len(points)
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((x - mx) ** 2 for x, _ in points)
    b = sum((x - mx) * (y - my) for x, y in points) / sxx if sxx > 0 else 0.0
    return my - b * mx, b


def _gib(n_bytes: float) -> str:
    return f"{n_bytes / 2**30:,.1f} GiB" if n_bytes < 2**40 else f"{n_bytes / 2**40:,.1f} TiB"


def scale_lines(m: dict[str, Any]) -> list[str]:
    """Markdown lines: the length table, the 1 h drive and the 1 000-node estimate."""
    lengths = m["lengths"]
    lines = [
        "",
        f"Cost versus drive length ({m['objects_per_frame']} objects per frame, one process):",
        "",
        "| drive length | frames | s per drive | ms per frame | log MiB | incidents |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    lines += [
        f"| {c['length_s'] / 60:g} min (measured) | {c['frames']} | {c['wall_s']:.2f} |"
        f" {c['ms_per_frame']:.2f} | {c['log_bytes'] / 2**20:.1f} | {c['incidents']} |"
        for c in lengths
    ]
    a, b = fit([(c["frames"], c["wall_s"]) for c in lengths])
    hour = next((c for c in lengths if c["frames"] >= _HOUR_FRAMES), None)
    how = "measured" if hour is not None else "extrapolated"
    if hour is not None:
        hour_s, hour_bytes = float(hour["wall_s"]), float(hour["log_bytes"])
    else:  # a quick run: the hour from a linear fit of the shorter drives, labelled so
        a_log, b_log = fit([(c["frames"], c["log_bytes"]) for c in lengths])
        hour_s, hour_bytes = a + b * _HOUR_FRAMES, a_log + b_log * _HOUR_FRAMES
        lines.append(
            f"| 60 min (**extrapolated**: linear fit of the rows above) | {_HOUR_FRAMES} |"
            f" {hour_s:.0f} | {1e3 * hour_s / _HOUR_FRAMES:.2f} | {hour_bytes / 2**20:.0f} | - |"
        )
    runs = m["runs"]
    p1, p2 = runs[0], runs[1]
    dask = next((r for r in runs if r["executor"].startswith("dask")), None)
    per_drive_s = p1["wall_s"] / p1["drives"]
    cores = _NODES * NODE_CORES
    total_core_h = _FLEET * hour_s / 3600
    wall_h = total_core_h / cores
    per_incident = p1["incidents_bytes"] / max(p1["incidents"], 1)
    longest = lengths[-1]
    incidents_per_h = longest["incidents"] * 3600 / longest["length_s"]
    record = p1["record_bytes"] / p1["drives"]
    drive_row = p1["drives_bytes"] / p1["drives"]
    lines += [
        "",
        "### What 1 000 nodes and 1 M drives need (from this run's numbers)",
        "",
        f"Assumed: 1 M drives of 1 h with {m['objects_per_frame']} objects per frame, 1 000",
        f"nodes of {NODE_CORES} cores (the node size is an assumption, the rest is measured here).",
        "",
        (
            f"- **Compute**: {hour_s:.0f} core-s per 1 h drive ({how} above) is"
            f" {total_core_h:,.0f} core-hours for the fleet, {wall_h:,.1f} h of wall time on"
            f" {cores:,} cores if they scale linearly (one task per core, no shared state"
            " between tasks; this run's 2-versus-1 figures are too noisy on a loaded machine"
            " to measure the efficiency). Short drives cost a fixed part too: the"
            f" {m['length_s']:g} s drives of the batch took {per_drive_s:.2f} s each on one worker"
            f" (fit intercept {a:.2f} s per drive: opening the log and map, building the scene)."
        ),
        (
            f"- **Input from object storage**: {hour_bytes / 2**20:.0f} MiB per 1 h MCAP"
            f" ({how}), {_gib(_FLEET * hour_bytes)} for the fleet; a core consumes"
            f" {hour_bytes / hour_s / 2**20:.2f} MiB/s, a {NODE_CORES}-core node"
            f" {NODE_CORES * hour_bytes / hour_s / 2**20:.0f} MiB/s — logs are read where the task"
            " runs, never through the scheduler: by path on a file system the workers share, or"
            " at any fsspec URL (`s3://`, `gcs://`, `http://`), which each task fetches into its"
            f" worker's temporary directory ({_gib(NODE_CORES * hour_bytes)} of local disk per"
            f" {NODE_CORES}-core node for the logs in flight; the fetch's CPU cost is in"
            " docs/fleet.md)."
        ),
        (
            f"- **Results**: {per_incident:.0f} B per incident row in `incidents.parquet` (this"
            f" batch), {incidents_per_h:.0f} incidents per drive-hour (the"
            f" {longest['length_s'] / 60:g} min drive, scaled) give"
            f" {_gib(_FLEET * incidents_per_h * per_incident)} of incident rows;"
            f" `drives.parquet` {drive_row:.0f} B per drive, {_gib(_FLEET * drive_row)}. What"
            f" travels back per task is the record ({record / 1024:.1f} KiB per drive here, one"
            " `logs/<key>.json` each)."
        ),
        (
            "- **Scheduler and driver limits**: at 1 h per task the scheduler hands out"
            f" {cores / hour_s:.1f} tasks/s over {cores:,} cores (the rate follows drive"
            " length, not fleet size: 15 s drives would need up to 240 times that). The limits at"
            " 1 M drives are ours: `run_batch` keeps every request in memory, `logs/` holds one"
            " file per drive (1 M files in one directory) and the final tables are assembled"
            " in one process. So: shard the batch (one results directory per shard, e.g. per"
            " day or vehicle) and concatenate the Parquet files, which share one schema."
        ),
    ]
    if dask is not None:
        extra = (dask["wall_s"] - p2["wall_s"]) / dask["drives"]
        lines.append(
            f"- **Dask versus the process pool** (both 2 workers, this run): {extra * 1e3:+.0f}"
            " ms of wall time per task (scheduler round trips, serialising request and record,"
            " and this machine's noise), against seconds of work per drive."
        )
    return lines
