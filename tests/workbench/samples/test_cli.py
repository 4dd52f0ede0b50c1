"""``workbench samples`` writes the requested scenarios and rejects unknown names."""

from __future__ import annotations

from typer.testing import CliRunner

from workbench.cli.main import app


def test_samples_command_writes_one_scenario(tmp_path):
    result = CliRunner().invoke(app, ["samples", str(tmp_path), "-s", "hard_braking_lead"])
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [
        "hard_braking_lead.bag",
        "hard_braking_lead.mcap",
        "hard_braking_lead.osm",
        "hard_braking_lead_rosbag2",
    ]


def test_samples_command_rejects_unknown_scenario(tmp_path):
    result = CliRunner().invoke(app, ["samples", str(tmp_path), "-s", "nope"])
    assert result.exit_code != 0
    assert not any(tmp_path.iterdir())
