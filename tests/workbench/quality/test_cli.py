"""``workbench info --quality``: the findings per object and kind."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from tests.workbench.quality.test_real import PEACH
from workbench.cli.main import app

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"


def test_info_quality_lists_the_peach_ego(external_dir):
    result = CliRunner().invoke(app, ["info", str(external_dir / PEACH), "--quality"])
    assert result.exit_code == 0, result.output
    rows = [line for line in result.output.splitlines() if "│ ego " in line]
    kinds = {line.split("│")[2].strip() for line in rows}
    assert {"speed_mismatch", "accel"} <= kinds
    mismatch = next(line for line in rows if "speed_mismatch" in line)
    assert "22-22" in mismatch  # frames
    assert "findings per kind: speed_mismatch " in result.output


def test_info_quality_on_a_clean_sample():
    result = CliRunner().invoke(app, ["info", str(SAMPLES / "hard_braking_lead.mcap"), "--quality"])
    assert result.exit_code == 0, result.output
    assert "data quality: 0 finding(s) on 0 of 4 objects" in result.output
    assert "teleport 0, id_jump 0" in result.output


def test_info_without_quality_reads_no_track():
    result = CliRunner().invoke(app, ["info", str(SAMPLES / "hard_braking_lead.mcap")])
    assert result.exit_code == 0, result.output
    assert "data quality" not in result.output
