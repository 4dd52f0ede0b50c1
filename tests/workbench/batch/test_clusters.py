"""The same batch on a stand-alone Dask cluster (scheduler + 2 workers on 127.0.0.1), on a
local Ray instance and on a Ray head (`ray start --head`, 127.0.0.1) through Ray Client
(``ray://``): the same tables as the process pool, a killed worker changes nothing.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from tests.workbench.batch.drives import (
    BAD,
    GOOD,
    ROOT,
    die_once,
    drive_rows,
    free_port,
    incident_rows,
)
from tests.workbench.cli_runs import run_workbench
from workbench.batch import open_pool, requests_for, run_batch
from workbench.incidents import IncidentRequest

if TYPE_CHECKING:
    from collections.abc import Iterator

#: Seconds the cluster may take to come up (a loaded 2-core machine).
START_TIMEOUT_S = 120


@pytest.fixture(scope="module")
def logs(fleet: Path) -> list[str]:
    return [str(fleet / name) for name in (*GOOD, *BAD)]


def _spawn(
    args: list[str], log: Path, program: str = "dask", **env_vars: str
) -> subprocess.Popen[bytes]:
    env = {**os.environ, "PYTHONPATH": str(ROOT), **env_vars}
    with log.open("wb") as fh:
        return subprocess.Popen(  # noqa: S603 - the venv's own dask or ray
            [str(Path(sys.executable).with_name(program)), *args],
            env=env,
            stdout=fh,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )


def _stop(procs: list[subprocess.Popen[bytes]]) -> None:
    for proc in procs:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGTERM)
    for proc in procs:
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


@pytest.fixture(scope="module")
def dask_scheduler(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """``tcp://127.0.0.1:PORT`` of a stand-alone ``dask scheduler`` with two ``dask worker``s."""
    from distributed import Client  # noqa: PLC0415

    folder = tmp_path_factory.mktemp("dask")
    file = folder / "scheduler.json"
    common = ["--no-dashboard"]
    procs = [
        _spawn(
            [
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--scheduler-file",
                str(file),
                *common,
            ],
            folder / "scheduler.log",
        )
    ]
    try:
        deadline = time.monotonic() + START_TIMEOUT_S
        while not file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        address = json.loads(file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        worker = ["worker", "--scheduler-file", str(file), "--nthreads", "1", "--host", "127.0.0.1"]
        procs.extend(
            _spawn([*worker, "--name", f"w{k}", *common], folder / f"worker{k}.log")
            for k in range(2)
        )
        with Client(address, timeout=f"{START_TIMEOUT_S}s") as client:  # type: ignore[no-untyped-call]
            client.wait_for_workers(2, timeout=START_TIMEOUT_S)
        yield address
    finally:
        _stop(procs)


def test_dask_standalone_cluster_gives_the_same_tables(
    logs: list[str], full: Path, dask_scheduler: str, tmp_path: Path
) -> None:
    out = tmp_path / "dask"
    args = ["batch", *logs, "--out", str(out), "--cluster", dask_scheduler, "--engines", "rss"]
    assert run_workbench(args) == 0
    assert incident_rows(out) == incident_rows(full)
    drives, expected = drive_rows(out), drive_rows(full)
    for name, status in {**dict.fromkeys(GOOD, "ok"), **BAD}.items():
        assert drives[name]["status"] == status
        assert drives[name]["error"] == expected[name]["error"]
    workers = {d["worker"] for d in drives.values()}
    assert all(w.split(":")[-1].isdigit() for w in workers)
    assert json.loads((out / "batch.json").read_text())["executor"].startswith(
        f"dask {dask_scheduler}"
    )


def test_dask_worker_killed_mid_batch_changes_nothing(
    logs: list[str], full: Path, dask_scheduler: str, tmp_path: Path
) -> None:
    template = IncidentRequest(log=Path(logs[0]), engines=("rss",))
    requests = requests_for([Path(p) for p in logs], template)
    marker = tmp_path / "killed"
    with open_pool(dask_scheduler, None) as pool:
        summary = run_batch(
            requests, tmp_path / "out", pool, task=functools.partial(die_once, str(marker))
        )
    assert marker.exists()
    assert len(summary.drives) == len(logs)
    assert incident_rows(tmp_path / "out") == incident_rows(full)


def test_ray_local_gives_the_same_tables(logs: list[str], full: Path, tmp_path: Path) -> None:
    out = tmp_path / "ray"
    args = ["batch", *logs, "--out", str(out), "--cluster", "ray-local:2", "--engines", "rss"]
    assert run_workbench(args) == 0
    assert incident_rows(out) == incident_rows(full)
    drives = drive_rows(out)
    assert {n: d["status"] for n, d in drives.items()} == {
        n: d["status"] for n, d in drive_rows(full).items()
    }


def _wait_for_ray_to_end() -> None:
    """Wait (up to the start time-out) until no Ray instance of an earlier test still runs:
    one shutting down while a head starts is a known source of failed Ray Client starts."""
    deadline = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < deadline:
        names = set()
        for comm in Path("/proc").glob("[0-9]*/comm"):
            with contextlib.suppress(OSError):
                names.add(comm.read_text().strip())
        if not names & {"raylet", "gcs_server"}:
            return
        time.sleep(0.5)


@pytest.fixture(scope="module")
def ray_head(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """``ray://127.0.0.1:PORT`` of a Ray head (``ray start --head --block``) on 127.0.0.1."""
    folder = tmp_path_factory.mktemp("ray")
    client_port = free_port()
    args = ["start", "--head", "--block", "--node-ip-address", "127.0.0.1"]
    args += ["--port", str(free_port()), "--ray-client-server-port", str(client_port)]
    args += ["--num-cpus", "2", "--include-dashboard", "false", "--disable-usage-stats"]
    _wait_for_ray_to_end()
    # Ray's single-machine mode: its servers listen on 127.0.0.1, not the network address.
    head = _spawn(args, folder / "head.log", "ray", RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER="0")
    try:
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline and head.poll() is None:
            with contextlib.suppress(OSError), socket.create_connection(("127.0.0.1", client_port)):
                break
            time.sleep(0.5)
        assert head.poll() is None, (folder / "head.log").read_text()
        yield f"ray://127.0.0.1:{client_port}"
    finally:
        _stop([head])  # SIGTERM: `ray start --block` drains and stops its processes


def test_ray_client_gives_the_same_tables(
    logs: list[str], full: Path, ray_head: str, tmp_path: Path
) -> None:
    out = tmp_path / "ray-client"
    args = ["batch", *logs, "--out", str(out), "--cluster", ray_head, "--engines", "rss"]
    assert run_workbench(args) == 0
    assert incident_rows(out) == incident_rows(full)
    timing = ("wall_s", "worker")
    drives, expected = drive_rows(out), drive_rows(full)
    assert drives.keys() == expected.keys()
    for name, row in drives.items():
        assert {k: v for k, v in row.items() if k not in timing} == {
            k: v for k, v in expected[name].items() if k not in timing
        }
    assert json.loads((out / "batch.json").read_text())["executor"] == f"ray {ray_head}"
