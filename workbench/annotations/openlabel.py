"""A drive's incidents and their labels as ASAM OpenLABEL 1.0 JSON, and back into the store.

::

    openlabel
      metadata      schema_version 1.0.0, tagged_file (the log's name), drive_sha256, settings
      actions       one per incident, worst first: name = incident id, type = incident/<engine>,
                    frame_intervals = its frames, action_data = engine, cause, objects,
                    severity facts, and once reviewed verdict, tags, note, reviewer, labelled_ns
      tags          one per review tag used on the drive, naming its incidents
      frames        every frame an incident covers: frame_properties.timestamp (UTC ISO 8601,
                    ns) and t_ns, and the actions present
      frame_intervals  the frames covered

Nothing in the export depends on when it was written, so export -> import -> export gives
the same file. The official JSON schema validates the output in the tests.
"""

from __future__ import annotations

import datetime as dt
import json
import math
from typing import TYPE_CHECKING, Any

from workbench.errors import WorkbenchError
from workbench.outputs import write_json

if TYPE_CHECKING:
    from pathlib import Path

    from workbench.annotations.store import Label, LabelStore
    from workbench.incidents import Incident, IncidentReport

__all__ = ["OpenLabelError", "export_openlabel", "import_openlabel", "write_openlabel"]

_TEXT_FIELDS = ("engine", "cause", "verdict", "note", "reviewer", "labelled_ns")


class OpenLabelError(WorkbenchError):
    """An OpenLABEL file this workbench cannot import (names the file and the element)."""


def _timestamp(t_ns: int) -> str:
    seconds, frac = divmod(t_ns, 1_000_000_000)
    stamp = dt.datetime.fromtimestamp(seconds, dt.UTC).strftime("%Y-%m-%dT%H:%M:%S")
    return f"{stamp}.{frac:09d}Z"


def _action_data(incident: Incident, label: Label | None) -> dict[str, Any]:
    text = {"engine": incident.engine, "cause": incident.cause}
    vec: list[dict[str, Any]] = [{"name": "objects", "val": list(incident.objects)}]
    if label is not None:
        text.update(
            verdict=label.verdict,
            note=label.note,
            reviewer=label.reviewer,
            labelled_ns=str(label.labelled_ns),
        )
        vec.append({"name": "tags", "val": list(label.tags)})
    num: list[dict[str, Any]] = []
    boolean: list[dict[str, Any]] = []
    for name, value in incident.severity.record().items():
        if isinstance(value, bool):
            boolean.append({"name": name, "val": value})
        elif isinstance(value, int | float) and math.isfinite(value):
            num.append({"name": name, "val": value})
        elif isinstance(value, str):
            text[f"severity.{name}"] = value
    data: dict[str, Any] = {"text": [{"name": k, "val": v} for k, v in text.items()]}
    data["num"] = num
    if boolean:
        data["boolean"] = boolean
    data["vec"] = vec
    return data


def _intervals(spans: list[tuple[int, int]]) -> list[dict[str, int]]:
    merged: list[list[int]] = []
    for start, end in sorted(spans):
        if merged and start <= merged[-1][1] + 1:
            merged[-1][1] = max(merged[-1][1], end)
        else:
            merged.append([start, end])
    return [{"frame_start": a, "frame_end": b} for a, b in merged]


def export_openlabel(report: IncidentReport, labels: dict[str, Label]) -> dict[str, Any]:
    """The OpenLABEL document of a drive's incidents (worst first) and their labels."""
    times = dict(report.frame_times)
    actions: dict[str, Any] = {}
    frames: dict[str, Any] = {}
    tagged: dict[str, list[str]] = {}
    for uid, incident in enumerate(report.incidents):
        label = labels.get(incident.id)
        actions[str(uid)] = {
            "name": incident.id,
            "type": f"incident/{incident.engine}",
            "frame_intervals": [
                {"frame_start": incident.start_frame, "frame_end": incident.end_frame}
            ],
            "action_data": _action_data(incident, label),
        }
        for tag in label.tags if label else ():
            tagged.setdefault(tag, []).append(incident.id)
        for frame in range(incident.start_frame, incident.end_frame + 1):
            entry = frames.setdefault(
                str(frame),
                {
                    "frame_properties": {
                        "timestamp": _timestamp(times[frame]),
                        "t_ns": times[frame],
                    },
                    "actions": {},
                },
            )
            entry["actions"][str(uid)] = {}
    doc: dict[str, Any] = {
        "metadata": {
            "schema_version": "1.0.0",
            "name": f"{report.log.name} incidents",
            "annotator": "rss-workbench",
            "tagged_file": report.log.name,
            "drive_sha256": report.drive_hash,
            "settings": report.settings,
        },
        "actions": actions,
        "tags": {
            str(k): {"type": tag, "tag_data": {"vec": [{"name": "incidents", "val": ids}]}}
            for k, (tag, ids) in enumerate(sorted(tagged.items()))
        },
        "frames": dict(sorted(frames.items(), key=lambda kv: int(kv[0]))),
        "frame_intervals": _intervals([(i.start_frame, i.end_frame) for i in report.incidents]),
    }
    return {"openlabel": doc}


def write_openlabel(doc: dict[str, Any], path: Path) -> None:
    """Write the document as indented JSON, atomically.

    Raises:
        WorkbenchError: The file cannot be written.
    """
    write_json(path, doc, "OpenLABEL")


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


def import_openlabel(path: Path, store: LabelStore) -> tuple[int, int]:
    """Write the reviewed incidents of an OpenLABEL file into the store.

    Actions with a ``verdict`` become labels (keeping their reviewer and ``labelled_ns``);
    a label already in the store as given is left alone, so importing twice changes nothing.

    Returns:
        ``(labels written, labels already present)``.

    Raises:
        OpenLabelError: Not an OpenLABEL 1.0 file written by ``labels export``.
        StoreError: The store cannot be written.
    """
    root = _read(path)
    meta = root["metadata"]
    drive_hash = meta.get("drive_sha256")
    if not isinstance(drive_hash, str) or not drive_hash:
        raise OpenLabelError(f"{path}: metadata.drive_sha256 missing (not a workbench export)")
    written = kept = 0
    actions = root.get("actions", {})
    for uid, action in sorted(actions.items(), key=lambda kv: int(kv[0])):
        where = f"{path}: actions.{uid}.action_data"
        data = action.get("action_data", {}) if isinstance(action, dict) else {}
        texts = data.get("text", [])
        if not any(isinstance(t, dict) and t.get("name") == "verdict" for t in texts):
            continue
        text = {name: str(_field(texts, name, where)) for name in _TEXT_FIELDS}
        try:
            at_ns = int(text["labelled_ns"])
        except ValueError as err:
            raise OpenLabelError(f"{where}: labelled_ns {text['labelled_ns']!r}") from err
        tags = tuple(str(t) for t in _field(data.get("vec", []), "tags", where))
        incident_id = str(action.get("name", ""))
        before = store.label(drive_hash, incident_id)
        given = (text["verdict"], tuple(sorted(set(tags))), text["note"], text["reviewer"], at_ns)
        if before is not None and given == (
            before.verdict,
            before.tags,
            before.note,
            before.reviewer,
            before.labelled_ns,
        ):
            kept += 1
            continue
        store.put(
            drive_hash,
            incident_id,
            text["verdict"],
            tags=tags,
            note=text["note"],
            reviewer=text["reviewer"],
            settings=meta.get("settings") or {},
            log_name=meta.get("tagged_file"),
            at_ns=at_ns,
        )
        written += 1
    return written, kept
