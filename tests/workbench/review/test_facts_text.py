"""Facts for a person: units from the names, three significant digits, ``—`` for none."""

import asyncio
import dataclasses
from typing import Any

from textual.widgets import Static

from tests.workbench.review.helpers import T0, report
from workbench.annotations import LabelStore
from workbench.incidents import Severity
from workbench.replay.incidents import short_labels
from workbench.review import ReviewSession
from workbench.review.app import ReviewApp
from workbench.review.facts_text import fact_text, facts_text, number_text

LONG_ID = "00000000000000000000000000000001"


def test_numbers_get_three_significant_digits_and_no_exponent():
    assert number_text(0.8317610715433722) == "0.832"
    assert number_text(-0.0) == "0"
    assert number_text(12.3456) == "12.3"
    assert number_text(1234.5) == "1234"  # never 1.23e+03
    assert number_text(0.000123456) == "0.000123"
    assert number_text(float("inf")) == "∞"
    assert number_text(float("nan")) == "—"


def test_units_come_from_the_name_and_none_is_a_dash():
    assert fact_text("shortfall_max_mps2", None) == "shortfall max —"
    assert fact_text("ttc_min_s", 1.23456) == "ttc min 1.23 s"
    assert fact_text("required_decel_max_mps2", 3.0) == "required decel max 3.00 m/s²"
    assert fact_text("speed_mps", 12.0) == "speed 12.0 m/s"
    assert fact_text("gap_m", 0.5) == "gap 0.500 m"
    assert fact_text("unsafe_frames", 7) == "unsafe frames 7"
    assert fact_text("responsible", "ego") == "responsible ego"
    assert fact_text("severity_rank", [-0.0, 0.8317610715433722, None]) == (
        "severity rank (0, 0.832, —)"
    )
    # a time stamp is shown in seconds after the drive's start
    assert fact_text("response_due_ns", T0 + 2_500_000_000, t0_ns=T0) == "response due 2.50 s"


def test_any_mapping_of_facts_is_text_in_its_order():
    text = facts_text({"b_m": 1.0, "a": None}, separator=" | ")
    assert text == "b 1.00 m | a —"


def test_objects_get_short_labels_by_first_incident():
    rep = report(3)  # objects "1", "2", "3" starting at frames 10, 20, 30
    again = dataclasses.replace(rep.incidents[0], id="rss-000040-x", start_frame=40)
    labels = short_labels([*reversed(rep.incidents), again])
    assert labels == {"1": "#1", "2": "#2", "3": "#3"}


def test_the_facts_panel_is_formatted_and_shows_full_ids_on_demand(tmp_path):
    rep = report(2)
    # as the RSS collector gives them (JSON-ready: None for a missing value)
    facts: dict[str, Any] = {"ttc_min_s": 0.8317610715433722, "shortfall_max_mps2": None}
    first = dataclasses.replace(
        rep.incidents[0],
        objects=(LONG_ID,),
        severity=Severity(0.0, 5, 0.4, facts),
    )
    rep = dataclasses.replace(rep, incidents=(first, *rep.incidents[1:]))
    with LabelStore(tmp_path / "l.sqlite") as store:
        app = ReviewApp(ReviewSession(rep, store, "ann"))

        async def run() -> tuple[str, str]:
            async with app.run_test() as pilot:
                await pilot.pause()
                short = str(app.query_one("#facts", Static).render())
                await pilot.press("i")
                await pilot.pause()
                full = str(app.query_one("#facts", Static).render())
                await pilot.press("q")
            return short, full

        short, full = asyncio.run(run())
    assert "object #1" in short
    assert LONG_ID not in short
    assert "ttc min 0.832 s" in short
    assert "shortfall max —" in short
    assert "None" not in short
    assert f"#1 = {LONG_ID}" in full
