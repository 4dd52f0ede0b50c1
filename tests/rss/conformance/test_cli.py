"""``workbench conformance rss`` prints one JSON line per case / step (lives here because
the command is a thin wrapper of :mod:`rss.conformance`)."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

from typer.testing import CliRunner

from workbench.cli.main import app

if TYPE_CHECKING:
    from pathlib import Path

CASES = {
    "cases": [
        {
            "id": "gap58",
            "kind": "structured",
            "constellation_type": "SameDirection",
            "road": {"length": 1000, "lane_widths": [3.5, 3.5]},
            "ego": {"s": 100, "y": 1.75, "length": 4, "width": 2, "v_lon": 13.888889},
            "other": {"s": 162, "y": 1.75, "length": 4, "width": 2, "v_lon": 13.888889},
            "ego_dynamics": {"response_time": 2.0, "accel_max": 2.0},
        },
        {"id": "u", "kind": "unstructured", "ego": {}, "other": {}},
        {
            "id": "seq",
            "kind": "sequence",
            "steps": [
                {"kind": "formula", "function": "stopping_distance", "speed": 10, "decel": -5}
            ],
        },
    ]
}


def test_conformance_rss_json_lines(tmp_path: Path) -> None:
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(CASES))
    result = CliRunner().invoke(app, ["conformance", "rss", str(path)])
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in result.stdout.splitlines()]
    assert [r["id"] for r in lines] == ["gap58", "u", "seq#0"]
    gap58 = lines[0]
    assert gap58["ok"] is True
    assert gap58["states"][0]["longitudinal"]["safe_distance"] == 59.722994
    assert gap58["proper_response"]["longitudinal_response"] == "BrakeMin"
    assert gap58["proper_response"]["dangerous_objects"] == [1]
    assert lines[1]["ok"] is False
    assert lines[1]["kind"] == "unstructured"
    assert "missing number" in lines[1]["error"]
    assert lines[2]["value"] == 10.0
    assert (lines[2]["sequence_id"], lines[2]["step"]) == ("seq", 0)


def test_conformance_rss_bad_json(tmp_path: Path) -> None:
    path = tmp_path / "bad.json"
    path.write_text("{not json")
    result = CliRunner().invoke(app, ["conformance", "rss", str(path)])
    assert result.exit_code != 0
