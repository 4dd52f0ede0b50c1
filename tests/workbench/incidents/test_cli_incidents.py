import json
from pathlib import Path

from tests.workbench.cli_runs import run_workbench as _run

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = SAMPLES / "hard_braking_lead.mcap"


def test_incidents_cover_exactly_the_unsafe_frames_of_evaluate(tmp_path, capsys):
    per_frame = tmp_path / "frames.jsonl"
    args = ["--engines", "rss,reachsets", "--reach-method", "simple"]
    assert _run(["evaluate", str(LOG), *args, "--per-frame", str(per_frame)]) == 0
    out = tmp_path / "incidents.json"
    assert _run(["incidents", str(LOG), *args, "--out", str(out)]) == 0
    lines = [json.loads(line) for line in per_frame.read_text().splitlines()]
    rows = json.loads(out.read_text())
    assert rows
    for engine in ("rss", "reachsets"):
        unsafe = {line["frame"] for line in lines if not line[engine]["is_safe"]}
        covered = {
            f
            for r in rows
            if r["engine"] == engine
            for f in range(r["start_frame"], r["end_frame"] + 1)
        }
        assert covered == unsafe, engine
    times = {line["frame"]: line["t_ns"] for line in lines}
    for row in rows:
        assert (row["start_ns"], row["end_ns"]) == (
            times[row["start_frame"]],
            times[row["end_frame"]],
        )
    # events in the documented order (docs/review.md): by their first (most severe) incident;
    # margins of different engines are not compared
    leads = [r for k, r in enumerate(rows) if k == 0 or rows[k - 1]["event"] != r["event"]]
    ranks = [r["severity"]["severity_rank"] for r in leads]
    keys = [(k["suspect"], -k["criticality"]) for k in ranks]
    assert keys == sorted(keys)
    again = tmp_path / "again.json"
    assert _run(["incidents", str(LOG), *args, "--out", str(again)]) == 0
    assert json.loads(again.read_text()) == rows
    assert "incident(s), worst first" in capsys.readouterr().out


def test_filters_and_bad_input_are_one_line(tmp_path, capsys):
    out = tmp_path / "i.json"
    code = _run(
        ["incidents", str(LOG), "--engines", "rss", "--engine", "reachsets", "--out", str(out)]
    )
    assert code == 0
    assert json.loads(out.read_text()) == []
    assert _run(["incidents", str(tmp_path / "missing.mcap")]) == 2
    assert _run(["incidents", str(LOG), "--engines", "rss", "--out", str(tmp_path / "x.txt")]) == 2
    err = capsys.readouterr().err
    assert "no such file" in err
    assert ".parquet" in err
    assert "Traceback" not in err
