"""Incidents resting on implausible data: ``data_suspect``, never dropped; the output files."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pyarrow.parquet as pq

from tests.workbench.cli_runs import run_workbench
from tests.workbench.quality.test_real import PEACH
from workbench.incidents import Incident, IncidentRequest, Severity, find_incidents
from workbench.quality import EGO_ID, Finding, Kind
from workbench.quality.output import quality_path, write_quality
from workbench.quality.suspect import flag_suspects

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"


def _incident(obj: str, start: int, end: int) -> Incident:
    return Incident(
        id=f"rss-{start:06d}-{obj}",
        engine="rss",
        objects=(obj,),
        cause="RSS lon BrakeMin",
        start_frame=start,
        end_frame=end,
        start_ns=start * 100,
        end_ns=end * 100,
        severity=Severity(0.0, end - start + 1, (end - start) * 1e-7),
    )


def _finding(obj: str, kind: Kind, start: int, end: int, *, value: float, bound: float) -> Finding:
    return Finding(obj, kind, start, end, start * 100, end * 100, end - start + 1, value, bound)


FINDINGS = (
    _finding(EGO_ID, Kind.ACCEL, 24, 27, value=-18.0, bound=-10.0),
    _finding(EGO_ID, Kind.ACCEL, 40, 40, value=-12.0, bound=-10.0),
    _finding("a", Kind.TELEPORT, 5, 6, value=9.0, bound=3.0),
    _finding("b", Kind.SPEED_MISMATCH, 10, 12, value=3.0, bound=2.0),
)


def test_overlapping_findings_of_its_objects_or_the_ego_make_an_incident_suspect():
    incidents = [
        _incident("a", 0, 10),  # its own teleport
        _incident("a", 20, 30),  # the ego's deceleration 24-27
        _incident("b", 13, 20),  # b's mismatch ends at 12, nothing overlaps
        _incident("c", 5, 12),  # b's mismatch is not c's
        _incident("c", 26, 45),  # two ego runs: the worst one is the reason
    ]
    flagged = flag_suspects(incidents, FINDINGS)
    assert [i.id for i in flagged] == [i.id for i in incidents]  # none dropped, order kept
    reasons = [i.data_suspect for i in flagged]
    assert reasons[0] == ("a teleport 9.00 beyond 3.00 m (frames 5-6)",)
    assert reasons[1] == ("ego accel -18.00 beyond -10.00 m/s² (frames 24-27)",)
    assert reasons[2] == ()
    assert reasons[3] == ()
    assert reasons[4] == ("ego accel -18.00 beyond -10.00 m/s² (frames 24-27)",)


def test_the_output_files_hold_counts_findings_and_suspect_incidents(tmp_path):
    incidents = flag_suspects([_incident("a", 0, 10), _incident("c", 13, 20)], FINDINGS)
    for suffix in ("json", "csv", "parquet"):
        written = write_quality(FINDINGS, incidents, tmp_path / f"inc.{suffix}")
        assert written == quality_path(tmp_path / f"inc.{suffix}")
        assert written.name == f"inc.data_quality.{suffix}"
    record = json.loads((tmp_path / "inc.data_quality.json").read_text())
    assert record["counts"]["accel"] == 2
    assert record["counts"]["teleport"] == 1
    assert record["counts"]["id_jump"] == 0
    assert record["objects"] == ["a", "b", EGO_ID]
    assert record["suspect"] == {"rss-000000-a": ["a teleport 9.00 beyond 3.00 m (frames 5-6)"]}
    with (tmp_path / "inc.data_quality.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert [r["kind"] for r in rows] == [str(f.kind) for f in FINDINGS]
    assert rows[2]["suspect_incidents"] == "rss-000000-a"
    table = pq.read_table(tmp_path / "inc.data_quality.parquet").to_pylist()
    assert [r["suspect_incidents"] for r in table] == [[], [], ["rss-000000-a"], []]
    assert table[0]["value"] == -18.0


def test_peach_incidents_resting_on_the_ego_trace_are_suspect(external_dir):
    report = find_incidents(IncidentRequest(external_dir / PEACH, ("rss",)))
    assert report.incidents
    ego = [f for f in report.findings if f.object_id == EGO_ID]
    assert any(f.kind == Kind.SPEED_MISMATCH and f.start_frame <= 22 <= f.end_frame for f in ego)
    for incident in report.incidents:
        overlaps = any(
            f.start_frame <= incident.end_frame and incident.start_frame <= f.end_frame for f in ego
        )
        ego_reasons = [r for r in incident.data_suspect if r.startswith(f"{EGO_ID} ")]
        assert bool(ego_reasons) == overlaps, incident.id


def test_incidents_out_writes_the_data_quality_beside_it(tmp_path):
    out = tmp_path / "inc.csv"
    code = run_workbench(
        [
            "incidents",
            str(SAMPLES / "hard_braking_lead.mcap"),
            "--engines",
            "rss",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    with quality_path(out).open() as fh:
        reader = csv.DictReader(fh)
        assert reader.fieldnames is not None
        assert "suspect_incidents" in reader.fieldnames
        assert list(reader) == []  # the sample's data is clean
