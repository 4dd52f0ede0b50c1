"""Stored labels and incidents: labels of split RSS incidents attach to the per-object incident;
labels made under other settings are named by the commands that read labels, never dropped."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from tests.workbench.cli_runs import run_workbench
from workbench.annotations import LabelStore
from workbench.annotations.attach import elsewhere_note, labels_for
from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, drive_content_hash, find_incidents
from workbench.review import ReviewSession

if TYPE_CHECKING:
    import pytest

LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"

#: The reference profile flags hard_braking_lead's car-following early; ``auto`` (highway)
#: only the lead's hard braking: the first profile's incidents are not all the second's.
REFERENCE = ["--engines", "rss", "--rss-profile", "adrss-5.0"]
REVIEW = ["--engines", "rss"]


def _ids(tmp_path: Path, options: list[str]) -> list[str]:
    out = tmp_path / "ids.json"
    assert run_workbench(["incidents", str(LOG), *options, "--out", str(out)]) == 0
    return [row["id"] for row in json.loads(out.read_text())]


def test_labels_of_other_settings_are_named_and_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    store = tmp_path / "labels.sqlite"
    reference, review = _ids(tmp_path, REFERENCE), _ids(tmp_path, REVIEW)
    away = [i for i in reference if i not in review]
    assert away
    for incident_id in reference:
        label = ["label", str(LOG), incident_id, *REFERENCE, "--verdict", "confirmed"]
        assert run_workbench([*label, "--store", str(store)]) == 0
    capsys.readouterr()
    doc = tmp_path / "doc.json"
    export = ["labels", "export", str(LOG), *REVIEW, "--store", str(store), "--out", str(doc)]
    assert run_workbench(export) == 0
    err = capsys.readouterr().err
    assert f"{len(away)} label(s) of this drive are for incidents these settings do not" in err
    assert "rss_profile adrss-5.0 (now auto)" in err
    # nothing is deleted: every label is still in the store
    with LabelStore(store) as labels:
        assert set(labels.labels(drive_content_hash(LOG))) == set(reference)
    # under the settings they were made with, the note is silent
    assert run_workbench([*export[:3], *REFERENCE, *export[5:]]) == 0
    assert "label(s) of this drive" not in capsys.readouterr().err


def test_a_label_of_an_incident_split_by_cause_attaches_to_the_per_object_incident(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Labels written when RSS split an object's run at every change of cause still count."""
    log = LOG.with_name("urban_intersection.mcap")
    # adrss-5.0: the reference's junction verdicts change cause inside one run (auto: urban)
    rep = find_incidents(
        IncidentRequest(log, ("rss",), options=engine_options({"rss_profile": "adrss-5.0"}))
    )
    merged = next(i for i in rep.incidents if len(i.legacy_ids) > 1)
    older, newer = merged.legacy_ids[:2]
    assert merged.id not in (older, newer)
    store = tmp_path / "labels.sqlite"
    with LabelStore(store) as labels:
        labels.put(rep.drive_hash, older, "confirmed", note="first piece", at_ns=1)
        labels.put(rep.drive_hash, newer, "false_positive", note="second piece", at_ns=2)
        stored = labels.labels(rep.drive_hash)
        attached = labels_for(rep, stored)
        # the latest of its pieces' labels, and no "other settings" note
        assert attached[merged.id].note == "second piece"
        assert elsewhere_note(rep, stored) is None
        session = ReviewSession(rep, labels, "ann")
        assert session.labels[merged.id].verdict == "false_positive"
        # a verdict given now is stored under the incident's own id and wins
        session.index = rep.incidents.index(merged)
        session.give("confirmed")
        assert labels_for(rep, labels.labels(rep.drive_hash))[merged.id].verdict == "confirmed"
        # undone, the piece's label is back
        assert session.undo() is merged
        assert session.labels[merged.id].note == "second piece"
    doc = tmp_path / "doc.json"
    export = ["labels", "export", str(log), "--engines", "rss", "--store", str(store)]
    export += ["--rss-profile", "adrss-5.0"]
    assert run_workbench([*export, "--out", str(doc)]) == 0
    assert "label(s) of this drive" not in capsys.readouterr().err
    action = next(
        a
        for a in json.loads(doc.read_text())["openlabel"]["actions"].values()
        if a["name"] == merged.id
    )
    assert {"name": "verdict", "val": "false_positive"} in action["action_data"]["text"]
