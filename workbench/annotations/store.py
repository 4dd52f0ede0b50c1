"""The label store: SQLite in WAL mode, shared by every command and every reviewer.

Keyed by the drive's content hash and the incident id. Every write is one transaction
(``BEGIN IMMEDIATE`` ... ``COMMIT``), so a process killed at any moment leaves each label
either written whole or not at all; a busy timeout lets several processes write at once.
"""

from __future__ import annotations

import contextlib
import json
import sqlite3
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Self

from workbench.annotations.errors import StoreCorruptError, StoreError, StoreLockedError
from workbench.annotations.schema import (
    SCHEMA_VERSION,
    VERDICTS,
    ReviewVerdict,
    check_tags,
    migrate,
    schema_version,
)
from workbench.outputs import json_text

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence
    from pathlib import Path
    from types import TracebackType

__all__ = ["BUSY_TIMEOUT_S", "Label", "LabelStore"]

#: How long a write waits for another process's transaction [s].
BUSY_TIMEOUT_S = 10.0


@dataclass(frozen=True, slots=True)
class Label:
    """An incident's current review label.

    Attributes:
        drive_hash: Content hash of the drive.
        incident_id: The incident's stable id.
        verdict: The review verdict.
        tags: Free tags, sorted, unique.
        note: Free text.
        reviewer: Who gave the verdict.
        labelled_ns: When this label was written (Unix time [ns]).
        first_labelled_ns: When the incident was first labelled (Unix time [ns]).
        settings: The settings that produced the incident (engines, parameters, merging).
        event_id: The store's id of this write (for undo).
    """

    drive_hash: str
    incident_id: str
    verdict: ReviewVerdict
    tags: tuple[str, ...] = ()
    note: str = ""
    reviewer: str = ""
    labelled_ns: int = 0
    first_labelled_ns: int = 0
    settings: dict[str, Any] = field(default_factory=dict)
    event_id: int = 0


_CURRENT = """
SELECT e.drive_hash, e.incident_id, e.verdict, e.tags, e.note, e.reviewer, e.at_ns,
       (SELECT MIN(f.at_ns) FROM label_events f
         WHERE f.drive_hash = e.drive_hash AND f.incident_id = e.incident_id),
       e.settings, e.event_id
FROM label_events e
WHERE e.event_id = (SELECT MAX(g.event_id) FROM label_events g
                     WHERE g.drive_hash = e.drive_hash AND g.incident_id = e.incident_id)
"""


def _label(row: Sequence[Any]) -> Label:
    return Label(
        drive_hash=row[0],
        incident_id=row[1],
        verdict=ReviewVerdict(row[2]),
        tags=tuple(json.loads(row[3])),
        note=row[4],
        reviewer=row[5],
        labelled_ns=int(row[6]),
        first_labelled_ns=int(row[7]),
        settings=json.loads(row[8]),
        event_id=int(row[9]),
    )


class LabelStore:
    """One connection to a label store file (created and migrated on open)."""

    def __init__(self, path: Path, *, timeout_s: float = BUSY_TIMEOUT_S) -> None:
        """Open (or create) the store at ``path``.

        Raises:
            StoreError: The file cannot be opened; ``StoreCorruptError`` when it is not a
                label store, ``StoreLockedError`` when it stays locked.
        """
        self.path = path
        self.timeout_s = timeout_s
        with self._errors("open"):
            path.parent.mkdir(parents=True, exist_ok=True)
            self._conn = sqlite3.connect(path, timeout=timeout_s, isolation_level=None)
        with self._errors("open"):
            self._wal()
            self._conn.execute("PRAGMA synchronous = FULL")
            found = schema_version(self._conn)
            if found > SCHEMA_VERSION:
                msg = f"schema version {found} is newer than this workbench's {SCHEMA_VERSION}"
                raise StoreCorruptError(f"{path}: label store {msg}")
            if found < SCHEMA_VERSION:
                migrate(self._conn)

    def _wal(self) -> None:
        """Switch to WAL, retrying within ``timeout_s``.

        SQLite answers a journal-mode switch with "database is locked" at once, without its
        busy handler, while another process is switching the same new file.
        """
        deadline = time.monotonic() + self.timeout_s
        while True:
            try:
                self._conn.execute("PRAGMA journal_mode = WAL")
            except sqlite3.OperationalError as err:
                if "locked" not in str(err) or time.monotonic() >= deadline:
                    raise
                time.sleep(0.01)
            else:
                return

    @contextlib.contextmanager
    def _errors(self, action: str) -> Iterator[None]:
        """Turn SQLite and file errors into one-line store errors naming the file."""
        try:
            yield
        except StoreError:
            raise
        except sqlite3.OperationalError as err:
            text = str(err)
            if "locked" in text or "busy" in text:
                msg = f"{self.path}: label store is locked by another process (waited "
                raise StoreLockedError(f"{msg}{self.timeout_s:g} s to {action})") from err
            raise StoreError(f"{self.path}: cannot {action} the label store ({text})") from err
        except sqlite3.DatabaseError as err:
            raise StoreCorruptError(f"{self.path}: not a readable label store ({err})") from err
        except OSError as err:
            raise StoreError(f"{self.path}: cannot {action} the label store ({err})") from err

    @contextlib.contextmanager
    def _write(self) -> Iterator[sqlite3.Connection]:
        with self._errors("write"):
            self._conn.execute("BEGIN IMMEDIATE")
            try:
                yield self._conn
            except BaseException:
                self._conn.execute("ROLLBACK")
                raise
            self._conn.execute("COMMIT")

    def put(
        self,
        drive_hash: str,
        incident_id: str,
        verdict: ReviewVerdict | str,
        *,
        tags: Sequence[str] = (),
        note: str = "",
        reviewer: str = "",
        settings: dict[str, Any] | None = None,
        log_name: str | None = None,
        at_ns: int | None = None,
    ) -> int:
        """Write an incident's label (one transaction); returns its event id.

        Args:
            drive_hash: Content hash of the drive.
            incident_id: The incident's id.
            verdict: A :class:`~workbench.annotations.schema.ReviewVerdict` (or its text).
            tags: Free tags (stored sorted and unique).
            note: Free text.
            reviewer: Who gives the verdict.
            settings: The settings that produced the incident (JSON-ready).
            log_name: The drive's file name, recorded the first time the drive is seen.
            at_ns: When (Unix time [ns]); now when ``None`` (imports keep theirs).

        Raises:
            StoreError: Unknown verdict, a bad tag (:class:`TagError`), or the store cannot
                be written.
        """
        if verdict not in VERDICTS:
            raise StoreError(f"verdict must be one of {', '.join(VERDICTS)}, not {verdict!r}")
        verdict = ReviewVerdict(verdict).value
        tags = check_tags(tags)
        when = time.time_ns() if at_ns is None else at_ns
        row = (
            drive_hash,
            incident_id,
            verdict,
            json_text(tags),
            note,
            reviewer,
            when,
            json_text(settings or {}, sort_keys=True),
        )
        with self._write() as conn:
            cursor = conn.execute(
                "INSERT INTO label_events (drive_hash, incident_id, verdict, tags, note,"
                " reviewer, at_ns, settings) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                row,
            )
            if log_name is not None:
                conn.execute(
                    "INSERT OR IGNORE INTO drives (drive_hash, log_name, first_seen_ns)"
                    " VALUES (?, ?, ?)",
                    (drive_hash, log_name, when),
                )
            return int(cursor.lastrowid or 0)

    def undo(self, event_id: int) -> Label | None:
        """Take back one write; returns the incident's label after it (``None``: unlabelled).

        Raises:
            StoreError: No such write, or the store cannot be written.
        """
        with self._write() as conn:
            key = conn.execute(
                "SELECT drive_hash, incident_id FROM label_events WHERE event_id = ?",
                (event_id,),
            ).fetchone()
            if key is None:
                raise StoreError(f"{self.path}: no label write {event_id} to undo")
            conn.execute("DELETE FROM label_events WHERE event_id = ?", (event_id,))
        return self.label(key[0], key[1])

    def label(self, drive_hash: str, incident_id: str) -> Label | None:
        """The incident's current label, if any."""
        with self._errors("read"):
            row = self._conn.execute(
                _CURRENT + " AND e.drive_hash = ? AND e.incident_id = ?",
                (drive_hash, incident_id),
            ).fetchone()
        return None if row is None else _label(row)

    def labels(self, drive_hash: str) -> dict[str, Label]:
        """Every current label of a drive, by incident id."""
        with self._errors("read"):
            rows = self._conn.execute(
                _CURRENT + " AND e.drive_hash = ? ORDER BY e.incident_id", (drive_hash,)
            ).fetchall()
        return {row[1]: _label(row) for row in rows}

    def log_name(self, drive_hash: str) -> str | None:
        """The file name the drive was first labelled under."""
        with self._errors("read"):
            row = self._conn.execute(
                "SELECT log_name FROM drives WHERE drive_hash = ?", (drive_hash,)
            ).fetchone()
        return None if row is None else str(row[0])

    def close(self) -> None:
        """Close the connection."""
        self._conn.close()

    def __enter__(self) -> Self:
        """Use as a context manager (closes on exit)."""
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        """Close the store."""
        self.close()
