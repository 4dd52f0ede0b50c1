import csv
import json

import pyarrow.parquet as pq
import pytest

from workbench.errors import WorkbenchError
from workbench.incidents import Incident, Severity, filter_incidents, write_incidents


def _incident(n: int, engine: str = "rss", obj: str = "a", margin: float = 0.0) -> Incident:
    return Incident(
        id=f"{engine}-{n:06d}-x",
        engine=engine,
        objects=(obj,),
        cause="RSS BrakeMin" if engine == "rss" else "reach-set collision",
        start_frame=n,
        end_frame=n + 2,
        start_ns=1_000 + n,
        end_ns=1_200 + n,
        severity=Severity(margin, 3, 2e-7, {"extra": "fact"} if n == 1 else {}),
    )


INCIDENTS = [_incident(1), _incident(2, "reachsets", "b", 0.8), _incident(3, obj="c")]


def test_filters_combine_and_keep_the_order():
    assert filter_incidents(INCIDENTS) == INCIDENTS
    assert [i.start_frame for i in filter_incidents(INCIDENTS, engines=["rss"])] == [1, 3]
    assert [i.start_frame for i in filter_incidents(INCIDENTS, objects=["b", "c"])] == [2, 3]
    assert [i.start_frame for i in filter_incidents(INCIDENTS, causes=["brakemin"])] == [1, 3]
    assert [i.start_frame for i in filter_incidents(INCIDENTS, max_margin=0.5)] == [1, 3]
    assert filter_incidents(INCIDENTS, engines=["rss"], objects=["b"]) == []


def test_json_csv_and_parquet_hold_the_same_rows(tmp_path):
    for suffix in ("json", "csv", "parquet"):
        write_incidents(INCIDENTS, tmp_path / f"i.{suffix}")
    rows = json.loads((tmp_path / "i.json").read_text())
    assert [r["id"] for r in rows] == [i.id for i in INCIDENTS]
    rank = rows[0]["severity"].pop("severity_rank")
    assert rows[0]["severity"] == {
        "worst_margin": 0.0,
        "unsafe_frames": 3,
        "duration_s": 2e-7,
        "extra": "fact",
    }
    assert rank["criticality"] == 0.0  # no physical facts: never on a collision course
    assert rank["gap_min_m"] is None
    assert rows[0]["data_suspect"] == []
    with (tmp_path / "i.csv").open() as fh:
        csv_rows = list(csv.DictReader(fh))
    assert [r["id"] for r in csv_rows] == [r["id"] for r in rows]
    assert [r["objects"] for r in csv_rows] == ["a", "b", "c"]
    assert [r["severity.extra"] for r in csv_rows] == ["fact", "", ""]
    assert [r["severity.severity_rank.criticality"] for r in csv_rows] == ["0.0"] * 3
    table = pq.read_table(tmp_path / "i.parquet").to_pylist()
    assert [r["id"] for r in table] == [r["id"] for r in rows]
    assert [r["objects"] for r in table] == [["a"], ["b"], ["c"]]
    assert [r["start_ns"] for r in table] == [r["start_ns"] for r in rows]
    assert [r["severity.worst_margin"] for r in table] == [0.0, 0.8, 0.0]
    assert not list(tmp_path.glob(".*.tmp"))


def test_empty_outputs_are_valid(tmp_path):
    for suffix in ("json", "csv", "parquet"):
        write_incidents([], tmp_path / f"e.{suffix}")
    assert json.loads((tmp_path / "e.json").read_text()) == []
    assert pq.read_table(tmp_path / "e.parquet").num_rows == 0


def test_unknown_suffix_is_a_clear_error(tmp_path):
    with pytest.raises(WorkbenchError, match=r"\.json, \.csv, \.parquet"):
        write_incidents(INCIDENTS, tmp_path / "i.txt")
