"""Issue 19's acceptance on every sample: with the commands' defaults (every engine, RSS
profile ``auto``, public-road reach rules), the drive's top-ranked incident is the scripted
actor during its scripted event (docs/samples.md).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.workbench.cli_runs import run_workbench

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
T0_S = 1_700_000_000
LEAD = "00000000000000000000000000000001"
BUS = "00000000000000000000000000000002"

#: sample: (scripted actors, their event [s from the start]), from docs/samples.md.
EVENTS = {
    # car 1 cuts in 5.5-8.5 s
    "highway_cut_in": ({"1"}, (5.5, 8.5)),
    # the lead brakes from 5 s to a standstill
    "hard_braking_lead": ({LEAD}, (5.0, 15.0)),
    # car 1 drifts into the ego lane from 4 s; the cars pass at 10.9 s
    "wrong_way_oncoming": ({"1"}, (4.0, 10.9)),
    # the ego yields at the stop line (stops at 9.9 s) to car 1 (8.5 s) and bus 2 (9.1 s)
    "urban_intersection": ({LEAD, BUS}, (0.0, 9.9)),
    # pedestrian 1 steps off at 3 s and is in the ego lane 5.2-7.9 s
    "pedestrian_crossing": ({"1"}, (3.0, 7.9)),
    # car 1 reverses out from 3 s onto the aisle (11.5 s), drives off from 12 s
    "parking_lot": ({LEAD}, (3.0, 20.0)),
}


@pytest.mark.parametrize("sample", sorted(EVENTS))
def test_the_top_ranked_incident_is_the_scripted_event(sample: str, tmp_path: Path) -> None:
    out = tmp_path / "incidents.json"
    assert run_workbench(["incidents", str(SAMPLES / f"{sample}.mcap"), "--out", str(out)]) == 0
    incidents = json.loads(out.read_text())
    assert incidents
    top = incidents[0]
    actors, (start_s, end_s) = EVENTS[sample]
    assert set(top["objects"]) <= actors, top
    # the incident overlaps the scripted event
    first_s, last_s = (top["start_ns"] / 1e9 - T0_S, top["end_ns"] / 1e9 - T0_S)
    assert first_s <= end_s
    assert last_s >= start_s
