import csv
import json

import pytest

from workbench.engines.base import VerdictSummary
from workbench.errors import WorkbenchError
from workbench.incidents import IncidentDetector
from workbench.sinks.violations import VIOLATION_ID_PREFIX, detect_violations, write_violations


def _results(
    pattern: str, engine: str = "reachsets"
) -> list[tuple[int, int, dict[str, VerdictSummary]]]:
    """One frame per character: '.' safe, 'x' unsafe with culprit 'a' and margin = frame."""
    out = []
    for i, ch in enumerate(pattern):
        unsafe = ch == "x"
        outputs = {
            engine: VerdictSummary(
                is_safe=not unsafe,
                culprits=(f"obj{i % 2}",) if unsafe else (),
                cause="collision" if unsafe else "",
                margin=float(10 - i) if unsafe else float("inf"),
            )
        }
        out.append((i, 1_000 + 100 * i, outputs))
    return out


def test_consecutive_unsafe_frames_merge_into_intervals():
    found = detect_violations(_results("..xxx..x."), "drive.mcap")
    assert [(v.start_frame, v.end_frame) for v in found] == [(2, 4), (7, 7)]
    first = found[0]
    assert first.objects == ["obj0", "obj1"]
    assert first.start_ns == 1_200
    assert first.end_ns == 1_400
    assert first.worst_margin == 6.0
    assert first.frames == 3
    assert first.labels == ["collision"]


def test_interval_open_at_the_end_is_kept_and_ids_are_stable():
    a = detect_violations(_results("..xx"), "drive.mcap")
    b = detect_violations(_results("..xx"), "drive.mcap")
    other_log = detect_violations(_results("..xx"), "other.mcap")
    assert [(v.start_frame, v.end_frame) for v in a] == [(2, 3)]
    assert a[0].id == b[0].id
    assert a[0].id != other_log[0].id
    assert a[0].id.startswith("viol-reachsets-000002-")


def test_violation_and_incident_ids_are_told_apart():
    (violation,) = detect_violations(_results("..xx"), "drive.mcap")
    detector = IncidentDetector("drive-hash")
    for frame, t_ns, verdicts in _results("..xx"):
        detector.add(frame, t_ns, verdicts)
    incidents = detector.incidents()
    assert incidents
    assert all(not i.id.startswith(VIOLATION_ID_PREFIX) for i in incidents)
    assert violation.id.startswith(VIOLATION_ID_PREFIX)
    assert violation.id.removeprefix(VIOLATION_ID_PREFIX) not in {i.id for i in incidents}


def test_all_safe_gives_no_violation():
    assert detect_violations(_results("....."), "drive.mcap") == []


def test_violations_written_as_json_and_csv(tmp_path):
    found = detect_violations(_results(".xx.x"), "drive.mcap")
    write_violations(found, tmp_path / "v.json")
    rows = json.loads((tmp_path / "v.json").read_text())
    assert [r["start_frame"] for r in rows] == [1, 4]
    write_violations(found, tmp_path / "v.csv")
    with (tmp_path / "v.csv").open() as fh:
        csv_rows = list(csv.DictReader(fh))
    assert [r["id"] for r in csv_rows] == [r["id"] for r in rows]
    assert not list(tmp_path.glob(".*.tmp"))
    assert not list(tmp_path.glob("*.part"))


def test_unknown_suffix_is_a_clear_error(tmp_path):
    with pytest.raises(WorkbenchError, match=r"\.json or \.csv"):
        write_violations([], tmp_path / "v.parquet")
