"""The per-log task of a batch: evaluate one drive where the task runs, return a plain record.

The task never raises across the wire: every error, typed or not, becomes the record's
``status = "failed"`` with the error's type and one-line message. Only the record travels
back (the drive's metadata and its incidents as flat rows); the log is read by the worker.

Statuses:

| status | meaning |
|---|---|
| ``ok`` | every ego message became a frame and the log was read to its end |
| ``partial`` | frames were evaluated, but the log ended early (truncated, corrupt) or |
|             | ego messages were lost |
| ``empty`` | the log was read, but yielded no frame |
| ``failed`` | the log could not be opened or evaluated (``error_type``, ``error``) |
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import socket
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from workbench.batch.remote import fetch, one_line
from workbench.batch.versions import engine_versions, settings_hash

if TYPE_CHECKING:
    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["EGO_LOSS_NOTES", "STATUSES", "evaluate_log", "failed_record", "incident_rows"]

#: Record statuses, best first.
STATUSES = ("ok", "partial", "empty", "failed")

#: Loss notes (:data:`loaders.losses.LOSS_NOTES`) that count ego messages not made frames.
EGO_LOSS_NOTES = ("skipped_out_of_order_ego", "skipped_invalid_ego", "ego_messages_without_pose")


def _count(value: str) -> int:
    return int(value) if value.isdigit() else 0


def incident_rows(report: IncidentReport) -> list[dict[str, Any]]:
    """The report's incidents as rows of ``incidents.parquet``.

    Drive path (its URL for a URL drive) and hash first, then the row of ``workbench
    incidents --out FILE.parquet``, then ``severity_names``: the severity facts' names in
    their order.
    """
    from workbench.incidents.table import flat_rows  # noqa: PLC0415 - worker-side import

    return [
        {
            "drive_path": str(report.log) if report.request is None else report.request.location,
            "drive_hash": report.drive_hash,
            **row,
            "severity_names": list(incident.severity.record()),
        }
        for incident, row in zip(report.incidents, flat_rows(report.incidents), strict=True)
    ]


def _worker() -> str:
    return f"{socket.gethostname()}:{os.getpid()}"


def failed_record(
    request: IncidentRequest, error_type: str, error: str, *, worker: str | None = None
) -> dict[str, Any]:
    """A ``failed`` record of the request's log (the base every record starts from).

    Args:
        request: The log and its settings.
        error_type: The error's type name (``WorkerLost`` when no worker finished it).
        error: One-line message.
        worker: Who tried (default: this process).
    """
    return {
        "path": request.location,
        "content_hash": "",
        "format": "",
        "frames": 0,
        "start_ns": 0,
        "duration_s": 0.0,
        "frames_lost": 0,
        "stopped_by": None,
        "wall_s": 0.0,
        "worker": _worker() if worker is None else worker,
        "engine_versions": engine_versions(),
        "settings_hash": settings_hash(request),
        "status": "failed",
        "error_type": error_type,
        "error": error,
        "incidents": [],
    }


def _from_report(record: dict[str, Any], report: IncidentReport) -> None:
    frames = len(report.frame_times)
    notes = report.info.notes if report.info is not None else {}
    lost = sum(_count(notes.get(key, "0")) for key in EGO_LOSS_NOTES)
    if frames == 0:
        status = "empty"
    elif report.stopped_by is not None or lost:
        status = "partial"
    else:
        status = "ok"
    stopped = report.stopped_by
    record.update(
        content_hash=report.drive_hash,
        format=report.info.source_format if report.info is not None else "",
        frames=frames,
        start_ns=report.start_ns,
        duration_s=report.info.duration_s if report.info is not None else 0.0,
        frames_lost=lost,
        stopped_by=None if stopped is None else str(stopped),
        status=status,
        error_type=None if stopped is None else type(stopped).__name__,
        error=None if stopped is None else str(stopped),
        incidents=incident_rows(report),
    )


def evaluate_log(request: IncidentRequest) -> dict[str, Any]:
    """Evaluate one drive; never raises (a failure is the record's ``status``).

    A URL drive (``request.url``) is fetched into a temporary directory of this worker
    first (:func:`workbench.batch.remote.fetch`); its record keeps the URL as ``path`` and
    the object's ``source_stamp``.

    Args:
        request: The drive and every setting that decides its incidents.

    Returns:
        The drive's record: path, content hash, format, frames, duration [s], frames lost,
        wall time [s], worker, engine versions, settings hash, status, error, incidents
        (flat rows, see :func:`incident_rows`).
    """
    started = time.perf_counter()
    record = failed_record(request, "", "")
    folder = ""
    try:
        from workbench.incidents import (  # noqa: PLC0415 - worker-side import
            drive_content_hash,
            find_incidents,
        )

        with contextlib.ExitStack() as stack:
            if request.url is not None:
                folder = stack.enter_context(tempfile.TemporaryDirectory(prefix="rss-wb-"))
                fetched = fetch(request.url, Path(folder))
                record["source_stamp"] = fetched.stamp
                request = dataclasses.replace(request, log=fetched.log)
            if request.log.exists():
                record["content_hash"] = drive_content_hash(request.log)
            _from_report(record, find_incidents(request))
    except Exception as err:  # noqa: BLE001 - the task reports every failure as a record
        record.update(status="failed", error_type=type(err).__name__, error=one_line(err))
    if folder and request.url is not None:  # messages name the URL, not the local copy
        parent = request.url.rpartition("/")[0]
        for key in ("error", "stopped_by"):
            if record[key]:
                record[key] = record[key].replace(folder, parent)
    record["wall_s"] = time.perf_counter() - started
    return record
