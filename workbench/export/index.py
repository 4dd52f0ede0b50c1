"""The export's index (``clips.json``, ``clips.csv``) and the directory it describes.

A directory holds one export: a new export into a directory that holds one (an index, clip
files or unfinished ``.part`` files) is refused unless asked to replace it, and replacing it
removes the earlier export's files first, so no clip is left that the index does not name.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import re
from typing import TYPE_CHECKING, Any

from workbench.errors import WorkbenchError
from workbench.outputs import PART_SUFFIX, finite, json_text, write_json, write_text

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

__all__ = ["INDEX_CSV", "INDEX_JSON", "clear_directory", "write_index"]

INDEX_JSON = "clips.json"
INDEX_CSV = "clips.csv"
#: Files an export writes besides the index: ``NNN_<id>.<kind>``, ``window_<frames>.<kind>``.
_CLIP_FILE = re.compile(
    r"^(\d{3}|window)_[A-Za-z0-9._-]+\.(mcap|bag|rrd|png|osm|xodr|openlabel\.json)$"
)
_CSV_FIELDS = (
    "stem",
    "id",
    "engine",
    "objects",
    "cause",
    "verdict",
    "tags",
    "note",
    "reviewer",
    "start_frame",
    "end_frame",
    "start_ns",
    "end_ns",
    "clip_start_ns",
    "clip_end_ns",
    "messages",
    "source",
    "drive_sha256",
    "mcap",
    "bag",
    "map",
    "openlabel",
    "rrd",
    "png",
    "problem",
)


def _earlier_export(out_dir: Path) -> list[Path]:
    """The files of an earlier export in ``out_dir`` (named by its index or by their form)."""
    found = {p for p in out_dir.iterdir() if p.is_file() and _CLIP_FILE.match(p.name)}
    found |= {p for p in out_dir.iterdir() if p.name.endswith(PART_SUFFIX)}
    index = out_dir / INDEX_JSON
    if index.is_file():
        found |= {index, out_dir / INDEX_CSV}
        with contextlib.suppress(OSError, ValueError, TypeError, AttributeError):
            for record in json.loads(index.read_text()):
                found |= {out_dir / name for name in record["files"].values() if name}
    return sorted(p for p in found if p.is_file() or p.name.endswith(PART_SUFFIX))


def clear_directory(out_dir: Path, *, force: bool) -> int:
    """Make ``out_dir`` ready for an export: created, and without an earlier export.

    Args:
        out_dir: The export directory.
        force: Remove an earlier export's files (else refuse).

    Returns:
        How many files of an earlier export were removed.

    Raises:
        WorkbenchError: The directory cannot be created or cleared, or holds an export and
            ``force`` is not set.
    """
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        earlier = _earlier_export(out_dir)
        if earlier and not force:
            msg = (
                f"{out_dir}: holds an earlier export ({len(earlier)} file(s), e.g. "
                f"{earlier[0].name}); --force replaces it"
            )
            raise WorkbenchError(msg)
        for path in earlier:
            path.unlink(missing_ok=True)
    except OSError as err:
        msg = f"{out_dir}: cannot prepare the export directory ({err.strerror})"
        raise WorkbenchError(msg) from err
    return len(earlier)


def _csv_row(record: dict[str, Any]) -> dict[str, Any]:
    severity = {f"severity.{k}": v for k, v in finite(record["severity"]).items()}
    return {
        **record,
        **{k: v or "" for k, v in record["files"].items()},
        **{k: "" if v is None else v for k, v in severity.items()},
        "objects": " ".join(record["objects"]),
        "tags": json_text(record["tags"]),  # a tag may hold blanks and commas: a JSON array
        "verdict": record["verdict"] or "",
        "problem": record["problem"] or "",
    }


def write_index(out_dir: Path, records: Sequence[dict[str, Any]]) -> tuple[Path, Path]:
    """Write ``clips.json`` and ``clips.csv`` (one row per clip; severity facts as columns).

    Returns:
        The two files.

    Raises:
        WorkbenchError: They cannot be written.
    """
    facts = sorted({f"severity.{k}" for r in records for k in r["severity"]})
    rows = io.StringIO()
    writer = csv.DictWriter(rows, fieldnames=[*_CSV_FIELDS, *facts], extrasaction="ignore")
    writer.writeheader()
    for record in records:
        writer.writerow(_csv_row(record))
    write_json(out_dir / INDEX_JSON, list(records), "the clip index")
    write_text(out_dir / INDEX_CSV, rows.getvalue(), "the clip index")
    return out_dir / INDEX_JSON, out_dir / INDEX_CSV
