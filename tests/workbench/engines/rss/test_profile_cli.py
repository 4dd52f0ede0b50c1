"""``--rss-profile`` and ``profile = NAME`` on the commands: shown by info, recorded by evaluate."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.workbench.cli_runs import run_workbench as _run

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"


@pytest.mark.parametrize(
    ("options", "shown"),
    [((), "rss profile auto -> highway:"), (("--rss-profile", "carla"), "rss profile carla:")],
)
def test_info_shows_the_active_profile(options, shown, capsys):
    assert _run(["info", str(SAMPLES / "highway_cut_in.mcap"), *options]) == 0
    assert shown in capsys.readouterr().out


def test_info_shows_urban_and_the_standstill_rule_in_town(capsys):
    assert _run(["info", str(SAMPLES / "urban_intersection.mcap")]) == 0
    out = " ".join(capsys.readouterr().out.split())  # the table wraps long lines
    assert "rss profile auto -> urban:" in out
    assert "b_min -3.4" in out
    assert "standstill rule 0.1 m/s" in out
    assert (
        _run(["info", str(SAMPLES / "urban_intersection.mcap"), "--rss-profile", "adrss-5.0"]) == 0
    )
    assert "standstill rule" not in capsys.readouterr().out


def test_unknown_profile_is_one_line(capsys):
    assert _run(["info", str(SAMPLES / "highway_cut_in.mcap"), "--rss-profile", "x"]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "adrss-5.0" in err[0]


def test_toml_profile_with_overrides_is_recorded(tmp_path):
    params = tmp_path / "params.toml"
    params.write_text('profile = "carla"\n[vehicle]\nresponse_time = 1.5\n')
    per_frame = tmp_path / "frames.jsonl"
    args = ["evaluate", str(SAMPLES / "hard_braking_lead.mcap"), "--engines", "rss"]
    args += ["--end", "1", "--rss-params", str(params), "--per-frame", str(per_frame)]
    assert _run(args) == 0
    lines = [json.loads(line) for line in per_frame.read_text().splitlines()]
    assert {line["rss"]["profile"] for line in lines} == {"carla+file"}
    # a contradicting --rss-profile is refused
    assert _run([*args, "--rss-profile", "highway"]) != 0


def test_replay_records_the_profile_as_a_recording_property(tmp_path):
    from rerun.chunk import RrdReader  # noqa: PLC0415 - only this test reads an .rrd

    out = tmp_path / "drive.rrd"
    args = ["replay", str(SAMPLES / "hard_braking_lead.mcap"), "--engines", "rss"]
    assert _run([*args, "--end", "1", "--rss-profile", "adrss-5.0", "--out", str(out)]) == 0
    store = RrdReader(out).store().stream().collect()
    props = store.reader(index=None, contents="/__properties/**").to_arrow_table().to_pydict()
    assert props["property:rss:profile"] == [["adrss-5.0"]]
