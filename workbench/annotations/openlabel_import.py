"""OpenLABEL files back into the label store, never losing a label without a word.

Each reviewed action of the file (one with a ``verdict``) meets the store's label of the
same drive and incident:

============  ==========================================================================
added         the store had none: the file's is written
unchanged     the same verdict, tags, note and reviewer: nothing is written
replaced      they differ and the file's wins (``--prefer newer``: the file's is newer;
              ``--prefer import``)
kept          they differ and the store's wins (``--prefer newer``: the store's is newer;
              ``--prefer store``)
conflicting   they differ and were written at the same time (``--prefer newer``): the
              store's stays, the conflict is reported
============  ==========================================================================

A clip's OpenLABEL (``workbench export``) names its source drive's content hash, so its
labels attach to the source drive, not to the clip.
"""

from __future__ import annotations

import enum
import json
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from workbench.annotations.errors import OpenLabelError, TagError
from workbench.annotations.schema import ReviewVerdict, check_tags
from workbench.annotations.store import Label

if TYPE_CHECKING:
    from pathlib import Path

    from workbench.annotations.store import LabelStore

__all__ = ["ImportOutcome", "ImportReport", "Prefer", "import_openlabel"]

#: One past the largest time an SQLite INTEGER holds, in ns.
_MAX_NS = 2**63
_TEXT_FIELDS = ("engine", "cause", "verdict", "note", "reviewer", "labelled_ns")


class Prefer(enum.StrEnum):
    """Which label wins when the file and the store differ."""

    newer = "newer"
    import_ = "import"
    store = "store"


@dataclass(frozen=True, slots=True)
class ImportOutcome:
    """What became of one reviewed incident of the file.

    Attributes:
        incident_id: The incident.
        status: ``added``, ``unchanged``, ``replaced``, ``kept`` or ``conflicting``.
        given: The file's label.
        stored: The store's label before the import (``None``: none).
    """

    incident_id: str
    status: str
    given: Label
    stored: Label | None

    def line(self) -> str:
        """One line for the terminal: both labels when they differ."""
        if self.stored is None or self.status == "unchanged":
            return f"{self.incident_id}: {self.status} ({_brief(self.given)})"
        return (
            f"{self.incident_id}: {self.status}: store {_brief(self.stored)}, "
            f"file {_brief(self.given)}"
        )


@dataclass(frozen=True, slots=True)
class ImportReport:
    """Everything one import did.

    Attributes:
        drive_hash: The drive the labels belong to (the file's ``drive_sha256``).
        log_name: The drive's log name in the file (``tagged_file``).
        outcomes: Per reviewed incident of the file, in the file's order.
    """

    drive_hash: str
    log_name: str
    outcomes: tuple[ImportOutcome, ...]

    def count(self, status: str) -> int:
        """How many incidents had this status."""
        return sum(o.status == status for o in self.outcomes)

    @property
    def written(self) -> int:
        """Labels written into the store (added or replaced)."""
        return self.count("added") + self.count("replaced")


def _brief(label: Label) -> str:
    tags = f" [{', '.join(label.tags)}]" if label.tags else ""
    by = f" by {label.reviewer}" if label.reviewer else ""
    return f"{label.verdict}{tags}{by} at {label.labelled_ns} ns"


def _content(label: Label) -> tuple[str, tuple[str, ...], str, str]:
    return (label.verdict, tuple(sorted(set(label.tags))), label.note, label.reviewer)


def decide(stored: Label | None, given: Label, prefer: Prefer) -> str:
    """The status of ``given`` against the store's label (see the module docstring)."""
    if stored is None:
        return "added"
    if _content(stored) == _content(given):
        return "unchanged"
    if prefer is Prefer.import_:
        return "replaced"
    if prefer is Prefer.store:
        return "kept"
    if given.labelled_ns == stored.labelled_ns:
        return "conflicting"
    return "replaced" if given.labelled_ns > stored.labelled_ns else "kept"


def _field(items: Any, name: str, where: str) -> Any:
    for item in items if isinstance(items, list) else ():
        if isinstance(item, dict) and item.get("name") == name:
            return item.get("val")
    raise OpenLabelError(f"{where}: no {name!r}")


def _read(path: Path) -> dict[str, Any]:
    try:
        doc = json.loads(path.read_text())
    except OSError as err:
        raise OpenLabelError(f"{path}: cannot read ({err.strerror})") from err
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        raise OpenLabelError(f"{path}: not JSON ({err})") from err
    root = doc.get("openlabel") if isinstance(doc, dict) else None
    if not isinstance(root, dict) or not isinstance(root.get("metadata"), dict):
        raise OpenLabelError(f"{path}: no openlabel.metadata object")
    if root["metadata"].get("schema_version") != "1.0.0":
        version = root["metadata"].get("schema_version")
        raise OpenLabelError(f"{path}: OpenLABEL schema_version {version!r}, expected '1.0.0'")
    return root


def _labels(path: Path, root: dict[str, Any], drive_hash: str) -> list[Label]:
    """The file's reviewed actions as labels, in the file's order."""
    labels = []
    actions = root.get("actions", {})
    if not isinstance(actions, dict):
        raise OpenLabelError(f"{path}: actions is not an object")
    for uid, action in sorted(actions.items(), key=lambda kv: (len(kv[0]), kv[0])):
        where = f"{path}: actions.{uid}.action_data"
        data = action.get("action_data", {}) if isinstance(action, dict) else {}
        texts = data.get("text", []) if isinstance(data, dict) else []
        if not isinstance(texts, list) or not any(
            isinstance(t, dict) and t.get("name") == "verdict" for t in texts
        ):
            continue
        text = {name: str(_field(texts, name, where)) for name in _TEXT_FIELDS}
        labels.append(_label(where, drive_hash, str(action.get("name", "")), text, data))
    return labels


def _label(where: str, drive_hash: str, incident_id: str, text: dict[str, str], data: Any) -> Label:
    """One reviewed action as a label; what the store would refuse is an error naming it."""
    try:
        verdict = ReviewVerdict(text["verdict"])
    except ValueError as err:
        known = ", ".join(v.value for v in ReviewVerdict)
        raise OpenLabelError(
            f"{where}: verdict {text['verdict']!r}, expected one of {known}"
        ) from err
    try:
        at_ns = int(text["labelled_ns"])
    except ValueError as err:
        raise OpenLabelError(f"{where}: labelled_ns {text['labelled_ns']!r}") from err
    if not 0 <= at_ns < _MAX_NS:  # the store keeps it as an SQLite INTEGER (64 bits, signed)
        raise OpenLabelError(
            f"{where}: labelled_ns {text['labelled_ns']!r} is not within 0 .. 2^63-1 ns"
        )
    tags = _field(data.get("vec", []), "tags", where)
    if not isinstance(tags, list):
        raise OpenLabelError(f"{where}: tags {tags!r} is not a list")
    try:
        checked = check_tags(sorted({str(t) for t in tags}))
    except TagError as err:
        raise OpenLabelError(f"{where}: {err}") from err
    return Label(drive_hash, incident_id, verdict, checked, text["note"], text["reviewer"], at_ns)


def import_openlabel(path: Path, store: LabelStore, prefer: Prefer = Prefer.newer) -> ImportReport:
    """Write the reviewed incidents of an OpenLABEL file into the store.

    Labels keep their reviewer and ``labelled_ns``; importing twice changes nothing.

    Args:
        path: A file of ``workbench labels export`` or of a clip (``workbench export``).
        store: The label store.
        prefer: Which label wins where the file and the store differ.

    Returns:
        Per reviewed incident, what became of it.

    Raises:
        OpenLabelError: Not an OpenLABEL 1.0 file written by the workbench.
        StoreError: The store cannot be written, or a verdict or tag it refuses.
    """
    root = _read(path)
    meta = root["metadata"]
    drive_hash = meta.get("drive_sha256")
    if not isinstance(drive_hash, str) or not drive_hash:
        raise OpenLabelError(f"{path}: metadata.drive_sha256 missing (not a workbench export)")
    log_name = str(meta.get("tagged_file") or "")
    outcomes = []
    for given in _labels(path, root, drive_hash):
        stored = store.label(drive_hash, given.incident_id)
        status = decide(stored, given, prefer)
        if status in {"added", "replaced"}:
            store.put(
                drive_hash,
                given.incident_id,
                given.verdict,
                tags=given.tags,
                note=given.note,
                reviewer=given.reviewer,
                settings=meta.get("settings") or {},
                log_name=log_name or None,
                at_ns=given.labelled_ns,
            )
        outcomes.append(ImportOutcome(given.incident_id, status, given, stored))
    return ImportReport(drive_hash, log_name, tuple(outcomes))
