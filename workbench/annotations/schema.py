"""The label store's schema, versioned: each migration is applied once, in order, atomically.

Version 1 keeps every label write as an event (the current label of an incident is its latest
event; undo deletes an event); version 2 adds the drives table naming each content hash's
log file. A store written by a newer version is refused.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from workbench.annotations.errors import TagError

if TYPE_CHECKING:
    import sqlite3
    from collections.abc import Sequence

__all__ = [
    "MAX_TAG_CHARS",
    "MIGRATIONS",
    "SCHEMA_VERSION",
    "VERDICTS",
    "ReviewVerdict",
    "check_tags",
    "migrate",
    "schema_version",
]


class ReviewVerdict(enum.StrEnum):
    """A reviewer's verdict on an incident: the one spelling of the store, CLI and viewer."""

    CONFIRMED = "confirmed"
    FALSE_POSITIVE = "false_positive"
    FOLLOW_UP = "follow_up"


#: The review verdicts the store accepts, as text (its schema's CHECK constraint).
VERDICTS = tuple(v.value for v in ReviewVerdict)

#: Longest review tag (characters).
MAX_TAG_CHARS = 64

#: ``MIGRATIONS[k]`` takes a store from version ``k`` to ``k + 1``.
MIGRATIONS: tuple[str, ...] = (
    f"""
    CREATE TABLE label_events (
        event_id INTEGER PRIMARY KEY AUTOINCREMENT,
        drive_hash TEXT NOT NULL,
        incident_id TEXT NOT NULL,
        verdict TEXT NOT NULL CHECK (verdict IN {VERDICTS!r}),
        tags TEXT NOT NULL,
        note TEXT NOT NULL,
        reviewer TEXT NOT NULL,
        at_ns INTEGER NOT NULL,
        settings TEXT NOT NULL
    );
    CREATE INDEX label_events_by_key ON label_events (drive_hash, incident_id, event_id);
    """,
    """
    CREATE TABLE drives (
        drive_hash TEXT PRIMARY KEY,
        log_name TEXT NOT NULL,
        first_seen_ns INTEGER NOT NULL
    );
    """,
)
#: The version this code writes.
SCHEMA_VERSION = len(MIGRATIONS)


def schema_version(conn: sqlite3.Connection) -> int:
    """The store's version (0: empty file)."""
    has_table = conn.execute(
        "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'schema_version'"
    ).fetchone()
    if has_table is None:
        return 0
    row = conn.execute("SELECT version FROM schema_version").fetchone()
    return 0 if row is None else int(row[0])


def migrate(conn: sqlite3.Connection, target: int = SCHEMA_VERSION) -> int:
    """Bring the store to ``target`` in one transaction; returns the version found before.

    The connection must be in autocommit mode (``isolation_level=None``); the write lock is
    taken first, so two processes opening a new store at once migrate it once.
    """
    conn.execute("BEGIN IMMEDIATE")
    try:
        found = schema_version(conn)
        if found == 0:
            conn.execute("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)")
        for step in MIGRATIONS[found:target]:
            for statement in step.split(";"):
                if statement.strip():
                    conn.execute(statement)
        if found < target:
            conn.execute("DELETE FROM schema_version")
            conn.execute("INSERT INTO schema_version (version) VALUES (?)", (target,))
        conn.execute("COMMIT")
    except BaseException:
        conn.execute("ROLLBACK")
        raise
    return found


def check_tags(tags: Sequence[str]) -> tuple[str, ...]:
    """The tags sorted and unique, each checked: not blank, one line, at most 64 characters.

    Raises:
        TagError: A tag that is blank, holds a line break or a control character, or is
            longer than :data:`MAX_TAG_CHARS`.
    """
    for tag in tags:
        if not tag.strip():
            raise TagError(f"tag {tag!r}: empty")
        if any(not c.isprintable() for c in tag):
            raise TagError(f"tag {tag!r}: one line of printable characters expected")
        if len(tag) > MAX_TAG_CHARS:
            raise TagError(f"tag {tag[:20]!r}...: {len(tag)} characters, at most {MAX_TAG_CHARS}")
    return tuple(sorted(set(tags)))
