import json
from pathlib import Path

import pytest

from tests.workbench.cli_runs import run_workbench as _run
from workbench.annotations import LabelStore
from workbench.incidents import drive_content_hash

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = SAMPLES / "hard_braking_lead.mcap"
ENGINES = ["--engines", "rss"]


@pytest.fixture
def incident_ids(tmp_path) -> list[str]:
    out = tmp_path / "i.json"
    assert _run(["incidents", str(LOG), *ENGINES, "--out", str(out)]) == 0
    return [row["id"] for row in json.loads(out.read_text())]


def test_label_writes_the_store_and_keeps_tags_and_note_when_not_given(tmp_path, incident_ids):
    store = tmp_path / "labels.sqlite"
    first = incident_ids[0]
    args = ["label", str(LOG), first, *ENGINES, "--store", str(store)]
    assert (
        _run(
            [
                *args,
                "--verdict",
                "follow_up",
                "--tag",
                "cut-in",
                "--tag",
                "night",
                "--note",
                "check the lead",
                "--reviewer",
                "ann",
            ]
        )
        == 0
    )
    assert _run([*args, "--verdict", "confirmed", "--reviewer", "bob"]) == 0
    with LabelStore(store) as labels:
        found = labels.labels(drive_content_hash(LOG))
    assert list(found) == [first]
    label = found[first]
    assert (label.verdict, label.tags, label.note, label.reviewer) == (
        "confirmed",
        ("cut-in", "night"),
        "check the lead",
        "bob",
    )
    assert label.settings["engines"] == ["rss"]
    assert label.settings["merge_gap_s"] == 0.0


def test_unknown_incident_and_corrupt_store_are_one_line_errors(tmp_path, incident_ids, capsys):
    store = tmp_path / "labels.sqlite"
    code = _run(
        ["label", str(LOG), "rss-bogus", *ENGINES, "--verdict", "confirmed", "--store", str(store)]
    )
    assert code == 2
    store.write_bytes(b"\0garbage" * 512)
    code = _run(
        [
            "label",
            str(LOG),
            incident_ids[0],
            *ENGINES,
            "--verdict",
            "confirmed",
            "--store",
            str(store),
        ]
    )
    assert code == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.startswith("error:")]
    assert len(lines) == 2
    assert "no incident 'rss-bogus'" in lines[0]
    assert "not a readable label store" in lines[1]
    assert "Traceback" not in err
