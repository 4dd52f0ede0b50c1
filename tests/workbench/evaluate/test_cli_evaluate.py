import itertools
import json
from pathlib import Path

import pytest

from tests.workbench.cli_runs import run_workbench as _run

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"


def test_evaluate_writes_pinned_per_frame_records(tmp_path, capsys):
    per_frame = tmp_path / "frames.jsonl"
    viol = tmp_path / "viol.json"
    log = SAMPLES / "hard_braking_lead.mcap"
    code = _run(
        [
            "evaluate",
            str(log),
            "--engines",
            "reachsets",
            "--reach-method",
            "simple",
            "--per-frame",
            str(per_frame),
            "--violations",
            str(viol),
            "--end",
            "3",
        ]
    )
    assert code == 0
    lines = [json.loads(line) for line in per_frame.read_text().splitlines()]
    assert lines, "no frames evaluated"
    assert [line["frame"] for line in lines] == list(range(len(lines)))
    assert all(a["t_ns"] < b["t_ns"] for a, b in itertools.pairwise(lines))
    for line in lines:
        assert set(line) == {"t_ns", "frame", "reachsets"}
        reach = line["reachsets"]
        assert isinstance(reach["is_safe"], bool)
        assert reach["is_safe"] == (not reach["collisions"])
        for hit in reach["collisions"]:
            assert set(hit) == {"object_id", "t_offset_s"}
            assert 0.0 <= hit["t_offset_s"] <= 4.0
    rows = json.loads(viol.read_text())
    unsafe_frames = {line["frame"] for line in lines if not line["reachsets"]["is_safe"]}
    covered = {f for r in rows for f in range(r["start_frame"], r["end_frame"] + 1)}
    assert covered == unsafe_frames
    assert f"{len(lines)} frames evaluated" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("engines", "message"),
    [("bogus", "unknown engine 'bogus'"), (",", "at least one")],
)
def test_bad_engine_choice_is_one_line_error(engines, message, capsys):
    code = _run(["evaluate", str(SAMPLES / "hard_braking_lead.mcap"), "--engines", engines])
    assert code == 2
    err = capsys.readouterr().err
    assert message in err
    assert "Traceback" not in err


def test_truncated_log_keeps_every_evaluated_frame(tmp_path, capsys):
    log = tmp_path / "cut.mcap"
    data = (SAMPLES / "hard_braking_lead.mcap").read_bytes()
    log.write_bytes(data[: len(data) // 2])
    per_frame = tmp_path / "frames.jsonl"
    viol = tmp_path / "viol.json"
    code = _run(["evaluate", str(log), "--per-frame", str(per_frame), "--violations", str(viol)])
    assert code == 2
    captured = capsys.readouterr()
    assert "truncated or corrupted" in captured.err
    assert str(log) in captured.err
    lines = per_frame.read_text().splitlines()
    assert len(lines) > 10
    assert f"cover the {len(lines)} readable frames" in captured.out
    assert json.loads(viol.read_text()) is not None
    assert not list(tmp_path.glob(".*.tmp"))
    assert not list(tmp_path.glob("*.part"))


def _unsafe_frames(tmp_path, name: str, extra: list[str]) -> int:
    per_frame = tmp_path / f"{name}.jsonl"
    log = SAMPLES / "hard_braking_lead.mcap"
    args = ["evaluate", str(log), "--engines", "rss", "--per-frame", str(per_frame), *extra]
    assert _run(args) == 0
    lines = [json.loads(line) for line in per_frame.read_text().splitlines()]
    return sum(1 for line in lines if not line["rss"]["is_safe"])


def test_rss_params_file_changes_the_dynamics(tmp_path):
    cautious = tmp_path / "cautious.toml"
    cautious.write_text("[ego]\nresponse_time = 2.0\n\n[vehicle]\nresponse_time = 2.0\n")
    default = _unsafe_frames(tmp_path, "default", [])
    slow = _unsafe_frames(tmp_path, "slow", ["--rss-params", str(cautious)])
    assert slow > default


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[car]\nbrake_min = 4\n", "brakes are negative"),
        ("[ego\n", "TOML"),
        ("[scene]\nreproduce_adrss_5_0_defects = 'yes'\n", "must be true or false"),
    ],
)
def test_bad_rss_params_are_one_line_errors(tmp_path, capsys, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    log = str(SAMPLES / "hard_braking_lead.mcap")
    assert _run(["evaluate", log, "--engines", "rss", "--rss-params", str(path)]) == 2
    err = capsys.readouterr().err
    assert message in err
    assert "Traceback" not in err


def test_missing_rss_params_file_is_named(tmp_path, capsys):
    missing = tmp_path / "nope.toml"
    log = str(SAMPLES / "hard_braking_lead.mcap")
    assert _run(["evaluate", log, "--engines", "rss", "--rss-params", str(missing)]) == 2
    assert str(missing) in capsys.readouterr().err


def test_evaluate_ego_topic_chooses_the_ego(tmp_path):
    """``--ego-topic /tf`` reads the sample's pose-only /tf ego: same frames and verdicts."""
    log = SAMPLES / "highway_cut_in.mcap"
    outputs = []
    for extra in ([], ["--ego-topic", "/tf"]):
        per_frame = tmp_path / f"frames{len(extra)}.jsonl"
        args = ["evaluate", str(log), "--engines", "rss", "--per-frame", str(per_frame)]
        assert _run([*args, "--end", "8", *extra]) == 0
        outputs.append([json.loads(line) for line in per_frame.read_text().splitlines()])
    odometry, tf = outputs
    assert len(odometry) == len(tf) == 160
    assert [r["rss"]["is_safe"] for r in tf] == [r["rss"]["is_safe"] for r in odometry]
    assert _run(["evaluate", str(log), "--engines", "rss", "--ego-topic", "/nope"]) == 2
