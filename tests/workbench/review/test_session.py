from tests.workbench.review.helpers import report
from workbench.annotations import LabelStore
from workbench.incidents import IncidentReport
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


def _overlapping_report() -> IncidentReport:
    import dataclasses  # noqa: PLC0415

    from tests.workbench.review.helpers import incident  # noqa: PLC0415

    rss = incident(1, 0.0)
    reach = dataclasses.replace(rss, id="reachsets-000010-abc", engine="reachsets")
    return dataclasses.replace(report(3), incidents=(rss, reach, *report(3).incidents[1:]))


def test_a_verdict_on_an_event_labels_each_of_its_incidents(tmp_path):
    rep = _overlapping_report()
    with LabelStore(tmp_path / "l.sqlite") as store:
        session = ReviewSession(rep, store, "ann")
        assert len(session.incidents) == 3  # rss + reachsets on object 1 are one event
        event_incidents = {i.id for i in session.members(session.incidents[0])}
        assert event_incidents == {rep.incidents[0].id, rep.incidents[1].id}
        shown = session.evidence(session.incidents[0])  # every engine's evidence is shown
        assert shown[0].startswith("event event-000010-")
        other = ({rep.incidents[0].id, rep.incidents[1].id} - {session.incidents[0].id}).pop()
        assert other in shown[1]
        session.add_tag("cut-in")
        session.give("confirmed")
        labels = store.labels(rep.drive_hash)
        assert {k: (v.verdict, v.tags) for k, v in labels.items()} == dict.fromkeys(
            event_incidents, ("confirmed", ("cut-in",))
        )
        assert session.reviewed == 1
        assert session.undo() is session.incidents[0]
        assert store.labels(rep.drive_hash) == {}  # one undo takes back the whole event
        session.give("false_positive")
    with LabelStore(tmp_path / "l.sqlite") as store:
        again = ReviewSession(rep, store, "bob")
        assert again.index == 1  # the event is done; resume at the next
        one_by_one = ReviewSession(rep, store, "bob", by_event=False)
        assert [i.id for i in one_by_one.incidents] == [i.id for i in rep.incidents]
        assert one_by_one.index == 2
