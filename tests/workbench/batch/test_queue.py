"""``workbench incidents RESULTS_DIR``: all drives' incidents, worst first, not evaluated again."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from tests.workbench.batch.conftest import ENGINES
from tests.workbench.batch.drives import GOOD, incident_rows
from tests.workbench.cli_runs import run_workbench
from workbench.batch.queue import incident_of, load_queue
from workbench.incidents.order import severity_key

if TYPE_CHECKING:
    from pathlib import Path

    import pytest


def _no_evaluation(*_args: Any, **_kwargs: Any) -> Any:
    raise AssertionError("a results directory is never evaluated again")


def test_incidents_of_a_results_dir_are_the_drives_incidents_worst_first(
    fleet: Path,
    full: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    single = tmp_path / "single.json"
    drive = fleet / GOOD[0]
    assert run_workbench(["incidents", str(drive), "--engines", ENGINES, "--out", str(single)]) == 0
    monkeypatch.setattr("workbench.incidents.find_incidents", _no_evaluation)
    monkeypatch.setattr("workbench.incidents.find.find_incidents", _no_evaluation)
    out = tmp_path / "fleet.json"
    assert run_workbench(["incidents", str(full), "--out", str(out)]) == 0
    listed = json.loads(out.read_text())
    assert len(listed) == len(incident_rows(full)) > 0
    ours = [r for r in listed if r["drive_path"] == str(drive)]
    expected = json.loads(single.read_text())
    assert [r["id"] for r in ours] == [i["id"] for i in expected]
    assert [r["severity.worst_margin"] for r in ours] == [
        i["severity"]["worst_margin"] for i in expected
    ]
    keys = [severity_key(incident_of(r))[:-2] for r in listed]
    assert keys == sorted(keys)
    table = capsys.readouterr().out
    assert f"{len(listed)} of {len(listed)} incident(s)" in table
    assert "hard_braking_lead" in table


def test_results_dir_filters_are_the_single_drive_ones(full: Path, tmp_path: Path) -> None:
    queue = load_queue(full)
    drive = queue[0].drive_path
    obj = queue[0].incident.objects[0]
    out = tmp_path / "some.parquet"
    assert run_workbench(["incidents", str(full), "--object", obj, "--out", str(out)]) == 0
    import pyarrow.parquet as pq  # noqa: PLC0415

    rows = pq.read_table(out).to_pylist()
    assert rows
    assert all(obj in r["objects"] for r in rows)
    assert any(r["drive_path"] == drive for r in rows)
    csv = tmp_path / "some.csv"
    assert run_workbench(["incidents", str(full), "--object", obj, "--out", str(csv)]) == 0
    lines = csv.read_text().splitlines()
    assert len(lines) == len(rows) + 1
    assert obj in lines[1]
    assert run_workbench(["incidents", str(full), "--engine", "nope", "--out", str(out)]) == 0
    assert pq.read_table(out).num_rows == 0
