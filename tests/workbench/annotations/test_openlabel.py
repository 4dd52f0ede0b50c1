import json
from pathlib import Path

import jsonschema
import pytest

from tests.workbench.cli_runs import run_workbench as _run
from workbench.annotations import Label, LabelStore, ReviewVerdict
from workbench.annotations.errors import OpenLabelError, TagError
from workbench.annotations.openlabel import export_openlabel, write_openlabel
from workbench.annotations.openlabel_import import Prefer, import_openlabel
from workbench.engines.registry import engine_options
from workbench.incidents import IncidentReport, IncidentRequest, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = SAMPLES / "highway_cut_in.mcap"


@pytest.fixture(scope="module")
def report() -> IncidentReport:
    return find_incidents(
        IncidentRequest(
            LOG, engines=("rss", "reachsets"), options=engine_options({"reach_method": "simple"})
        )
    )


@pytest.fixture
def schema(external_dir):
    path = external_dir / "openlabel" / "openlabel_json_schema-v1.0.0.json"
    return json.loads(path.read_text())


def _labelled_store(path: Path, report: IncidentReport) -> LabelStore:
    store = LabelStore(path)
    first, second = report.incidents[:2]
    store.put(
        report.drive_hash,
        first.id,
        "confirmed",
        tags=["cut-in", "late"],
        note="brake late",
        reviewer="ann",
        settings=report.settings,
        log_name=LOG.name,
        at_ns=1_000,
    )
    store.put(
        report.drive_hash,
        second.id,
        "false_positive",
        tags=["cut-in"],
        reviewer="bob",
        settings=report.settings,
        at_ns=2_000,
    )
    return store


@pytest.mark.external
def test_export_validates_against_the_official_schema(tmp_path, report, schema):
    with _labelled_store(tmp_path / "l.sqlite", report) as store:
        doc = export_openlabel(report, store.labels(report.drive_hash))
    jsonschema.Draft7Validator(schema).validate(doc)
    root = doc["openlabel"]
    assert root["metadata"]["tagged_file"] == LOG.name
    assert [a["name"] for a in root["actions"].values()] == [i.id for i in report.incidents]
    first = root["actions"]["0"]
    texts = {t["name"]: t["val"] for t in first["action_data"]["text"]}
    assert (texts["verdict"], texts["note"], texts["reviewer"]) == (
        "confirmed",
        "brake late",
        "ann",
    )
    assert texts["engine"] == report.incidents[0].engine
    incident = report.incidents[0]
    assert first["frame_intervals"] == [
        {"frame_start": incident.start_frame, "frame_end": incident.end_frame}
    ]
    times = dict(report.frame_times)
    frame = root["frames"][str(incident.start_frame)]
    assert frame["frame_properties"]["t_ns"] == times[incident.start_frame]
    assert "0" in frame["actions"]
    tags = {t["type"]: t["tag_data"]["vec"][0]["val"] for t in root["tags"].values()}
    first_two = [i.id for i in report.incidents[:2]]
    assert tags == {"cut-in": first_two, "late": [first_two[0]]}
    covered = {f for i in report.incidents for f in range(i.start_frame, i.end_frame + 1)}
    assert set(map(int, root["frames"])) == covered


@pytest.mark.external
def test_export_import_export_is_identical_and_import_is_idempotent(tmp_path, report, schema):
    with _labelled_store(tmp_path / "a.sqlite", report) as store:
        write_openlabel(
            export_openlabel(report, store.labels(report.drive_hash)), tmp_path / "1.json"
        )
    with LabelStore(tmp_path / "b.sqlite") as fresh:
        assert import_openlabel(tmp_path / "1.json", fresh).count("added") == 2
        again = import_openlabel(tmp_path / "1.json", fresh)
        assert [o.status for o in again.outcomes] == ["unchanged", "unchanged"]
        write_openlabel(
            export_openlabel(report, fresh.labels(report.drive_hash)), tmp_path / "2.json"
        )
        assert fresh.log_name(report.drive_hash) == LOG.name
    assert (tmp_path / "1.json").read_bytes() == (tmp_path / "2.json").read_bytes()
    jsonschema.Draft7Validator(schema).validate(json.loads((tmp_path / "2.json").read_text()))


def test_cli_export_import_round_trip(tmp_path, capsys):
    args = ["--engines", "rss", "--reach-method", "simple"]
    out = tmp_path / "i.json"
    assert _run(["incidents", str(LOG), *args, "--out", str(out)]) == 0
    first = json.loads(out.read_text())[0]["id"]
    a, b = tmp_path / "a.sqlite", tmp_path / "b.sqlite"
    assert _run(["label", str(LOG), first, *args, "--verdict", "follow_up", "--store", str(a)]) == 0
    assert (
        _run(
            [
                "labels",
                "export",
                str(LOG),
                *args,
                "--out",
                str(tmp_path / "1.json"),
                "--store",
                str(a),
            ]
        )
        == 0
    )
    assert _run(["labels", "import", str(tmp_path / "1.json"), "--store", str(b)]) == 0
    assert (
        _run(
            [
                "labels",
                "export",
                str(LOG),
                *args,
                "--out",
                str(tmp_path / "2.json"),
                "--store",
                str(b),
            ]
        )
        == 0
    )
    assert (tmp_path / "1.json").read_text() == (tmp_path / "2.json").read_text()
    assert "1 label(s) written" in capsys.readouterr().out


def _reviewed(verdict: str, tags: list[str], labelled_ns: str = "1") -> str:
    """A one-incident OpenLABEL file as the workbench writes it, with this label."""
    text = {"engine": "rss", "cause": "c", "verdict": verdict, "note": "", "reviewer": "r"}
    data = {
        "text": [{"name": k, "val": v} for k, v in {**text, "labelled_ns": labelled_ns}.items()],
        "vec": [{"name": "tags", "val": tags}],
    }
    meta = {"schema_version": "1.0.0", "drive_sha256": "d"}
    action = {"name": "x", "type": "t", "action_data": data}
    return json.dumps({"openlabel": {"metadata": meta, "actions": {"0": action}}})


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{not json", "not JSON"),
        ('{"openlabel": {}}', "no openlabel.metadata"),
        ('{"openlabel": {"metadata": {"schema_version": "0.9"}}}', "schema_version '0.9'"),
        ('{"openlabel": {"metadata": {"schema_version": "1.0.0"}}}', "drive_sha256 missing"),
        (
            (
                '{"openlabel": {"metadata": {"schema_version": "1.0.0", "drive_sha256": "d"},'
                ' "actions": {"0": {"name": "x", "type": "t", "action_data":'
                ' {"text": [{"name": "verdict", "val": "confirmed"}]}}}}}'
            ),
            "actions.0.action_data: no 'engine'",
        ),
        (_reviewed("maybe", []), "actions.0.action_data: verdict 'maybe', expected one of"),
        (_reviewed("confirmed", ["two\nlines"]), "actions.0.action_data: tag 'two\\\\nlines'"),
        (  # found by the fuzzer: past what an SQLite INTEGER holds
            _reviewed("confirmed", [], labelled_ns="10700000000000000000"),
            "actions.0.action_data: labelled_ns '10700000000000000000' is not within 0",
        ),
        (_reviewed("confirmed", [], labelled_ns="-5"), "actions.0.action_data: labelled_ns '-5'"),
    ],
)
def test_bad_files_are_one_line_errors(tmp_path, text, message, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text(text)
    with LabelStore(tmp_path / "l.sqlite") as store, pytest.raises(OpenLabelError, match=message):
        import_openlabel(bad, store)
    assert _run(["labels", "import", str(bad), "--store", str(tmp_path / "l.sqlite")]) == 2
    err = capsys.readouterr().err
    assert message.split(":")[0] in err
    assert "Traceback" not in err


def _file_with(tmp_path: Path, report: IncidentReport, verdict: str, at_ns: int) -> Path:
    incident = report.incidents[0]
    label = Label(
        report.drive_hash, incident.id, ReviewVerdict(verdict), ("late",), "n", "ann", at_ns
    )
    path = tmp_path / f"{verdict}-{at_ns}.json"
    write_openlabel(export_openlabel(report, {incident.id: label}), path)
    return path


@pytest.mark.parametrize(
    "case",
    [
        (1_000, Prefer.newer, "replaced", "confirmed"),  # the file's is newer
        (3_000, Prefer.newer, "kept", "false_positive"),  # the store's is newer
        (2_000, Prefer.newer, "conflicting", "false_positive"),  # same time: never replaced
        (3_000, Prefer.import_, "replaced", "confirmed"),
        (1_000, Prefer.store, "kept", "false_positive"),
    ],
)
def test_import_keeps_the_newer_verdict_and_reports_the_conflict(tmp_path, report, case):
    stored_ns, prefer, status, verdict_after = case
    incident = report.incidents[0]
    file = _file_with(tmp_path, report, "confirmed", 2_000)
    with LabelStore(tmp_path / "l.sqlite") as store:
        store.put(report.drive_hash, incident.id, "false_positive", reviewer="bob", at_ns=stored_ns)
        result = import_openlabel(file, store, prefer)
        (outcome,) = result.outcomes
        assert (outcome.incident_id, outcome.status) == (incident.id, status)
        assert outcome.stored is not None
        assert outcome.stored.verdict == "false_positive"
        after = store.label(report.drive_hash, incident.id)
        assert after is not None
        assert after.verdict == verdict_after
        assert result.written == (status == "replaced")
    line = outcome.line()
    assert "false_positive" in line
    assert "confirmed" in line


def test_cli_import_names_each_differing_label(tmp_path, report, capsys):
    incident = report.incidents[0]
    file = _file_with(tmp_path, report, "confirmed", 2_000)
    store = tmp_path / "l.sqlite"
    with LabelStore(store) as labels:
        labels.put(report.drive_hash, incident.id, "follow_up", at_ns=5_000)
    assert _run(["labels", "import", str(file), "--store", str(store)]) == 0
    out = capsys.readouterr().out
    assert f"{incident.id}: kept: store follow_up" in out
    assert "0 label(s) written" in out
    assert _run(["labels", "import", str(file), "--store", str(store), "--prefer", "import"]) == 0
    assert f"{incident.id}: replaced" in capsys.readouterr().out
    with LabelStore(store) as labels:
        after = labels.label(report.drive_hash, incident.id)
    assert after is not None
    assert after.verdict == "confirmed"


@pytest.mark.parametrize("tag", ["", "  ", "two\nlines", "x" * 65])
def test_bad_tags_are_refused(tmp_path, tag):
    with LabelStore(tmp_path / "l.sqlite") as store, pytest.raises(TagError):
        store.put("d", "i", "confirmed", tags=["ok", tag])
