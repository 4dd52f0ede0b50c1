"""``workbench diff``: new, vanished and changed incidents between two batches, labels joined."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

import pyarrow.parquet as pq

from tests.workbench.cli_runs import run_workbench
from workbench.annotations.store import LabelStore
from workbench.batch.diff import Tolerance, diff_results

if TYPE_CHECKING:
    from pathlib import Path

    import pytest

#: Two small NGSIM scenarios (the 11-scenario run is in docs/fleet.md).
SCENARIOS = ("USA_US101-3_3_T-1.xml", "USA_Peach-3_1_T-1.xml")


def test_a_batch_against_itself_has_no_change(full: Path) -> None:
    result = diff_results(full, full)
    assert result.changes == []
    assert result.matched == len(pq.read_table(full / "incidents.parquet"))
    assert result.only_a == result.only_b == 0


def test_drives_evaluated_on_one_side_only_are_not_compared(reference: Path, full: Path) -> None:
    result = diff_results(reference, full)
    assert result.changes == []
    assert (result.only_a, result.only_b) == (0, 1)  # the partial half.mcap


def test_tolerance_compares_numbers_relatively_and_the_rest_exactly() -> None:
    tol = Tolerance(rtol=0.05)
    assert tol.same(1.0, 1.04)
    assert not tol.same(1.0, 1.2)
    assert tol.same([1.0, "x"], [1.01, "x"])
    assert not tol.same("ego", "both")
    assert not tol.same(True, False)


def test_profiles_diff_on_ngsim_lists_vanished_and_fails_on_a_confirmed_one(
    external_dir: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    logs = [str(external_dir / "commonroad_ngsim" / name) for name in SCENARIOS]
    batches = {}
    for profile in ("adrss-5.0", "highway"):
        out = tmp_path / profile
        args = ["batch", *logs, "--out", str(out), "--rss-profile", profile, "--engines", "rss"]
        assert run_workbench([*args, "--jobs", "2"]) == 0
        batches[profile] = out
    store = tmp_path / "labels.sqlite"
    report = tmp_path / "diff.json"
    a, b = str(batches["adrss-5.0"]), str(batches["highway"])
    base = ["diff", a, b, "--store", str(store), "--fail-on", "vanished-confirmed"]
    assert run_workbench([*base, "--out", str(report)]) == 0
    changes = json.loads(report.read_text())["changes"]
    vanished = [c for c in changes if c["kind"] == "vanished"]
    assert vanished
    b_rows = pq.read_table(batches["highway"] / "incidents.parquet").to_pylist()
    for change in vanished:
        a_row = change["a"]
        assert change["b"] is None
        assert a_row["severity.profile"] == "adrss-5.0"
        assert a_row["severity.worst_margin"] is not None
        assert not [
            r
            for r in b_rows
            if (r["drive_hash"], r["engine"], r["objects"])
            == (a_row["drive_hash"], a_row["engine"], a_row["objects"])
            and r["start_ns"] <= a_row["end_ns"]
            and a_row["start_ns"] <= r["end_ns"]
        ]
    chosen = vanished[-1]["a"]
    with LabelStore(store) as labels:
        labels.put(chosen["drive_hash"], chosen["id"], "confirmed", reviewer="test")
    capsys.readouterr()
    assert run_workbench([*base, "--out", str(report)]) == 1
    first = json.loads(report.read_text())["changes"][0]
    assert (first["kind"], first["verdict"], first["a"]["id"]) == (
        "vanished-confirmed",
        "confirmed",
        chosen["id"],
    )
    captured = capsys.readouterr()
    assert "failing: vanished-confirmed" in captured.err
    assert "(1 confirmed)" in captured.out
