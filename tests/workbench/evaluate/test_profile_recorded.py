"""Every output of a run records the RSS parameter profile its verdicts were checked with."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from tests.workbench.cli_runs import run_workbench

LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"


@pytest.mark.parametrize(("chosen", "recorded"), [("auto", "highway"), ("adrss-5.0", "adrss-5.0")])
def test_violations_and_incidents_name_the_profile(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], chosen: str, recorded: str
) -> None:
    engines = ["--engines", "rss,reachsets", "--rss-profile", chosen]
    table = tmp_path / "violations.csv"
    assert run_workbench(["evaluate", str(LOG), *engines, "--violations", str(table)]) == 0
    assert f"with rss, reachsets (rss profile {recorded});" in capsys.readouterr().out
    with table.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert {r["engine"] for r in rows} == {"rss", "reachsets"}
    # the RSS rows name their profile; the reach-set engine's verdicts name none
    assert {(r["engine"], r["profile"]) for r in rows} == {("rss", recorded), ("reachsets", "")}
    out = tmp_path / "incidents.json"
    assert run_workbench(["incidents", str(LOG), *engines, "--out", str(out)]) == 0
    incidents = json.loads(out.read_text())
    assert {i["severity"].get("profile") for i in incidents if i["engine"] == "rss"} == {recorded}
