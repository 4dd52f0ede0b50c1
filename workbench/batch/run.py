"""Run a batch: skip what is fresh, submit the rest one task per log, then assemble.

Each record is kept as it arrives; a lost worker's log is submitted again.
"""

from __future__ import annotations

import dataclasses
import datetime as dt
import glob
from concurrent.futures import FIRST_COMPLETED, Future, wait
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING, Any
from urllib.parse import urlsplit
from urllib.request import url2pathname

from loaders.open import LOG_SUFFIXES, is_rosbag2_dir
from workbench.batch.executors import BatchError
from workbench.batch.remote import expand_url, is_url
from workbench.batch.reports import request_record
from workbench.batch.results import Results
from workbench.batch.task import evaluate_log, failed_record
from workbench.batch.versions import engine_versions, settings_hash
from workbench.outputs import json_text

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from workbench.batch.executors import Pool
    from workbench.incidents import IncidentRequest

__all__ = [
    "MAX_ATTEMPTS",
    "BatchSummary",
    "expand_logs",
    "request_of",
    "requests_for",
    "run_batch",
]

#: Times a log is submitted before a lost worker counts as its failure.
MAX_ATTEMPTS = 3


def _walk(folder: Path) -> list[Path]:
    found: list[Path] = []
    for entry in sorted(folder.iterdir()):
        if is_rosbag2_dir(entry):
            found.append(entry)
        elif entry.is_dir():
            found.extend(_walk(entry))
        elif entry.suffix.lower() in LOG_SUFFIXES and not entry.name.startswith("."):
            found.append(entry)
    return found


def _local(argument: str) -> str | None:
    """The local path a ``file://`` URL on this host names; ``None`` for any other URL.

    Not a URL: the argument as is.

    Raises:
        BatchError: A ``file://`` URL naming another host.
    """
    if not is_url(argument):
        return argument
    parts = urlsplit(argument)
    if parts.scheme != "file":
        return None
    if parts.netloc not in {"", "localhost"}:
        msg = f"{argument}: a file:// URL of another host (give a path the workers share)"
        raise BatchError(msg)
    return url2pathname(parts.path)


def _expand_path(argument: str) -> list[Path]:
    found = sorted(glob.glob(argument))  # noqa: PTH207 - a user's pattern, maybe absolute
    logs: list[Path] = []
    for path in [Path(m).resolve() for m in found] or [Path(argument).resolve()]:
        if path.is_dir() and not is_rosbag2_dir(path):
            logs.extend(_walk(path))
        elif path.exists():
            logs.append(path)
        else:
            raise BatchError(f"{argument}: no such file, directory or match")
    inside_bags = {p for p in logs if p.suffix.lower() == ".db3" and is_rosbag2_dir(p.parent)}
    return [p for p in logs if p not in inside_bags]


def expand_logs(arguments: Sequence[str]) -> list[Path | str]:
    """The logs named by files, directories (searched for logs), globs and URLs.

    A directory contributes every file with a suffix the loaders open
    (:data:`loaders.open.LOG_SUFFIXES`, any case; hidden files skipped), so no log a
    single-drive command reads is left out of a batch of its folder.

    Paths absolute; a ``file://`` URL on this host is the path it names; any other URL
    (fsspec: ``s3://``, ``http://``, ``gcs://``, chains) stays a URL, globbed or searched
    with fsspec where it is a pattern or a directory (:func:`workbench.batch.remote.expand_url`).
    Sorted, unique. A rosbag2 directory (it holds ``metadata.yaml``) is one log; ``.db3``
    files inside it are not listed again.

    Raises:
        BatchError: An argument matches nothing; a URL of an unknown protocol or whose
            file system is not installed.
    """
    out: dict[Path | str, None] = {}
    for given in arguments:
        local = _local(given)
        found = expand_url(given) if local is None else _expand_path(local)
        out.update(dict.fromkeys(found))
    return sorted(out, key=str)


@dataclass(frozen=True, slots=True)
class BatchSummary:
    """What a batch did.

    Attributes:
        drives: Every log's record (no incidents), in table order (by path).
        evaluated: Logs evaluated by this run (the rest were fresh).
        skipped: Logs kept from an earlier run.
        executor: The pool's name.
        versions: This command's engine versions as JSON text (as in ``drives.parquet``).
    """

    drives: list[dict[str, Any]]
    evaluated: int
    skipped: int
    executor: str
    versions: str = ""

    @property
    def failed(self) -> list[dict[str, Any]]:
        """The failed logs' records."""
        return [d for d in self.drives if d["status"] == "failed"]


def run_batch(
    requests: Sequence[IncidentRequest],
    out: Path,
    pool: Pool,
    *,
    on_start: Callable[[int, int], None] | None = None,
    on_done: Callable[[dict[str, Any]], None] | None = None,
    window: int | None = None,
    task: Callable[[IncidentRequest], dict[str, Any]] = evaluate_log,
) -> BatchSummary:
    """Evaluate every request's log on ``pool`` into the results directory ``out``.

    Args:
        requests: One per log, same settings.
        out: The results directory.
        pool: Where the tasks run.
        on_start: Called with ``(logs to evaluate, logs kept)`` before the first submit.
        on_done: Called with each finished log's record.
        window: Tasks in flight at most (default: 4 per worker, at least 8).
        task: The per-log task (tests wrap :func:`evaluate_log`; it must never raise).

    Raises:
        BatchError: The results cannot be written.
    """
    started = dt.datetime.now(dt.UTC)
    results = Results(out)
    versions = engine_versions()
    s_hash = settings_hash(requests[0]) if requests else ""
    todo = [r for r in requests if not results.is_fresh(r, versions, s_hash)]
    if on_start is not None:
        on_start(len(todo), len(requests) - len(todo))
    attempts: dict[str, int] = {}
    queue = list(reversed(todo))
    flying: dict[Future[Any], IncidentRequest] = {}
    limit = window or max(8, 4 * pool.workers)
    while queue or flying:
        while queue and len(flying) < limit:
            request = queue.pop()
            attempts[request.location] = attempts.get(request.location, 0) + 1
            flying[pool.submit(task, request)] = request
        done, _ = wait(flying, return_when=FIRST_COMPLETED)
        for future in done:
            request = flying.pop(future)
            try:
                record = future.result()
            except Exception as err:  # noqa: BLE001 - the task never raises: a lost worker
                pool.recover()
                if attempts[request.location] < MAX_ATTEMPTS:
                    queue.append(request)
                    continue
                detail = f"worker lost {MAX_ATTEMPTS} times ({type(err).__name__}: {err})"
                record = failed_record(request, "WorkerLost", detail, worker="")
            results.put(record)
            if on_done is not None:
                on_done(record)
    logs = sorted(r.location for r in requests)
    batch = {
        "settings": requests[0].record() if requests else {},
        "request": request_record(requests[0]) if requests else None,
        "settings_hash": s_hash,
        "engine_versions": versions,
        "executor": pool.name,
        "started": started.isoformat(),
        "ended": dt.datetime.now(dt.UTC).isoformat(),
        "evaluated": len(todo),
    }
    drives = results.assemble(logs, batch)
    text = json_text(versions, sort_keys=True)
    return BatchSummary(drives, len(todo), len(requests) - len(todo), pool.name, text)


def request_of(log: Path | str, make: Callable[[Path], IncidentRequest]) -> IncidentRequest:
    """The request of one log of :func:`expand_logs` (a URL: ``url`` set, ``log`` its name)."""
    if isinstance(log, Path):
        return make(log)
    name = PurePosixPath(urlsplit(log.split("::")[-1]).path.rstrip("/")).name
    return dataclasses.replace(make(Path(name)), url=log)


def requests_for(logs: Sequence[Path | str], template: IncidentRequest) -> list[IncidentRequest]:
    """One request per log (path or URL) with the template's settings."""

    def make(path: Path) -> IncidentRequest:
        return dataclasses.replace(template, log=path, url=None)

    return [request_of(log, make) for log in logs]
