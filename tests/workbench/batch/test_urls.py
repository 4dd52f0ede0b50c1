"""``workbench batch`` with drives at URLs: ``file://`` (a path), ``http://`` on the process
pool (a server on 127.0.0.1 that every worker process reaches: the cross-process proof) and
fsspec's ``memory://`` in this process (its file system is private to a process, so those
tests prove the listing, fetching, hashing and resume logic, not a worker's read).
"""

from __future__ import annotations

import functools
import json
import random
import shutil
import sys
import threading
from concurrent.futures import Future
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import TYPE_CHECKING, Any

import fsspec
import pytest

from tests.workbench.batch.conftest import ENGINES
from tests.workbench.batch.drives import BAD, GOOD, SAMPLES, drive_rows, incident_rows
from tests.workbench.cli_runs import run_workbench
from workbench.batch import BatchError, expand_logs, remote, requests_for, run_batch
from workbench.incidents import IncidentRequest, drive_content_hash

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator


def test_file_urls_name_the_same_logs_as_paths(fleet: Path, tmp_path: Path) -> None:
    folder = tmp_path / "with space %"  # percent-encoded in the URL
    shutil.copytree(fleet, folder)
    assert expand_logs([(folder / GOOD[0]).as_uri()]) == [folder / GOOD[0]]
    assert expand_logs([folder.as_uri()]) == expand_logs([str(folder)])
    local = f"file://localhost{(folder / GOOD[1]).as_uri().removeprefix('file://')}"
    assert expand_logs([local]) == [folder / GOOD[1]]


def _one_line_error(argument: str) -> str:
    with pytest.raises(BatchError) as err:
        expand_logs([argument])
    text = str(err.value)
    assert argument in text
    assert "\n" not in text
    return text


def test_unknown_protocols_and_other_hosts_are_refused_in_one_line() -> None:
    assert "unknown URL protocol nosuch://" in _one_line_error("nosuch://bucket/a.mcap")
    assert "another host" in _one_line_error("file://host/a.mcap")


def test_a_missing_backend_names_what_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "s3fs", None)  # as if not installed
    text = _one_line_error("s3://bucket/drives/*.mcap")
    assert "s3:// file system is not installed" in text
    assert "pip install 'fsspec[s3]'" in text


class _Quiet(SimpleHTTPRequestHandler):
    def log_message(self, *_args: Any) -> None:
        """No access log on stderr."""


#: Bytes of a log larger than fsspec's HTTP block (5 MiB): read as one stream.
BIG_BYTES = 6 << 20


@pytest.fixture(scope="module")
def http_root(fleet: Path, tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """``http://127.0.0.1:PORT``: a copy of the fleet in ``/fleet``, ``/big/big.mcap``.

    Python's server: directory listings, no range requests, no ETag.
    """
    folder = tmp_path_factory.mktemp("served")
    shutil.copytree(fleet, folder / "fleet")
    (folder / "big").mkdir()
    (folder / "big" / "big.mcap").write_bytes(random.Random(30).randbytes(BIG_BYTES))  # noqa: S311
    server = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_Quiet, directory=folder))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        thread.join()
        server.server_close()


@pytest.fixture(scope="module")
def http_fleet(http_root: str) -> str:
    """The fleet's folder on the server."""
    return f"{http_root}/fleet"


def test_http_globs_and_directories_list_like_paths(fleet: Path, http_fleet: str) -> None:
    local = expand_logs([str(fleet)])
    assert expand_logs([f"{http_fleet}/"]) == [f"{http_fleet}/{Path(p).name}" for p in local]
    mcaps = [f"{http_fleet}/{Path(p).name}" for p in local if Path(p).suffix == ".mcap"]
    assert expand_logs([f"{http_fleet}/*.mcap"]) == mcaps
    assert "no drive" in _one_line_error(f"{http_fleet}/nothing-*.mcap")
    missing = f"{http_fleet}/missing.mcap"
    assert expand_logs([missing]) == [missing]  # not checked where the batch starts


@pytest.fixture(scope="module")
def mixed(
    fleet: Path, http_root: str, http_fleet: str, tmp_path_factory: pytest.TempPathFactory
) -> tuple[Path, list[str]]:
    """A process-pool batch of one local drive, the fleet's others over HTTP, a 404 and a
    6 MiB log: its results directory and its command line.
    """
    logs = [str(fleet / GOOD[1]), *(f"{http_fleet}/{name}" for name in (GOOD[0], *BAD))]
    logs += [f"{http_fleet}/missing.mcap", f"{http_root}/big/big.mcap"]
    out = tmp_path_factory.mktemp("mixed") / "results"
    args = ["batch", *logs, "--out", str(out), "--jobs", "2", "--engines", ENGINES]
    assert run_workbench(args) == 0
    return out, args


def test_mixed_local_and_http_drives_on_the_process_pool(
    fleet: Path, full: Path, http_fleet: str, mixed: tuple[Path, list[str]], tmp_path: Path
) -> None:
    """Same rows as the all-local batch; the URL drives keep their URL; resume keeps them."""
    out, args = mixed
    as_url = {name: f"{http_fleet}/{name}" for name in (GOOD[0], *BAD)}
    (tmp_path / "big.mcap").write_bytes(random.Random(30).randbytes(BIG_BYTES))  # noqa: S311

    def located(path: str) -> str:
        return as_url.get(Path(path).name, path)

    expected = [{**r, "drive_path": located(r["drive_path"])} for r in incident_rows(full)]
    assert expected
    assert incident_rows(out) == expected
    drives, local = drive_rows(out), drive_rows(full)
    for name, row in local.items():
        got = drives[name]
        assert got["path"] == located(row["path"])
        for key in ("content_hash", "format", "frames", "status", "error_type"):
            assert got[key] == row[key], (name, key)
        if row["error"] is not None:  # the message names the URL, not the worker's copy
            assert got["error"] == row["error"].replace(str(fleet), http_fleet)
    big = drives["big.mcap"]  # fetched whole, then refused by the loader
    assert big["error_type"] == "CorruptLogError"
    assert big["content_hash"] == drive_content_hash(tmp_path / "big.mcap")
    missing = drives["missing.mcap"]
    assert (missing["status"], missing["error_type"]) == ("failed", "FetchError")
    assert f"{http_fleet}/missing.mcap" in missing["error"]

    assert run_workbench(args) == 0  # resumed: only the unreachable URL is tried again
    assert json.loads((out / "batch.json").read_text())["evaluated"] == 1  # missing.mcap
    assert incident_rows(out) == expected


def test_fleet_commands_fetch_url_drives_again(
    full: Path, mixed: tuple[Path, list[str]], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``labels export``, ``export`` and ``review`` of a results directory with URL drives."""
    out, _ = mixed
    store = ["--store", str(tmp_path / "labels.sqlite")]
    written = {}
    for name, results in (("url", out), ("local", full)):
        folder = tmp_path / name
        assert run_workbench(["labels", "export", str(results), "--out", str(folder), *store]) == 0
        written[name] = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert len(written["url"]) == 3  # the good drives and the partial one
    assert written["url"] == written["local"]

    clips = tmp_path / "clips"
    args = ["export", str(out), "--all", "--out", str(clips), "--no-rrd", "--no-thumbnails"]
    assert run_workbench([*args, *store]) == 0
    sources = {c["source"] for p in clips.glob("*/clips.json") for c in json.loads(p.read_text())}
    assert sources == {r["drive_path"] for r in incident_rows(out)}
    assert any(s.startswith("http://") for s in sources)

    alive: list[bool] = []

    def reviewer(session: Any, viewer: Any = None) -> None:
        assert viewer is None
        alive.extend(s.report.log.exists() for s in session.sessions)

    monkeypatch.setattr("workbench.review.loop.run_review", reviewer)
    assert run_workbench(["review", str(out), *store]) == 0
    assert alive == [True, True]  # the copies live while the queue is reviewed


class _InlinePool:
    """Runs each task in this process (``memory://`` is private to a process)."""

    name = "in-process"
    workers = 1

    def submit(self, fn: Callable[[Any], Any], arg: Any) -> Future[Any]:
        future: Future[Any] = Future()
        future.set_result(fn(arg))
        return future

    def recover(self) -> None:
        """Nothing to recover."""


BAG = "hard_braking_lead_rosbag2"


@pytest.fixture
def memory_fleet() -> Iterator[str]:
    """``memory://fleet30``: a rosbag2 directory (map inside), an MCAP with its sidecar map."""
    fs = fsspec.filesystem("memory")
    root = "/fleet30"
    fs.put(str(SAMPLES / BAG), f"{root}/{BAG}", recursive=True)
    for name in ("hard_braking_lead.mcap", "hard_braking_lead.osm"):
        fs.pipe(f"{root}/drives/{name}", (SAMPLES / name).read_bytes())
    try:
        yield "memory://fleet30"
    finally:
        fs.rm(root, recursive=True)


def _batch(logs: list[Path | str], out: Path) -> dict[str, dict[str, Any]]:
    template = IncidentRequest(log=Path(), engines=(ENGINES,))
    run_batch(requests_for(logs, template), out, _InlinePool())
    return {Path(r["path"]).name: r for r in drive_rows(out).values()}


def _named(row: dict[str, Any]) -> dict[str, Any]:
    return {**row, "drive_path": Path(row["drive_path"]).name}


def test_memory_urls_give_the_rows_of_the_same_local_drives(
    memory_fleet: str, tmp_path: Path
) -> None:
    urls = expand_logs([f"{memory_fleet}/"])  # fsspec's one spelling: memory:///fleet30
    assert urls == ["memory:///fleet30/drives/hard_braking_lead.mcap", f"memory:///fleet30/{BAG}"]
    remote_rows = _batch(list(urls), tmp_path / "url")
    local_rows = _batch([SAMPLES / BAG, SAMPLES / "hard_braking_lead.mcap"], tmp_path / "local")
    for name, row in local_rows.items():
        for key in ("content_hash", "format", "frames", "status", "incidents"):
            assert remote_rows[name][key] == row[key], (name, key)
    assert all(r["status"] == "ok" for r in remote_rows.values())
    by_name = [_named(r) for r in incident_rows(tmp_path / "url")]
    assert by_name
    assert by_name == [_named(r) for r in incident_rows(tmp_path / "local")]


def test_a_fetch_brings_the_sidecar_map_and_the_whole_bag(
    memory_fleet: str, tmp_path: Path
) -> None:
    single = remote.fetch(f"{memory_fleet}/drives/hard_braking_lead.mcap", tmp_path / "a")
    assert sorted(p.name for p in single.log.parent.iterdir()) == [
        "hard_braking_lead.mcap",
        "hard_braking_lead.osm",
    ]
    bag = remote.fetch(f"{memory_fleet}/{BAG}", tmp_path / "b")
    assert sorted(p.name for p in bag.log.iterdir()) == sorted(
        p.name for p in (SAMPLES / BAG).iterdir()
    )
    assert bag.size_bytes == sum(p.stat().st_size for p in (SAMPLES / BAG).iterdir())


def test_resume_skips_an_unchanged_url_and_evaluates_a_changed_one(
    memory_fleet: str, tmp_path: Path
) -> None:
    url = f"{memory_fleet}/drives/hard_braking_lead.mcap"
    out = tmp_path / "out"
    first = _batch([url], out)["hard_braking_lead.mcap"]
    template = IncidentRequest(log=Path(), engines=(ENGINES,))
    again = run_batch(requests_for([url], template), out, _InlinePool())
    assert (again.evaluated, again.skipped) == (0, 1)
    data = (SAMPLES / "hard_braking_lead.mcap").read_bytes()
    fsspec.filesystem("memory").pipe(url.removeprefix("memory://"), data[: len(data) // 2])
    changed = run_batch(requests_for([url], template), out, _InlinePool())
    assert (changed.evaluated, changed.skipped) == (1, 0)
    row = drive_rows(out)["hard_braking_lead.mcap"]
    assert row["status"] == "partial"
    assert row["content_hash"] != first["content_hash"]


def test_a_url_over_the_size_limit_fails_in_one_line(
    memory_fleet: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(remote, "MAX_FETCH_BYTES", 1000)
    url = f"{memory_fleet}/drives/hard_braking_lead.mcap"
    row = _batch([url], tmp_path / "out")["hard_braking_lead.mcap"]
    assert (row["status"], row["error_type"]) == ("failed", "FetchError")
    assert row["error"].startswith(f"{url}: ")
    assert "more than the 1000 bytes" in row["error"]
