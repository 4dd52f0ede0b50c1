"""``workbench batch`` on the local process pool: statuses, resume, killed workers and batches."""

from __future__ import annotations

import contextlib
import functools
import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.workbench.batch.conftest import ENGINES
from tests.workbench.batch.drives import (
    BAD,
    GOOD,
    ROOT,
    die_once,
    drive_rows,
    incident_rows,
)
from tests.workbench.cli_runs import run_workbench
from workbench.batch import open_pool, requests_for, run_batch
from workbench.incidents import IncidentRequest


def _good(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [r for r in rows if Path(r["drive_path"]).name in GOOD]


def test_bad_logs_fail_with_their_error_and_good_rows_are_unchanged(
    fleet: Path, reference: Path, full: Path
) -> None:
    drives = drive_rows(full)
    assert set(drives) == {*GOOD, *BAD}
    for name in GOOD:
        assert drives[name]["status"] == "ok", drives[name]
        assert drives[name]["frames"] > 0
        assert len(drives[name]["content_hash"]) == 64
    for name, status in BAD.items():
        assert drives[name]["status"] == status, drives[name]
        assert name in drives[name]["error"]
        assert drives[name]["error_type"].endswith("Error")
    assert drives["half.mcap"]["frames"] > 0
    assert drives["empty.bag"]["error_type"] == "EmptyLogError"
    rows = incident_rows(full)
    assert _good(rows) == incident_rows(reference)
    assert {Path(r["drive_path"]).name for r in rows} <= {*GOOD, "half.mcap"}
    assert all(r["drive_hash"] == drives[Path(r["drive_path"]).name]["content_hash"] for r in rows)
    batch = json.loads((full / "batch.json").read_text())
    assert batch["status_counts"] == {"ok": 2, "partial": 1, "empty": 0, "failed": 4}
    assert sorted(Path(f["path"]).name for f in batch["failed"]) == sorted(
        n for n, s in BAD.items() if s == "failed"
    )
    assert batch["settings"]["engines"] == ENGINES.split(",")
    assert str(fleet) in batch["failed"][0]["path"]


def test_summary_names_the_failed_logs(
    fleet: Path, full: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    logs = [str(fleet / name) for name in (*GOOD, *BAD)]
    assert (
        run_workbench(["batch", *logs, "--out", str(full), "--jobs", "1", "--engines", ENGINES])
        == 0
    )
    out = capsys.readouterr().out
    assert "0 evaluated, 7 kept from an earlier run" in out
    assert "2 ok, 1 partial, 0 empty, 4 failed" in out
    for name, status in BAD.items():
        assert any(line.startswith(f"{status}: ") and name in line for line in out.splitlines())


def test_rerun_evaluates_only_changed_logs_or_settings(
    fleet: Path, reference: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "copy"
    shutil.copytree(reference, out)
    logs = [str(fleet / name) for name in GOOD]
    args = ["batch", *logs, "--out", str(out), "--jobs", "1", "--engines", ENGINES]
    capsys.readouterr()
    assert run_workbench(args) == 0
    assert "0 evaluated, 2 kept" in capsys.readouterr().out
    assert incident_rows(out) == incident_rows(reference)
    assert run_workbench(["batch", logs[1], *args[3:], "--min-duration", "0.2"]) == 0
    assert "1 evaluated, 0 kept" in capsys.readouterr().out
    saa = tmp_path / GOOD[1]
    shutil.copy(fleet / GOOD[1], saa)
    own = ["batch", str(saa), "--out", str(tmp_path / "own"), "--jobs", "1", "--engines", ENGINES]
    assert run_workbench(own) == 0
    assert "1 evaluated, 0 kept" in capsys.readouterr().out
    saa.write_bytes(saa.read_bytes() + b"\n")
    assert run_workbench(own) == 0
    assert "1 evaluated, 0 kept" in capsys.readouterr().out
    assert run_workbench(own) == 0
    assert "0 evaluated, 1 kept" in capsys.readouterr().out


def test_a_killed_worker_is_replaced_and_the_tables_are_the_same(
    fleet: Path, reference: Path, tmp_path: Path
) -> None:
    template = IncidentRequest(log=fleet, engines=tuple(ENGINES.split(",")))
    requests = requests_for([fleet / name for name in GOOD], template)
    marker = tmp_path / "killed"
    with open_pool(None, 2) as pool:
        summary = run_batch(
            requests, tmp_path / "out", pool, task=functools.partial(die_once, str(marker))
        )
    assert marker.exists()
    assert [d["status"] for d in summary.drives] == ["ok", "ok"]
    assert incident_rows(tmp_path / "out") == incident_rows(reference)


def test_a_killed_batch_reruns_only_the_unfinished_logs(
    fleet: Path, reference: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    logs = [str(fleet / name) for name in GOOD]
    args = ["batch", *logs, "--out", str(out), "--jobs", "1", "--engines", ENGINES]
    command = [sys.executable, "-c", "from workbench.cli.main import main; main()", *args]
    proc = subprocess.Popen(  # noqa: S603 - our own CLI
        command, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    with contextlib.suppress(subprocess.TimeoutExpired):
        proc.wait(timeout=0.5)
    records = out / "logs"
    try:
        for _ in range(1200):  # at most 120 s for the first log
            if proc.poll() is not None or (records.is_dir() and any(records.glob("*.json"))):
                break
            with contextlib.suppress(subprocess.TimeoutExpired):
                proc.wait(timeout=0.1)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    finished = len(list(records.glob("*.json")))
    assert finished >= 1
    assert run_workbench(args) == 0
    assert f"{len(GOOD) - finished} evaluated, {finished} kept" in capsys.readouterr().out
    assert incident_rows(out) == incident_rows(reference)


def test_missing_extra_and_bad_cluster_are_one_line_errors(
    fleet: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    log = str(fleet / GOOD[1])
    monkeypatch.setitem(sys.modules, "ray", None)
    assert run_workbench(["batch", log, "--out", str(tmp_path), "--cluster", "ray-local:1"]) == 2
    err = capsys.readouterr().err
    assert "pip install 'rss-workbench[ray]'" in err
    assert len(err.strip().splitlines()) == 1
    assert run_workbench(["batch", log, "--out", str(tmp_path), "--cluster", "spark://x"]) == 2
    assert "expected tcp://HOST:PORT" in capsys.readouterr().err


def test_a_log_without_frames_is_empty_and_one_losing_ego_messages_partial(
    tmp_path: Path,
) -> None:
    """The /tf ego with a vehicle frame no transform reaches: no frame; the lidar: losses."""
    from tests.loaders.ego_logs import write_variant  # noqa: PLC0415

    bag = write_variant(ROOT, tmp_path, "tf", storage="bag")
    for frame, status in (("nowhere", "empty"), ("lidar", "partial")):
        profile = tmp_path / f"{frame}.toml"
        profile.write_text(f'[tf]\nvehicle_frame = "{frame}"\n', encoding="utf-8")
        out = tmp_path / frame
        args = ["batch", str(bag), "--out", str(out), "--profile", str(profile)]
        assert run_workbench([*args, "--jobs", "1", "--engines", ENGINES]) == 0
        drive = drive_rows(out)[bag.name]
        assert drive["status"] == status, drive
        assert drive["frames_lost"] > 0
        assert drive["error"] is None
        assert (drive["frames"] == 0) == (status == "empty")


def test_log_arguments_expand_to_drives(tmp_path: Path) -> None:
    from workbench.batch import BatchError, expand_logs  # noqa: PLC0415

    samples = ROOT / "sample_logs"
    found = [p for p in expand_logs([str(samples)]) if isinstance(p, Path)]
    assert found == expand_logs([str(samples)])  # paths, no URL
    names = [p.name for p in found]
    assert "highway_cut_in_rosbag2" in names  # a rosbag2 directory is one drive
    assert not [n for n in names if n.endswith((".db3", ".osm", ".json"))]
    assert found == sorted(found)
    assert all(p.is_absolute() for p in found)
    assert expand_logs([str(samples / "*.saa"), str(samples / "racing_overtake.saa")]) == [
        samples / "racing_overtake.saa"
    ]
    with pytest.raises(BatchError, match="no such file"):
        expand_logs([str(tmp_path / "none*.mcap")])
