"""A results directory as one review queue: every drive's incidents, worst first.

Nothing is evaluated again: the incidents are read back from ``incidents.parquet`` as the
same :class:`~workbench.incidents.Incident` records the single-drive commands use, so the
filters and the order are theirs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from workbench.batch.executors import BatchError
from workbench.batch.results import INCIDENTS_SCHEMA
from workbench.incidents.model import Incident, Severity
from workbench.incidents.order import severity_key
from workbench.outputs import atomic_output, json_text, write_text

if TYPE_CHECKING:
    from collections.abc import Iterable

__all__ = ["FleetIncident", "load_queue", "read_table", "write_queue"]

#: Severity columns that are :class:`Severity` fields, not facts.
_SEVERITY_FIELDS = ("worst_margin", "unsafe_frames", "duration_s")


@dataclass(frozen=True, slots=True)
class FleetIncident:
    """An incident of one drive of a batch.

    Attributes:
        drive_path: The drive as the batch named it.
        drive_hash: The drive's content hash (what labels are keyed by).
        drive_start_ns: The drive's first time stamp (0 if unknown).
        incident: The incident.
        row: Its ``incidents.parquet`` row.
    """

    drive_path: str
    drive_hash: str
    drive_start_ns: int
    incident: Incident
    row: dict[str, Any]

    def rank_key(self) -> tuple[Any, ...]:
        """Worst first across drives: the incidents' own order, then drive and time."""
        i = self.incident
        return (*severity_key(i)[:-2], self.drive_path, i.start_ns, i.id)


def read_table(results: Path, name: str) -> list[dict[str, Any]]:
    """The rows of ``RESULTS/<name>`` (``incidents.parquet`` or ``drives.parquet``).

    Raises:
        BatchError: The file is missing, unreadable, or of another schema.
    """
    import pyarrow.parquet as pq  # noqa: PLC0415 - only when reading results

    path = results / name
    try:
        table = pq.read_table(path)
    except (OSError, ValueError) as err:
        raise BatchError(f"{path}: cannot read the batch's table ({err})") from err
    schema = (table.schema.metadata or {}).get(b"rss_workbench.schema", b"").decode()
    if name == "incidents.parquet" and schema != INCIDENTS_SCHEMA:
        msg = f"{path}: incident rows of schema {schema or 'none'!r}, expected {INCIDENTS_SCHEMA}"
        raise BatchError(msg)
    rows: list[dict[str, Any]] = table.to_pylist()
    return rows


def incident_of(row: dict[str, Any]) -> Incident:
    """The :class:`Incident` an ``incidents.parquet`` row holds (its facts in their order)."""
    names = row.get("severity_names") or [
        k.removeprefix("severity.")
        for k, v in row.items()
        if k.startswith("severity.") and v is not None
    ]
    facts: dict[str, Any] = {
        name: row.get(f"severity.{name}")
        for name in names
        if not name.startswith("severity_rank")  # derived from the facts (incidents.order)
    }
    margin = facts.pop("worst_margin", None)
    severity = Severity(
        worst_margin=math.inf if margin is None else float(margin),
        unsafe_frames=int(facts.pop("unsafe_frames", 0)),
        duration_s=float(facts.pop("duration_s", 0.0)),
        facts=facts,
    )
    return Incident(
        id=row["id"],
        engine=row["engine"],
        objects=tuple(row["objects"] or ()),
        cause=row["cause"],
        start_frame=int(row["start_frame"]),
        end_frame=int(row["end_frame"]),
        start_ns=int(row["start_ns"]),
        end_ns=int(row["end_ns"]),
        severity=severity,
        data_suspect=tuple(row.get("data_suspect") or ()),
    )


def load_queue(results: Path) -> list[FleetIncident]:
    """Every incident of the batch in ``results``, worst first across drives.

    Raises:
        BatchError: The tables cannot be read.
    """
    starts = {d["path"]: int(d["start_ns"] or 0) for d in read_table(results, "drives.parquet")}
    queue = [
        FleetIncident(
            row["drive_path"],
            row["drive_hash"],
            starts.get(row["drive_path"], 0),
            incident_of(row),
            row,
        )
        for row in read_table(results, "incidents.parquet")
    ]
    return sorted(queue, key=FleetIncident.rank_key)


def write_queue(incidents: Iterable[FleetIncident], path: Path) -> None:
    """Write the incidents' rows as ``.parquet``, ``.json`` (a list) or ``.csv``, atomically.

    Raises:
        BatchError: Unknown suffix, or the file cannot be written.
    """
    rows = [f.row for f in incidents]
    if path.suffix == ".json":
        write_text(path, json_text(rows, indent=2) + "\n", "the incident list")
        return
    if path.suffix not in {".parquet", ".csv"}:
        raise BatchError(f"{path}: must end in .parquet, .json or .csv, not {path.suffix!r}")
    import pyarrow as pa  # noqa: PLC0415
    import pyarrow.csv as pcsv  # noqa: PLC0415
    import pyarrow.parquet as pq  # noqa: PLC0415

    if path.suffix == ".csv":  # lists (objects, fact names, sort keys) as space-separated text
        rows = [
            {k: " ".join(map(str, v)) if isinstance(v, list) else v for k, v in r.items()}
            for r in rows
        ]
    table = pa.Table.from_pylist(rows)
    with atomic_output(path, "the incident list") as part:
        try:
            if path.suffix == ".csv":
                pcsv.write_csv(table, part)
            else:
                pq.write_table(table, part)
        except pa.ArrowException as err:
            raise BatchError(f"{path}: cannot write ({err})") from err


def drive_name(drive_path: str) -> str:
    """The drive's file (or rosbag2 directory) name, for tables."""
    return Path(drive_path).name
