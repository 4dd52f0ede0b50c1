"""The review UI over a queue of several drives (textual's Pilot, no engine run)."""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING

from tests.workbench.review.helpers import incident, report
from workbench.annotations import LabelStore
from workbench.review import ReviewSession
from workbench.review.app import ReviewApp
from workbench.review.fleet import FleetSession, FleetViewer

if TYPE_CHECKING:
    from collections.abc import Iterator

    from workbench.incidents import Incident, IncidentReport


def _drive(name: str, criticalities: list[float]) -> IncidentReport:
    """A drive whose incidents have these criticalities (the first fact of the order)."""
    found = tuple(
        incident(n, 1.0, drive=name, facts={"criticality": c})
        for n, c in enumerate(criticalities, start=1)
    )
    return dataclasses.replace(
        report(1), log=Path(f"{name}.mcap"), drive_hash=name * 64, incidents=found
    )


class _Link:
    def __init__(self, drive: str, log: list[tuple[str, str]]) -> None:
        self.drive = drive
        self.log = log

    def show(self, incident: Incident) -> None:
        self.log.append((self.drive, incident.id))

    def mark(self, incident: Incident, verdict: str | None) -> None:
        self.log.append((self.drive, f"{incident.id}={verdict}"))


async def _review(app: ReviewApp, keys: list[str]) -> None:
    async with app.run_test() as pilot:
        for key in keys:
            await pilot.press(key)
        await pilot.pause()


def test_one_queue_interleaves_drives_worst_first_and_opens_each_when_due(
    tmp_path: Path,
) -> None:
    a, b = _drive("a", [5.0, 3.0, 1.0]), _drive("b", [4.0, 2.0])
    opened: list[str] = []
    shown: list[tuple[str, str]] = []

    @contextlib.contextmanager
    def open_drive(session: ReviewSession) -> Iterator[_Link]:
        opened.append(session.report.drive_hash[0])
        yield _Link(session.report.drive_hash[0], shown)

    with LabelStore(tmp_path / "l.sqlite") as store:
        fleet = FleetSession([ReviewSession(r, store, "ann", by_event=False) for r in (a, b)])
        order = [i.id for i in fleet.incidents]
        assert order == [a.incidents[0].id, b.incidents[0].id, a.incidents[1].id,
                         b.incidents[1].id, a.incidents[2].id]  # fmt: skip
        viewer = FleetViewer(fleet, open_drive)
        asyncio.run(_review(ReviewApp(fleet, viewer), ["c", "c", "f", "c", "c", "z", "q"]))
        viewer.close()
        labels_a, labels_b = store.labels(a.drive_hash), store.labels(b.drive_hash)
    assert {k: v.verdict for k, v in labels_a.items()} == {
        a.incidents[0].id: "confirmed",
        a.incidents[1].id: "false_positive",
    }  # the last confirmation (a's third) was undone
    assert {k: v.verdict for k, v in labels_b.items()} == dict.fromkeys(
        (i.id for i in b.incidents), "confirmed"
    )
    views = [(d, i) for d, i in shown if "=" not in i]
    walked = [i for k, (_, i) in enumerate(views) if k == 0 or views[k - 1][1] != i]
    assert walked[:5] == order
    assert all(i.endswith(d) for d, i in views)  # each row shown in its own drive's viewer
    drives = [d for k, (d, _) in enumerate(views) if k == 0 or views[k - 1][0] != d]
    assert opened == drives  # a drive opened each time the cursor came to it, only then
    assert opened[:5] == ["a", "b", "a", "b", "a"]


def test_a_fleet_session_resumes_at_the_worst_unlabelled_row(tmp_path: Path) -> None:
    a, b = _drive("a", [5.0, 1.0]), _drive("b", [4.0])
    with LabelStore(tmp_path / "l.sqlite") as store:
        store.put(a.drive_hash, a.incidents[0].id, "confirmed")
        fleet = FleetSession([ReviewSession(r, store, "ann") for r in (a, b)])
        assert fleet.current is b.incidents[0]
        assert fleet.reviewed == 1
        assert fleet.session_of(b.incidents[0]).report is b
