"""``labels export RESULTS`` and ``export RESULTS``: per drive, from the batch's incidents."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from tests.workbench.batch.conftest import ENGINES
from tests.workbench.batch.drives import GOOD
from tests.workbench.cli_runs import run_workbench
from workbench.annotations.store import LabelStore
from workbench.batch.queue import load_queue

if TYPE_CHECKING:
    from pathlib import Path

    import pytest


def _no_evaluation(*_args: Any, **_kwargs: Any) -> Any:
    raise AssertionError("a results directory is never evaluated again")


def test_labels_export_writes_the_single_drive_file_per_drive(
    fleet: Path, full: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    store = tmp_path / "labels.sqlite"
    drive = fleet / GOOD[0]
    single = tmp_path / "single.json"
    args = ["--store", str(store)]
    assert (
        run_workbench(
            ["labels", "export", str(drive), "--engines", ENGINES, "--out", str(single), *args]
        )
        == 0
    )
    monkeypatch.setattr("workbench.incidents.find_incidents", _no_evaluation)
    monkeypatch.setattr("workbench.incidents.find.find_incidents", _no_evaluation)
    out = tmp_path / "openlabel"
    assert run_workbench(["labels", "export", str(full), "--out", str(out), *args]) == 0
    files = sorted(p.name for p in out.iterdir())
    assert len(files) == 3  # the good drives and the partial one; not the failed ones
    ours = next(out.glob(f"{drive.name}-*.openlabel.json"))
    assert json.loads(ours.read_text()) == json.loads(single.read_text())


def test_export_of_a_results_dir_cuts_the_confirmed_incidents_of_every_drive(
    full: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    store = tmp_path / "labels.sqlite"
    chosen = load_queue(full)[0]
    with LabelStore(store) as labels:
        labels.put(chosen.drive_hash, chosen.incident.id, "confirmed", reviewer="test")
    monkeypatch.setattr("workbench.incidents.find_incidents", _no_evaluation)
    monkeypatch.setattr("workbench.incidents.find.find_incidents", _no_evaluation)
    out = tmp_path / "clips"
    args = ["export", str(full), "--verdict", "confirmed", "--out", str(out), "--store", str(store)]
    assert run_workbench([*args, "--no-rrd", "--no-thumbnails"]) == 0
    indexes = list(out.glob("*/clips.json"))
    written = [json.loads(p.read_text()) for p in indexes]
    ids = [clip["id"] for index in written for clip in index]
    assert ids == [chosen.incident.id]
    assert len(list(out.glob("*/*.mcap"))) == 1
