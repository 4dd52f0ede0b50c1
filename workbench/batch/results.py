"""A batch's results directory: one small file per finished log, then three tables.

Layout::

    RESULTS/
      logs/<key>.json     one per finished log (the task's record), written as it arrives
      incidents.parquet   every incident of every drive (schema below), worst first per drive
      drives.parquet      one row per log of the batch (path, hash, format, status, ...)
      batch.json          settings, engine versions, executor, start/end, counts, failed logs

Every file is written to ``<name>.part`` and renamed, so a killed batch leaves whole files
only, and loses only the logs in flight. ``incidents.parquet`` rows (schema
:data:`INCIDENTS_SCHEMA`): ``drive_path``, ``drive_hash``, then the row of ``workbench
incidents --out FILE.parquet`` (:func:`workbench.incidents.table.flat_rows`): ``id``,
``engine``, ``objects``, ``cause``, ``start_frame``, ``end_frame``, ``start_ns``, ``end_ns``,
``duration_s`` and every severity fact as ``severity.<name>``; last ``severity_names``, the
names of the incident's facts in their order.
"""

from __future__ import annotations

import hashlib
import json
from typing import TYPE_CHECKING, Any

from workbench.batch.executors import BatchError
from workbench.outputs import atomic_output, json_text, write_text

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence
    from pathlib import Path

    from workbench.incidents import IncidentRequest

__all__ = [
    "DRIVES_SCHEMA",
    "INCIDENTS_SCHEMA",
    "Results",
    "is_results_dir",
]

#: Version of the ``incidents.parquet`` row schema (Parquet metadata ``rss_workbench.schema``).
INCIDENTS_SCHEMA = "incidents/1"
#: Version of the ``drives.parquet`` row schema.
DRIVES_SCHEMA = "drives/1"

#: Columns of ``drives.parquet`` in order (``engine_versions`` as JSON text).
DRIVE_COLUMNS = (
    "path",
    "content_hash",
    "format",
    "frames",
    "start_ns",
    "duration_s",
    "frames_lost",
    "stopped_by",
    "wall_s",
    "worker",
    "engine_versions",
    "settings_hash",
    "status",
    "error_type",
    "error",
    "incidents",
)

#: The first columns of ``incidents.parquet`` (an empty table has these), by type.
_INCIDENT_BASE = {
    "drive_path": "string",
    "drive_hash": "string",
    "id": "string",
    "engine": "string",
    "objects": "list",
    "cause": "string",
    "start_frame": "int64",
    "end_frame": "int64",
    "start_ns": "int64",
    "end_ns": "int64",
    "duration_s": "double",
}


def is_results_dir(path: Path) -> bool:
    """Whether ``path`` is a batch's results directory (it holds ``batch.json``)."""
    return path.is_dir() and (path / "batch.json").is_file()


def _key(log: str) -> str:
    return hashlib.sha256(log.encode()).hexdigest()[:24]


class Results:
    """A results directory being filled (per-log records) and assembled (tables)."""

    def __init__(self, root: Path) -> None:
        """Open (and create) ``root``.

        Raises:
            BatchError: ``root`` exists and is not a directory, or cannot be created.
        """
        self.root = root
        try:
            (root / "logs").mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise BatchError(f"{root}: cannot create the results directory ({err})") from err

    def record_path(self, log: str) -> Path:
        """Where the record of ``log`` (its path as given to the task) is kept."""
        return self.root / "logs" / f"{_key(log)}.json"

    def put(self, record: dict[str, Any]) -> None:
        """Keep a finished log's record (atomically; NaN and infinities become null)."""
        write_text(
            self.record_path(record["path"]), json_text(record, sort_keys=True), "a batch record"
        )

    def get(self, log: str) -> dict[str, Any] | None:
        """The kept record of ``log``, or ``None`` (none, or unreadable: evaluate again)."""
        try:
            record = json.loads(self.record_path(log).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return record if isinstance(record, dict) and record.get("path") == log else None

    def is_fresh(self, request: IncidentRequest, versions: dict[str, str], s_hash: str) -> bool:
        """Whether the request's log was evaluated with these engine versions, settings, content.

        Keyed by the log's location (path or URL). A local log is hashed again only when a
        record with these versions and settings exists; a URL log is not fetched again: its
        record is kept while the object's :func:`~workbench.batch.remote.stamp` (size and
        modification time or ETag, from metadata) is the one recorded when its content hash
        was computed.
        """
        from workbench.batch.remote import stamp  # noqa: PLC0415
        from workbench.incidents import drive_content_hash  # noqa: PLC0415

        record = self.get(request.location)
        if record is None or record.get("engine_versions") != versions:
            return False
        if record.get("settings_hash") != s_hash:
            return False
        try:
            if request.url is not None:
                return bool(record.get("source_stamp") == stamp(request.url))
            if not request.log.exists():
                return record.get("content_hash") == ""
            return bool(record.get("content_hash") == drive_content_hash(request.log))
        except Exception:  # noqa: BLE001 - unreadable now: evaluate again (the task reports it)
            return False

    def assemble(self, logs: Sequence[str], batch: dict[str, Any]) -> list[dict[str, Any]]:
        """Write ``incidents.parquet``, ``drives.parquet`` and ``batch.json`` for ``logs``.

        Args:
            logs: The batch's logs (paths or URLs), in table order.
            batch: What ``batch.json`` holds besides the counts and the failed logs.

        Returns:
            The drives' records (without their incidents), in ``logs`` order; a log without
            a record (never finished) is left out.
        """
        records = [r for r in (self.get(log) for log in logs) if r is not None]
        incidents = [row for r in records for row in r["incidents"]]
        drives = [_drive_row(r) for r in records]
        self._parquet("incidents.parquet", _incident_table(incidents), INCIDENTS_SCHEMA)
        self._parquet("drives.parquet", _drive_table(drives), DRIVES_SCHEMA)
        counts = {s: sum(d["status"] == s for d in drives) for s in ("ok", "partial", "empty")}
        counts["failed"] = sum(d["status"] == "failed" for d in drives)
        summary = {
            **batch,
            "schemas": {"incidents": INCIDENTS_SCHEMA, "drives": DRIVES_SCHEMA},
            "logs": len(logs),
            "finished": len(records),
            "incidents": len(incidents),
            "status_counts": counts,
            "failed": [
                {"path": d["path"], "error": d["error"]} for d in drives if d["status"] == "failed"
            ],
        }
        text = json_text(summary, indent=2, sort_keys=True) + "\n"
        write_text(self.root / "batch.json", text, "the batch summary")
        return drives

    def _parquet(self, name: str, table: Any, schema: str) -> None:
        import pyarrow.parquet as pq  # noqa: PLC0415 - only when assembling

        table = table.replace_schema_metadata({"rss_workbench.schema": schema})
        with atomic_output(self.root / name, f"the batch's {name}") as part:
            pq.write_table(table, part)


def _drive_row(record: dict[str, Any]) -> dict[str, Any]:
    row = {name: record.get(name) for name in DRIVE_COLUMNS if name != "incidents"}
    row["engine_versions"] = json_text(record.get("engine_versions"), sort_keys=True)
    row["incidents"] = len(record["incidents"])
    return row


def _incident_table(rows: Iterable[dict[str, Any]]) -> Any:
    import pyarrow as pa  # noqa: PLC0415

    rows = list(rows)
    base = {
        name: pa.list_(pa.string()) if kind == "list" else pa.type_for_alias(kind)
        for name, kind in _INCIDENT_BASE.items()
    }
    if not rows:
        return pa.schema(list(base.items())).empty_table()
    names: dict[str, None] = dict.fromkeys(_INCIDENT_BASE)
    for row in rows:
        names.update(dict.fromkeys(row))
    table = pa.Table.from_pylist([{n: row.get(n) for n in names} for row in rows])
    fields = [pa.field(n, base[n]) if n in base else table.schema.field(n) for n in names]
    return table.cast(pa.schema(fields))


def _drive_table(rows: list[dict[str, Any]]) -> Any:
    import pyarrow as pa  # noqa: PLC0415

    types = {
        "frames": pa.int64(),
        "start_ns": pa.int64(),
        "frames_lost": pa.int64(),
        "incidents": pa.int64(),
        "duration_s": pa.float64(),
        "wall_s": pa.float64(),
    }
    schema = pa.schema([(n, types.get(n, pa.string())) for n in DRIVE_COLUMNS])
    return pa.Table.from_pylist(rows, schema=schema)
