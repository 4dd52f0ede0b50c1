"""Incident tables: filters, and the ``--out`` files (JSON, CSV, Parquet)."""

from __future__ import annotations

import csv
from typing import TYPE_CHECKING, Any

from workbench.errors import WorkbenchError
from workbench.outputs import atomic_output, json_text

if TYPE_CHECKING:
    from collections.abc import Collection, Iterable, Mapping
    from pathlib import Path

    from workbench.incidents.model import Incident

__all__ = ["OUT_SUFFIXES", "filter_incidents", "flat_rows", "write_incidents"]

#: Suffixes ``write_incidents`` knows.
OUT_SUFFIXES = (".json", ".csv", ".parquet")


def filter_incidents(
    incidents: Iterable[Incident],
    *,
    engines: Collection[str] = (),
    objects: Collection[str] = (),
    causes: Collection[str] = (),
    max_margin: float | None = None,
) -> list[Incident]:
    """The incidents matching every given filter (an empty filter matches all), order kept.

    Args:
        incidents: Incidents to filter.
        engines: Keep these engines.
        objects: Keep incidents involving one of these object ids.
        causes: Keep incidents whose cause contains one of these texts (case-insensitive).
        max_margin: Keep incidents whose worst margin is at most this (engine units).
    """
    wanted_causes = [c.lower() for c in causes]
    return [
        i
        for i in incidents
        if (not engines or i.engine in engines)
        and (not objects or set(i.objects) & set(objects))
        and (not wanted_causes or any(c in i.cause.lower() for c in wanted_causes))
        and (max_margin is None or i.severity.worst_margin <= max_margin)
    ]


def _flat(record: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    row: dict[str, Any] = {}
    for key, value in record.items():
        if isinstance(value, dict):
            row.update(_flat(value, f"{prefix}{key}."))
        else:
            row[f"{prefix}{key}"] = value
    return row


def _records(
    incidents: Iterable[Incident], events: Mapping[str, str] | None
) -> list[dict[str, Any]]:
    if events is None:
        return [i.record() for i in incidents]
    return [{**i.record(), "event": events.get(i.id)} for i in incidents]


def flat_rows(
    incidents: Iterable[Incident], events: Mapping[str, str] | None = None
) -> list[dict[str, Any]]:
    """One flat row per incident: nested facts as ``severity.<name>`` (``.<name>``) columns."""
    rows = [_flat(record) for record in _records(incidents, events)]
    names: dict[str, None] = {}
    for row in rows:
        names.update(dict.fromkeys(row))
    return [{name: row.get(name) for name in names} for row in rows]


def _write_parquet(rows: list[dict[str, Any]], path: Path) -> None:
    import pyarrow as pa  # noqa: PLC0415 - only for Parquet output
    import pyarrow.parquet as pq  # noqa: PLC0415

    if not rows:
        schema = pa.schema([("id", pa.string()), ("objects", pa.list_(pa.string()))])
        pq.write_table(schema.empty_table(), path)
        return
    pq.write_table(pa.Table.from_pylist(rows), path)


def write_incidents(
    incidents: Iterable[Incident], path: Path, events: Mapping[str, str] | None = None
) -> None:
    """Write incidents as JSON (a list of objects), CSV or Parquet by suffix, atomically.

    ``events``: the event id of each incident id, written as each incident's ``event``.

    Raises:
        WorkbenchError: Unknown suffix, or the file cannot be written.
    """
    found = list(incidents)
    if path.suffix not in OUT_SUFFIXES:
        msg = f"{path}: incidents file must end in {', '.join(OUT_SUFFIXES)}, not {path.suffix!r}"
        raise WorkbenchError(msg)
    with atomic_output(path, "incidents") as tmp:
        if path.suffix == ".json":
            tmp.write_text(json_text(_records(found, events), indent=2) + "\n")
        elif path.suffix == ".parquet":
            _write_parquet(flat_rows(found, events), tmp)
        else:
            rows = flat_rows(found, events)
            with tmp.open("w", newline="") as fh:
                writer = csv.DictWriter(fh, fieldnames=list(rows[0]) if rows else ["id"])
                writer.writeheader()
                for row in rows:
                    lists = {k: " ".join(row[k]) for k in ("objects", "data_suspect")}
                    writer.writerow({**row, **lists})
