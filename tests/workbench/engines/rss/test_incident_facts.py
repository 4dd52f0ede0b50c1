"""An RSS incident's facts agree with the per-frame records of its frames."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from workbench.cli.main import app
from workbench.incidents import IncidentRequest, find_incidents

LOG = Path(__file__).resolve().parents[4] / "sample_logs" / "hard_braking_lead.mcap"


def test_incident_facts_summarise_the_frames(tmp_path: Path) -> None:
    report = find_incidents(IncidentRequest(LOG, engines=("rss",)))
    per_frame = tmp_path / "frames.jsonl"
    result = CliRunner().invoke(
        app, ["evaluate", str(LOG), "--engines", "rss", "--per-frame", str(per_frame)]
    )
    assert result.exit_code == 0, result.output
    records = [json.loads(line)["rss"] for line in per_frame.read_text().splitlines()]
    assert report.incidents
    for incident in report.incidents:
        (obj,) = incident.objects
        frames = records[incident.start_frame : incident.end_frame + 1]
        facts = incident.severity.facts
        ratios = [r["severity"][obj]["distance_ratio"] for r in frames if obj in r["severity"]]
        assert facts["distance_ratio_min"] == min(ratios)
        parties = {r["responsibility"][obj] for r in frames if obj in r["responsibility"]}
        want = "both" if "both" in parties or parties == {"ego", "object"} else parties.pop()
        assert facts["responsible"] == want
        shortfalls = [
            d["shortfall_mps2"]
            for r in frames
            for d in r["compliance"].get(obj, [])
            if d["shortfall_mps2"] is not None
        ]
        assert facts["shortfall_max_mps2"] == (max(shortfalls) if any(shortfalls) else None)
    worst = report.incidents[0]
    assert worst.severity.facts["responsible"] in {"ego", "both"}  # the ego follows the lead
