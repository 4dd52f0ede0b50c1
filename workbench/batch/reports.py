"""A batch's drives as the single-drive commands see them: one ``IncidentReport`` each.

The incidents come from ``incidents.parquet`` (not evaluated again); the request from
``batch.json``; the frame times (which OpenLABEL frames and clip windows need) from one pass
of the loader over the drive, without the engines.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import tempfile
from contextlib import ExitStack, closing
from pathlib import Path
from typing import TYPE_CHECKING, Any

from workbench.batch.executors import BatchError
from workbench.batch.queue import incident_of, read_table
from workbench.batch.remote import fetch, is_url
from workbench.incidents import IncidentReport, IncidentRequest, IncidentSettings

if TYPE_CHECKING:
    from collections.abc import Iterator

__all__ = ["batch_request", "drive_reports", "request_record"]

#: ``IncidentRequest`` fields that are paths.
_PATHS = ("log", "map_path", "profile")


def request_record(request: IncidentRequest) -> dict[str, Any]:
    """The request as JSON, for ``batch.json``.

    Paths as text, ``settings`` as its two numbers, ``ego_size`` as its three (``null``
    for the log's), ``options`` as each registered engine's options by field name.
    """
    from workbench.engines.options import options_json  # noqa: PLC0415
    from workbench.engines.registry import engine, names  # noqa: PLC0415

    out: dict[str, Any] = {}
    for f in dataclasses.fields(request):
        value = getattr(request, f.name)
        if f.name in {"settings", "ego_size"}:
            value = None if value is None else dataclasses.asdict(value)
        elif f.name == "options":
            value = {n: options_json(engine(n), request.options_of(n)) for n in names()}
        elif f.name in _PATHS:
            value = None if value is None else str(value)
        elif isinstance(value, tuple):
            value = list(value)
        out[f.name] = value
    return out


def batch_request(results: Path) -> IncidentRequest:
    """The request of the batch in ``results`` (its ``log`` is the results directory).

    Raises:
        BatchError: ``batch.json`` is missing, unreadable or has no request.
    """
    from workbench.driver.run import EgoSize  # noqa: PLC0415
    from workbench.engines.options import options_from  # noqa: PLC0415
    from workbench.engines.registry import engine  # noqa: PLC0415

    path = results / "batch.json"
    try:
        record = json.loads(path.read_text(encoding="utf-8"))["request"]
        values = dict(record)
        for name in _PATHS:
            values[name] = None if values.get(name) is None else Path(values[name])
        values["engines"] = tuple(values["engines"])
        values["settings"] = IncidentSettings(**values["settings"])
        size = values.get("ego_size")
        values["ego_size"] = None if size is None else EgoSize(**size)
        values["options"] = {
            name: options_from(engine(name), section=own, where=f"{path} options.{name}")
            for name, own in values.get("options", {}).items()
        }
        values["log"] = results
        values["url"] = None  # the first drive's, when it was a URL
        return IncidentRequest(**values)
    except (OSError, ValueError, KeyError, TypeError) as err:
        raise BatchError(f"{path}: no readable request ({err})") from err


def _frame_times(request: IncidentRequest) -> tuple[tuple[int, int], ...]:
    from loaders.errors import LoaderError  # noqa: PLC0415

    times: list[tuple[int, int]] = []
    # a truncated log: the frames before the break, as the batch evaluated them
    with closing(request.open_drive()) as drive, contextlib.suppress(LoaderError):
        times.extend((f.index, f.t_ns) for f in drive.frames())
    return tuple(times)


def drive_reports(
    results: Path, *, with_incidents_only: bool = False, copies: ExitStack | None = None
) -> Iterator[IncidentReport]:
    """One report per drive the batch evaluated (not ``failed``), in ``drives.parquet`` order.

    Args:
        results: The results directory.
        with_incidents_only: Skip drives without incidents (no loader pass for them).
        copies: Keeps the local copies of URL drives until it closes (default: each copy
            lives until the next report is asked for).

    A URL drive is fetched again (:func:`workbench.batch.remote.fetch`) into a temporary
    directory (see ``copies``).

    Raises:
        BatchError: The batch's files cannot be read; a URL drive cannot be fetched.
        LoaderError: A drive cannot be opened any more.
    """
    template = batch_request(results)
    settings = json.loads((results / "batch.json").read_text(encoding="utf-8"))["settings"]
    by_drive: dict[str, list[dict[str, Any]]] = {}
    for row in read_table(results, "incidents.parquet"):
        by_drive.setdefault(row["drive_path"], []).append(row)
    drives = read_table(results, "drives.parquet")
    for drive in drives:
        rows = by_drive.get(drive["path"], [])
        if drive["status"] == "failed" or (with_incidents_only and not rows):
            continue
        with ExitStack() as own:
            request = (copies or own).enter_context(_drive_request(template, drive["path"]))
            yield IncidentReport(
                log=request.log,
                drive_hash=drive["content_hash"],
                settings=settings,
                incidents=tuple(incident_of(r) for r in rows),
                frame_times=_frame_times(request),
                start_ns=int(drive["start_ns"] or 0),
                request=request,
            )


@contextlib.contextmanager
def _drive_request(template: IncidentRequest, location: str) -> Iterator[IncidentRequest]:
    """The request of one drive of the batch (a URL drive: its local copy).

    A URL drive is fetched into a temporary directory kept while the caller holds its report.

    Raises:
        FetchError: The URL drive cannot be fetched any more.
    """
    if not is_url(location):
        yield dataclasses.replace(template, log=Path(location))
        return
    with tempfile.TemporaryDirectory(prefix="rss-wb-") as folder:
        fetched = fetch(location, Path(folder))
        yield dataclasses.replace(template, log=fetched.log, url=location)
