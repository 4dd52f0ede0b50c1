"""Clip plans: selection, windows within the drive, portable file names."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from workbench.annotations import Label, ReviewVerdict
from workbench.errors import WorkbenchError
from workbench.export import Selection, plan_clips, safe_stem
from workbench.incidents import Incident, IncidentReport, Severity


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("rss-000119-b09b019ca5", "rss-000119-b09b019ca5"),
        ("../../etc/passwd", "etc_passwd"),
        ("a b/c\\d:e*f?g", "a_b_c_d_e_f_g"),
        ("..", "clip"),
        ("", "clip"),
        (".hidden", "hidden"),
        ("x" * 300, "x" * 96),
        ("a..b", "a_b"),
        ("\x00\n$(rm -rf)", "rm_-rf"),
    ],
)
def test_safe_stem(text: str, expected: str) -> None:
    assert safe_stem(text) == expected


def _incident(iid: str, start: int, end: int) -> Incident:
    return Incident(
        iid,
        "rss",
        ("7",),
        "lon",
        start,
        end,
        start * 10,
        end * 10,
        Severity(0.1, end - start + 1, 0.0),
    )


def _report() -> IncidentReport:
    frames = tuple((k, k * 10) for k in range(100))
    incidents = (_incident("a/../b", 2, 5), _incident("c", 50, 98))
    return IncidentReport(Path("drive.mcap"), "h", {}, incidents, frames, 0)


def test_windows_clamped_to_the_drive_and_names_unique() -> None:
    plans = plan_clips(_report(), {}, Selection(all=True), margin_ns=100)
    assert [(p.start_ns, p.end_ns) for p in plans] == [(0, 150), (400, 990)]
    assert [p.stem for p in plans] == ["001_a_b", "002_c"]
    assert all("/" not in p.stem for p in plans)


def test_selection_by_id_and_by_verdict() -> None:
    report = _report()
    label = Label("h", "c", ReviewVerdict.CONFIRMED, ("late",), "note", "ann")
    assert [p.event()["incident_id"] for p in plan_clips(report, {}, Selection(ids=("c",)), 0)] == [
        "c"
    ]
    chosen = plan_clips(report, {"c": label}, Selection(verdict="confirmed"), 0)
    assert [p.event()["incident_id"] for p in chosen] == ["c"]
    assert chosen[0].event()["verdict"] == "confirmed"
    assert json.loads(chosen[0].event()["tags"]) == ["late"]
    assert plan_clips(report, {"c": label}, Selection(verdict="follow_up"), 0) == []


@pytest.mark.parametrize(
    ("selection", "message"),
    [
        (Selection(ids=("nope",)), "no incident nope"),
        (Selection(), "exactly one of"),
        (Selection(ids=("c",), all=True), "exactly one of"),
    ],
)
def test_bad_selection_is_one_clear_error(selection: Selection, message: str) -> None:
    with pytest.raises(WorkbenchError, match=message):
        plan_clips(_report(), {}, selection, 0)
