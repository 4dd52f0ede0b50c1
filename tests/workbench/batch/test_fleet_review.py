"""``review RESULTS``: one queue over every drive, worst first, each drive opened when due."""

from __future__ import annotations

import contextlib
import json
from typing import TYPE_CHECKING, Any

import pytest
import rerun as rr

from tests.workbench.batch.drives import free_port
from tests.workbench.cli_runs import run_workbench
from workbench.annotations.store import LabelStore
from workbench.batch.queue import load_queue
from workbench.review import loop

if TYPE_CHECKING:
    from collections.abc import Iterator
    from pathlib import Path

    from workbench.review.fleet import FleetSession


def _no_evaluation(*_args: Any, **_kwargs: Any) -> Any:
    raise AssertionError("a results directory is never evaluated again")


def _no_find(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("workbench.incidents.find_incidents", _no_evaluation)
    monkeypatch.setattr("workbench.incidents.find.find_incidents", _no_evaluation)


def test_review_of_a_results_dir_is_one_queue_worst_first_across_drives(
    full: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[tuple[str, str]] = []
    written: list[tuple[str, str]] = []

    def reviewer(session: FleetSession, viewer: Any = None) -> None:
        assert viewer is None  # no viewer asked for
        seen.extend((session.session_of(i).report.drive_hash, i.id) for i in session.incidents)
        first = session.current
        assert first is not None
        session.give("confirmed")  # moves nothing: the UI moves the cursor
        written.append((session.session_of(first).report.drive_hash, first.id))
        last = session.go(len(session.incidents) - 1)
        assert last is not None
        session.give("false_positive")
        assert session.undo() is last  # the last write taken back, cursor on its row
        assert session.index == len(session.incidents) - 1

    _no_find(monkeypatch)
    monkeypatch.setattr("workbench.review.loop.run_review", reviewer)
    store = tmp_path / "labels.sqlite"
    args = ["review", str(full), "--store", str(store), "--by", "incident"]
    assert run_workbench(args) == 0

    queue = load_queue(full)
    assert seen == [(f.drive_hash, f.incident.id) for f in queue]
    assert len({drive for drive, _ in seen}) > 1  # one queue over several drives
    with LabelStore(store) as labels:
        stored = {
            (drive, incident_id): label.verdict
            for drive in {d for d, _ in seen}
            for incident_id, label in labels.labels(drive).items()
        }
    assert stored == dict.fromkeys(written, "confirmed")


@pytest.mark.parametrize("keep", ["all", "none"])
def test_review_of_a_results_dir_keeps_the_filters_of_incidents(
    keep: str, full: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    queue = load_queue(full)
    margins = [f.incident.severity.worst_margin for f in queue]
    cut = max(margins) if keep == "all" else min(margins) - 1.0
    listed = tmp_path / "listed.json"
    filters = ["--max-margin", str(cut)]
    assert run_workbench(["incidents", str(full), *filters, "--out", str(listed)]) == 0
    seen: list[str] = []
    _no_find(monkeypatch)
    monkeypatch.setattr(
        "workbench.review.loop.run_review",
        lambda session, viewer=None: seen.extend(i.id for i in session.incidents),
    )
    store = ["--store", str(tmp_path / "labels.sqlite")]
    assert run_workbench(["review", str(full), *filters, "--by", "incident", *store]) == 0
    expected = [row["id"] for row in json.loads(listed.read_text())]
    assert seen == expected
    assert len(seen) == (len(queue) if keep == "all" else 0)


def test_review_of_a_results_dir_opens_each_drive_when_its_incident_comes_up(
    full: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    opened: list[str] = []
    replayed = loop.replayed

    @contextlib.contextmanager
    def counted(source: Any, destination: Any, progress: Any = None) -> Iterator[Any]:
        opened.append(source.drive_hash)
        assert source.incidents  # the batch's incidents: the pass only draws
        with replayed(source, destination, progress) as live:
            yield live

    walked: list[str] = []

    def reviewer(session: FleetSession, viewer: Any = None) -> None:
        assert viewer is not None
        for incident in session.incidents:
            walked.append(session.session_of(incident).report.drive_hash)
            viewer.show(incident)
            viewer.mark(incident, "confirmed")

    _no_find(monkeypatch)
    monkeypatch.setattr(loop, "replayed", counted)
    monkeypatch.setattr(loop, "run_review", reviewer)
    sink = rr.RecordingStream("fleet-review-test")  # an in-process gRPC proxy as the viewer
    url = rr.serve_grpc(grpc_port=free_port(), recording=sink)
    store = ["--store", str(tmp_path / "labels.sqlite")]
    assert run_workbench(["review", str(full), "--connect", url, *store]) == 0
    changes = [d for k, d in enumerate(walked) if k == 0 or walked[k - 1] != d]
    assert opened == changes  # a drive is opened when the queue reaches it, not before
    assert set(opened) == {f.drive_hash for f in load_queue(full)}


def test_review_of_a_results_dir_refuses_serve_in_one_line(
    full: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    store = ["--store", str(tmp_path / "labels.sqlite")]
    assert run_workbench(["review", str(full), "--serve", *store]) != 0
    err = capsys.readouterr().err.strip()
    assert "--serve" in err
    assert "Traceback" not in err
