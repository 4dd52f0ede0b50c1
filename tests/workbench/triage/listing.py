"""What ``workbench incidents FILE`` lists by default on a drive, read from its JSON output.

The command runs in-process with nothing but ``--out FILE.json``, so every default (engines,
RSS profile, grouping into events) is the command's. The listing is read tolerantly: an entry
is either an incident record (``objects``, ``start_ns``, ``end_ns``) or an event holding its
incident records under ``incidents``; either way it yields the entry's objects, time span and
the incidents it stands for.
"""

from __future__ import annotations

import contextlib
import functools
import io
import json
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tests.workbench.cli_runs import run_workbench

#: An entry covers a conflict when their time spans come within this of each other [s].
SPAN_TOLERANCE_S = 0.5


@dataclass(frozen=True, slots=True)
class Entry:
    """One listed entry (event or incident), in list order.

    Attributes:
        rank: 1 for the first listed.
        id: The entry's id.
        objects: Every object of the entry (and of its incidents).
        start_ns: Earliest start of the entry or its incidents.
        end_ns: Latest end.
        incidents: The incident records it stands for (itself for an incident).
        record: The entry's own JSON record.
    """

    rank: int
    id: str
    objects: tuple[str, ...]
    start_ns: int
    end_ns: int
    incidents: tuple[dict[str, Any], ...]
    record: dict[str, Any]

    def covers(self, conflict: dict[str, Any], dt_ns: int) -> bool:
        """Whether the entry has the conflict's object and a span within the tolerance of its.

        ``conflict``: ``object`` and ``steps`` (first, last) of the independent measure;
        ``dt_ns``: the scenario's time step.
        """
        first, last = conflict["steps"]
        tolerance_ns = int(SPAN_TOLERANCE_S * 1e9)
        return (
            conflict["object"] in self.objects
            and self.start_ns <= last * dt_ns + tolerance_ns
            and self.end_ns >= first * dt_ns - tolerance_ns
        )

    def describe(self) -> str:
        """``#rank id objects [start, end] s`` for messages."""
        return (
            f"#{self.rank} {self.id} objects {','.join(self.objects) or '-'} "
            f"[{self.start_ns / 1e9:.1f}, {self.end_ns / 1e9:.1f}] s"
        )


def _entry(rank: int, record: dict[str, Any]) -> Entry:
    parts = record.get("incidents")
    incidents = tuple(p for p in parts if isinstance(p, dict)) if isinstance(parts, list) else ()
    pieces = (*incidents, record) if incidents else (record,)
    objects = sorted({str(o) for p in pieces for o in p.get("objects", ())})
    starts = [int(p["start_ns"]) for p in pieces if "start_ns" in p]
    ends = [int(p["end_ns"]) for p in pieces if "end_ns" in p]
    return Entry(
        rank=rank,
        id=str(record.get("id", "?")),
        objects=tuple(objects),
        start_ns=min(starts),
        end_ns=max(ends),
        incidents=incidents or (record,),
        record=record,
    )


@functools.cache
def default_listing(xml: Path) -> tuple[Entry, ...]:
    """``workbench incidents XML --out FILE.json`` read back, worst first."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "incidents.json"
        with contextlib.redirect_stdout(io.StringIO()):  # the table; the file is read
            code = run_workbench(["incidents", str(xml), "--out", str(out)])
        if code != 0:
            raise AssertionError(f"workbench incidents {xml.name} exited {code}")
        records = json.loads(out.read_text())
    if isinstance(records, dict):  # a wrapper object: its list of entries
        records = next(v for v in records.values() if isinstance(v, list))
    return tuple(_entry(rank, r) for rank, r in enumerate(records, start=1))
