"""Events: overlapping incidents of every engine on one object, one id, one place in the order."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from tests.workbench.cli_runs import run_workbench
from workbench.incidents import Incident, Severity, event_id, group_events

T0 = 1_000_000_000
DT = 100_000_000
LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"


def _incident(engine: str, obj: str, start: int, end: int, gap_m: float = 5.0) -> Incident:
    return Incident(
        id=f"{engine}-{start:06d}-{obj}",
        engine=engine,
        objects=(obj,) if obj else (),
        cause="x",
        start_frame=start,
        end_frame=end,
        start_ns=T0 + start * DT,
        end_ns=T0 + end * DT,
        severity=Severity(0.0, end - start + 1, (end - start) * DT / 1e9, {"gap_min_m": gap_m}),
    )


def test_overlapping_incidents_of_one_object_are_one_event_with_every_engine():
    rss = _incident("rss", "7", 10, 30, gap_m=2.0)
    reach = _incident("reachsets", "7", 25, 40, gap_m=3.0)
    chained = _incident("unstructured", "7", 40, 45)  # touches reach's last frame
    (event,) = group_events([reach, chained, rss])
    assert event.incidents[0] is rss  # the most severe (smallest gap) leads
    assert {i.id for i in event.incidents} == {rss.id, reach.id, chained.id}
    assert event.engines == ("rss", "reachsets", "unstructured")
    assert (event.start_frame, event.end_frame) == (10, 45)
    assert event.id == event_id([chained, rss, reach])  # from the incident ids, any order
    assert event.id.startswith("event-000010-")
    assert event.record()["incidents"] == [i.id for i in event.incidents]


def test_disjoint_windows_or_other_objects_are_other_events():
    first, later = _incident("rss", "7", 10, 20), _incident("reachsets", "7", 21, 30)
    other = _incident("reachsets", "8", 10, 20, gap_m=1.0)
    nameless = _incident("reachsets", "", 10, 20)
    events = group_events([first, later, other, nameless])
    assert sorted(len(e.incidents) for e in events) == [1, 1, 1, 1]
    assert events[0].lead is other  # smallest gap first
    assert len({e.id for e in events}) == 4
    # the same incidents give the same ids
    assert [e.id for e in group_events([nameless, other, later, first])] == [e.id for e in events]


def _incidents_json(tmp_path: Path, *extra: str) -> tuple[list[dict[str, Any]], str]:
    out = tmp_path / f"i{len(extra)}.json"
    args = ["--engines", "rss,reachsets", "--reach-method", "simple", "--reach-rules", "reference"]
    assert run_workbench(["incidents", str(LOG), *args, *extra, "--out", str(out)]) == 0

    def strict(value: str) -> None:
        raise AssertionError(f"non-finite number {value} in the incidents JSON")

    return json.loads(out.read_text(), parse_constant=strict), out.name


def test_cli_lists_events_by_default_and_incidents_by_incident(tmp_path, capsys):
    by_event, _ = _incidents_json(tmp_path)
    title = capsys.readouterr().out
    assert "event(s) of" in title
    by_incident, _ = _incidents_json(tmp_path, "--by", "incident")
    assert "event(s)" not in capsys.readouterr().out
    assert sorted(r["id"] for r in by_event) == sorted(r["id"] for r in by_incident)
    assert all("event" not in r for r in by_incident)
    # each incident once, grouped: an event's incidents are consecutive
    events = [r["event"] for r in by_event]
    assert all(e.startswith("event-") for e in events)
    runs = [e for k, e in enumerate(events) if k == 0 or events[k - 1] != e]
    assert len(runs) == len(set(events))
    # the sample's reach-set and RSS incidents on the braking lead overlap: fewer events
    assert len(set(events)) < len(by_event)
    engines: dict[str, set[str]] = {}
    for row in by_event:
        engines.setdefault(row["event"], set()).add(row["engine"])
    assert {"rss", "reachsets"} in engines.values()
