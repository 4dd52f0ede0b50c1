"""The review UI driven by textual's Pilot."""

import asyncio

from textual.widgets import DataTable

from tests.workbench.review.helpers import report
from workbench.annotations import LabelStore
from workbench.review import ReviewSession
from workbench.review.app import ReviewApp


class _Viewer:
    def __init__(self) -> None:
        self.shown: list[str] = []
        self.marked: list[tuple[str, str | None]] = []

    def show(self, incident):
        self.shown.append(incident.id)

    def mark(self, incident, verdict):
        self.marked.append((incident.id, verdict))


async def _review(app: ReviewApp, keys: list[str]) -> None:
    async with app.run_test() as pilot:
        for key in keys:
            await pilot.press(key)
        await pilot.pause()


def test_keys_record_verdicts_tags_notes_and_undo(tmp_path):
    rep = report(3)
    ids = [i.id for i in rep.incidents]
    viewer = _Viewer()
    with LabelStore(tmp_path / "l.sqlite") as store:
        app = ReviewApp(ReviewSession(rep, store, "ann"), viewer)
        keys = ["t", *"cut-in", "enter", "c", "f", "n", *"check", "enter", "u", "z", "k", "q"]
        asyncio.run(_review(app, keys))
        labels = store.labels(rep.drive_hash)
    # c on the first, f on the second, note typed on the third, u then undone
    assert {k: (v.verdict, v.tags, v.reviewer) for k, v in labels.items()} == {
        ids[0]: ("confirmed", ("cut-in",), "ann"),
        ids[1]: ("false_positive", (), "ann"),
    }
    assert viewer.shown[0] == ids[0]
    assert ids[2] in viewer.shown
    assert (ids[2], "follow_up") in viewer.marked
    assert viewer.marked[-1] == (ids[2], None)


def test_resumes_at_the_first_unlabelled_incident(tmp_path):
    rep = report(3)
    with LabelStore(tmp_path / "l.sqlite") as store:
        store.put(rep.drive_hash, rep.incidents[0].id, "confirmed")
        app = ReviewApp(ReviewSession(rep, store, "ann"))

        async def run() -> int:
            async with app.run_test() as pilot:
                await pilot.pause()
                row = app.query_one(DataTable).cursor_row
                await pilot.press("q")
            return row

        assert asyncio.run(run()) == 1
