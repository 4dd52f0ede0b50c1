"""The ``data_quality`` section of ``workbench incidents --out FILE``: a file beside it.

``FILE.json`` keeps its pinned shape (a list of incidents); the drive's data quality goes to
``FILE.data_quality.json`` (resp. ``.csv``, ``.parquet``):

- JSON: ``{"counts": {kind: n}, "objects": [..], "findings": [..], "suspect": {incident id:
  [reasons]}}`` (:func:`~workbench.quality.summary.quality_record`, finite numbers only);
- CSV / Parquet: one row per finding (:meth:`Finding.record`) with ``suspect_incidents``,
  the ids of the incidents it makes suspect (space-separated in CSV).
"""

from __future__ import annotations

import csv
from typing import TYPE_CHECKING, Any

from workbench.outputs import atomic_output, json_text
from workbench.quality.summary import quality_record
from workbench.quality.suspect import suspect_reasons

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from workbench.incidents.model import Incident
    from workbench.quality.checks import Finding

__all__ = ["quality_path", "write_quality"]

_COLUMNS = (
    "object_id",
    "kind",
    "start_frame",
    "end_frame",
    "start_ns",
    "end_ns",
    "frames",
    "value",
    "bound",
    "unit",
    "suspect_incidents",
)


def quality_path(out: Path) -> Path:
    """Where the data-quality section of the incidents file ``out`` goes."""
    return out.with_name(f"{out.stem}.data_quality{out.suffix}")


def _rows(findings: Sequence[Finding], incidents: Sequence[Incident]) -> list[dict[str, Any]]:
    return [
        {
            **f.record(),
            "suspect_incidents": [i.id for i in incidents if suspect_reasons(i, (f,))],
        }
        for f in findings
    ]


def write_quality(findings: Sequence[Finding], incidents: Sequence[Incident], out: Path) -> Path:
    """Write the data-quality section beside the incidents file ``out`` (atomically).

    Returns:
        The path written (:func:`quality_path`).

    Raises:
        WorkbenchError: The file cannot be written.
    """
    path = quality_path(out)
    rows = _rows(findings, incidents)
    with atomic_output(path, "the data quality") as tmp:
        if path.suffix == ".json":
            record = quality_record(findings)
            record["suspect"] = {i.id: list(i.data_suspect) for i in incidents if i.data_suspect}
            tmp.write_text(json_text(record, indent=2) + "\n")
        elif path.suffix == ".parquet":
            import pyarrow as pa  # noqa: PLC0415 - only for Parquet output
            import pyarrow.parquet as pq  # noqa: PLC0415

            kinds = {"value": pa.float64(), "bound": pa.float64()}
            kinds.update(dict.fromkeys(("object_id", "kind", "unit"), pa.string()))
            kinds["suspect_incidents"] = pa.list_(pa.string())
            schema = pa.schema([(c, kinds.get(c, pa.int64())) for c in _COLUMNS])
            pq.write_table(pa.Table.from_pylist(rows, schema=schema), tmp)
        else:
            with tmp.open("w", newline="") as fh:
                writer = csv.DictWriter(fh, fieldnames=list(_COLUMNS))
                writer.writeheader()
                for row in rows:
                    writer.writerow(
                        {**row, "suspect_incidents": " ".join(row["suspect_incidents"])}
                    )
    return path
