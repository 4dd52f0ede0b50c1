"""Drives named by fsspec URLs: listed where the batch starts, fetched where its task runs.

A URL drive (``s3://bucket/drives/a.mcap``, ``http://host/a.bag``, ``gcs://...``, a chained
``simplecache::s3://...``) is read by the task, on its worker, into a local copy in the
worker's temporary directory, which the loaders then open like any file; the copy is removed
when the task ends. Why a copy and not a file object: the loaders read paths (rosbags and
SQLite for ``.db3`` need a real file, the MCAP reader seeks its summary and chunk indexes,
the sidecar map ``LOG.osm`` and the rosbag2 directory are files beside or inside the log),
and a seek over object storage is a request; one sequential download is the cheap read.

The copy keeps the log's name (its suffix decides the loader), the sidecar map beside it is
fetched too (the same candidates :func:`loaders.message_logs.mapsource.sidecar_candidates`
tries), and a rosbag2 directory is fetched whole. The content hash is the copy's
(:func:`workbench.incidents.drive_content_hash`): the bytes the loader read. A fetch larger
than :data:`MAX_FETCH_BYTES` or than the free space of the temporary directory fails the
task with a one-line :class:`FetchError`.
"""

from __future__ import annotations

import hashlib
import re
import shutil
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Any

from loaders.message_logs.mapsource import sidecar_candidates
from loaders.open import LOG_SUFFIXES, SCENARIO_SUFFIXES
from workbench.batch.executors import BatchError
from workbench.incidents.content import CHUNK_BYTES

__all__ = [
    "MAX_FETCH_BYTES",
    "FetchError",
    "Fetched",
    "expand_url",
    "fetch",
    "is_url",
    "one_line",
    "stamp",
]

#: ``scheme://`` or a chain ``outer::inner://``: a URL, not a path.
_URL = re.compile(r"^(?:[A-Za-z][A-Za-z0-9+.-]*::)*[A-Za-z][A-Za-z0-9+.-]*://")
#: Glob characters of a URL pattern (a ``?`` of an http(s) URL is its query).
_MAGIC = re.compile(r"[*?\[]")
_HTTP_MAGIC = re.compile(r"[*\[]")
#: Bytes one task fetches at most (besides the free space of its temporary directory).
MAX_FETCH_BYTES = 64 << 30
#: Free bytes a fetch leaves in the temporary directory.
RESERVE_BYTES = 1 << 30


class FetchError(BatchError):
    """A URL drive cannot be listed or fetched (unknown protocol, missing backend, too big)."""


@dataclass(frozen=True, slots=True)
class Fetched:
    """A URL drive's local copy.

    Attributes:
        log: The copy (file or rosbag2 directory), named as at the URL.
        stamp: The object's :func:`stamp` before the fetch.
        size_bytes: Bytes fetched, the sidecar map included.
    """

    log: Path
    stamp: str
    size_bytes: int


def is_url(text: str) -> bool:
    """Whether ``text`` is a URL (``scheme://...`` or an fsspec chain ``a::b://...``)."""
    return bool(_URL.match(text))


def one_line(err: BaseException) -> str:
    """The error's message on one line (its type's name when it has none)."""
    return " ".join(str(err).split()) or type(err).__name__


def _backend_hint(protocol: str) -> str:
    from importlib.metadata import PackageNotFoundError, metadata  # noqa: PLC0415

    try:
        extras = metadata("fsspec").get_all("Provides-Extra") or []
    except PackageNotFoundError:
        extras = []
    return f"pip install 'fsspec[{protocol}]'" if protocol in extras else "see fsspec's docs"


def _check_protocols(url: str) -> None:
    import fsspec  # noqa: PLC0415 - only for URL drives

    for part in url.split("::"):
        protocol = part.split("://", 1)[0]
        try:
            fsspec.get_filesystem_class(protocol)
        except ValueError as err:
            msg = f"{url}: unknown URL protocol {protocol}:// (fsspec has no such file system)"
            raise FetchError(msg) from err
        except ImportError as err:
            msg = (
                f"{url}: the {protocol}:// file system is not installed"
                f" ({one_line(err)}; {_backend_hint(protocol)})"
            )
            raise FetchError(msg) from err


def _filesystem(url: str) -> tuple[Any, str]:
    """``(file system, path in it)`` of ``url``.

    Raises:
        FetchError: Unknown protocol, missing backend, or the URL's options are refused.
    """
    _check_protocols(url)
    from fsspec.core import url_to_fs  # noqa: PLC0415

    try:
        return url_to_fs(url)  # type: ignore[no-any-return]
    except (ValueError, TypeError, OSError) as err:
        raise FetchError(f"{url}: {one_line(err)}") from err


def _suffix(path: str) -> str:
    return PurePosixPath(path.rstrip("/")).suffix.lower()


def _logs_under(fs: Any, folder: str) -> list[str]:
    """Logs in ``folder`` and below: rosbag2 directories whole, files by suffix."""
    files = sorted(fs.find(folder))
    bags = sorted({f.rsplit("/", 1)[0] for f in files if f.endswith("/metadata.yaml")})
    in_bag = [f for f in files if any(f.startswith(b + "/") for b in bags)]
    names = [
        f
        for f in files
        if f not in in_bag
        and _suffix(f) in LOG_SUFFIXES
        and not PurePosixPath(f).name.startswith(".")
    ]
    return sorted([*bags, *names])


def _matches(fs: Any, path: str) -> list[str]:
    if fs.isdir(path):
        if fs.isfile(path.rstrip("/") + "/metadata.yaml"):
            return [path.rstrip("/")]
        return _logs_under(fs, path)
    return [path] if fs.exists(path) else []


def expand_url(url: str) -> list[str]:
    """The drives a URL names, as URLs, where the batch starts (no drive is read).

    A URL whose name ends in a log suffix (:data:`loaders.open.LOG_SUFFIXES`) is one drive,
    not checked here (the task reports a missing one as ``failed``: the workers may see what
    the starting machine does not). A
    pattern (``s3://bucket/drives/*.mcap``) is globbed and a directory searched (a rosbag2
    directory is one drive) with fsspec.

    Raises:
        FetchError: Unknown protocol, missing backend, a pattern or directory that matches
            nothing or cannot be listed.
    """
    fs, path = _filesystem(url)
    head, _, last = url.rpartition("::")
    inner = fs if not head else _filesystem(last)[0]

    def named(found: str) -> str:  # one spelling per object (memory://a is memory:///a)
        return f"{head}::" * bool(head) + str(inner.unstrip_protocol(found))

    magic = _HTTP_MAGIC if last.startswith(("http:", "https:")) else _MAGIC
    if not magic.search(path) and _suffix(path) in LOG_SUFFIXES:
        return [named(path)]
    try:
        found = sorted(fs.glob(path)) if magic.search(path) else [path]
        paths = [m for p in found for m in _matches(fs, p)]
    except (OSError, ValueError) as err:
        raise FetchError(f"{url}: cannot list ({one_line(err)})") from err
    if not paths:
        raise FetchError(f"{url}: no drive at or under this URL")
    return [named(p) for p in paths]


def _files(fs: Any, path: str) -> dict[str, str]:
    """The object's files by their path relative to the drive's parent."""
    name = PurePosixPath(path.rstrip("/")).name
    # A drive file's suffix: a file, without asking (an HTTP "isdir" is a GET of the page).
    if _suffix(name) in LOG_SUFFIXES or not fs.isdir(path):
        return {name: path}
    root = path.rstrip("/")
    inside = {f[len(root) + 1 :]: f for f in sorted(fs.find(root)) if f.startswith(f"{root}/")}
    # A listing's links name files under the drive only: no "..", nothing absolute.
    return {f"{name}/{rel}": f for rel, f in inside.items() if ".." not in rel.split("/")}


def stamp(url: str) -> str:
    """A fingerprint of the object(s) at ``url`` from their metadata (no content read).

    fsspec's ``ukey`` of each file: its info (size, and modification time, ETag or
    generation where the backend reports them). A resumed batch keeps a URL drive's record
    while this is unchanged.

    Raises:
        FetchError: The URL cannot be reached, or names nothing.
    """
    fs, path = _filesystem(url)
    try:
        keys = [f"{rel}\0{fs.ukey(f)}" for rel, f in _files(fs, path).items()]
    except (OSError, ValueError) as err:
        raise FetchError(f"{url}: cannot reach ({one_line(err)})") from err
    return hashlib.sha256("\n".join(keys).encode()).hexdigest()[:24]


def _limit_bytes(folder: Path) -> int:
    return max(0, min(MAX_FETCH_BYTES, shutil.disk_usage(folder).free - RESERVE_BYTES))


def _copy(fs: Any, source: str, target: Path, budget: int, url: str) -> int:
    target.parent.mkdir(parents=True, exist_ok=True)
    done = 0
    # One sequential read: HTTP as a stream (no range requests, which not every server
    # answers); the other file systems read ahead in blocks of their own size.
    protocols = (fs.protocol,) if isinstance(fs.protocol, str) else tuple(fs.protocol)
    stream = {"block_size": 0} if {"http", "https"} & set(protocols) else {}
    with fs.open(source, "rb", **stream) as src, target.open("wb") as dst:
        while block := src.read(CHUNK_BYTES):
            done += len(block)
            if done > budget:
                break
            dst.write(block)
    if done > budget:
        msg = f"{url}: more than {budget} bytes to fetch into {target.parent} (the task's limit)"
        raise FetchError(msg)
    return done


def fetch(url: str, folder: Path) -> Fetched:
    """Copy the drive at ``url`` (and its sidecar map) into ``folder``.

    Raises:
        FetchError: The URL cannot be reached, names nothing, or is larger than the limit
            (:data:`MAX_FETCH_BYTES`, and the free space of ``folder`` less 1 GiB).
    """
    fs, path = _filesystem(url)
    before = stamp(url)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        budget = _limit_bytes(folder)
        files = _files(fs, path)
        sizes = [fs.size(f) or 0 for f in files.values()]
        if sum(sizes) > budget:
            msg = (
                f"{url}: {sum(sizes)} bytes to fetch, more than the {budget} bytes"
                f" this task may write into {folder}"
            )
            raise FetchError(msg)
        fetched = 0
        for rel, source in files.items():
            fetched += _copy(fs, source, folder / rel, budget - fetched, url)
        log = folder / PurePosixPath(path.rstrip("/")).name
        parent = path.rstrip("/").rpartition("/")[0]
        scenario = log.suffix.lower() in SCENARIO_SUFFIXES  # CommonRoad, .saa: no sidecar
        for candidate in [] if scenario else sidecar_candidates(log):
            remote = f"{parent}/{candidate.relative_to(folder).as_posix()}"
            if not candidate.exists() and fs.isfile(remote):
                fetched += _copy(fs, remote, candidate, budget - fetched, url)
    except (OSError, ValueError) as err:
        raise FetchError(f"{url}: cannot fetch ({one_line(err)})") from err
    return Fetched(log, before, fetched)
