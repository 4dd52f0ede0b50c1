from tests.workbench.review.helpers import report
from workbench.annotations import LabelStore
from workbench.review import ReviewSession


def test_verdicts_tags_notes_undo_and_resume(tmp_path):
    rep = report(3)
    ids = [i.id for i in rep.incidents]
    with LabelStore(tmp_path / "l.sqlite") as store:
        session = ReviewSession(rep, store, "ann")
        assert session.index == 0
        session.add_tag("cut-in")
        session.set_note("late")
        assert store.labels(rep.drive_hash) == {}  # nothing without a verdict
        session.give("confirmed")
        session.move(1)
        session.give("follow_up")
        session.add_tag("night")
        labels = store.labels(rep.drive_hash)
        assert {k: (v.verdict, v.tags, v.note) for k, v in labels.items()} == {
            ids[0]: ("confirmed", ("cut-in",), "late"),
            ids[1]: ("follow_up", ("night",), ""),
        }
        assert session.undo() is rep.incidents[1]
        restored = store.label(rep.drive_hash, ids[1])
        assert restored is not None
        assert restored.tags == ()
        assert session.undo() is rep.incidents[1]
        assert store.label(rep.drive_hash, ids[1]) is None
        assert session.reviewed == 1
    with LabelStore(tmp_path / "l.sqlite") as store:
        again = ReviewSession(rep, store, "bob")
        assert again.index == 1  # the first unlabelled, worst first
        assert again.undo() is None  # another session's writes are not undone
        again.move(5)
        assert again.index == 2
        again.move(-9)
        assert again.index == 0
