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
import math
from typing import TYPE_CHECKING, Any

from workbench.outputs import write_json

if TYPE_CHECKING:
    from pathlib import Path

    from workbench.annotations.store import Label
    from workbench.incidents import Incident, IncidentReport

__all__ = ["export_openlabel", "write_openlabel"]


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
