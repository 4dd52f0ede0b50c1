"""What-if: an incident under another RSS profile, against a whole-drive run of that profile."""

from __future__ import annotations

import asyncio
import dataclasses
from pathlib import Path

import pytest
from textual.widgets import Static

from rss.profiles import PROFILES
from workbench.annotations import LabelStore
from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, find_incidents
from workbench.incidents.whatif import what_if
from workbench.review import ReviewSession
from workbench.review.app import ReviewApp

LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"
REQUEST = IncidentRequest(LOG, engines=("rss",))


@pytest.fixture(scope="module")
def report():
    return find_incidents(REQUEST)


@pytest.mark.parametrize("profile", sorted(PROFILES))
def test_what_if_agrees_with_the_whole_drive_under_that_profile(report, profile: str) -> None:
    incident = report.incidents[0]
    outcome = what_if(REQUEST, incident, profile)
    whole = find_incidents(
        dataclasses.replace(REQUEST, options=engine_options({"rss_profile": profile}))
    )
    overlapping = [
        i
        for i in whole.incidents
        if i.objects == incident.objects
        and i.start_ns <= incident.end_ns
        and i.end_ns >= incident.start_ns
    ]
    assert outcome.stays == bool(overlapping)
    assert outcome.profile in outcome.line()


def test_what_if_key_shows_the_outcome(report, tmp_path: Path) -> None:
    with LabelStore(tmp_path / "l.sqlite") as store:
        app = ReviewApp(ReviewSession(report, store, "ann"))

        async def run() -> str:
            async with app.run_test() as pilot:
                await pilot.press("w")
                await pilot.pause()
                return str(app.query_one("#facts", Static).render())

        text = asyncio.run(run())
    first = min(PROFILES)
    assert f"what-if {first}: " in text


def _overlaps(incident, others) -> bool:
    return any(
        i.objects == incident.objects
        and i.start_ns <= incident.end_ns
        and i.end_ns >= incident.start_ns
        for i in others
    )


def test_an_incident_that_the_highway_profile_clears() -> None:
    log = LOG.with_name("urban_intersection.mcap")  # a junction: auto keeps adrss-5.0 here
    reference = IncidentRequest(
        log, engines=("rss",), options=engine_options({"rss_profile": "adrss-5.0"})
    )
    strict = find_incidents(reference).incidents
    relaxed = find_incidents(
        dataclasses.replace(reference, options=engine_options({"rss_profile": "highway"}))
    ).incidents
    cleared = [i for i in strict if not _overlaps(i, relaxed)]
    assert cleared, "the stricter ad-rss defaults flag something the highway profile does not"
    outcome = what_if(reference, cleared[0], "highway")
    assert not outcome.stays
    assert outcome.line() == "what-if highway: no longer an incident"


def test_incident_start_positions_are_the_frames_actors(report) -> None:
    drive = REQUEST.open_drive()
    try:
        frames = {f.index: f for f in drive.frames()}
    finally:
        drive.close()
    for incident in report.incidents:
        at = report.objects_at_start_m[incident.start_frame]
        frame = frames[incident.start_frame]
        for obj in incident.objects:
            j = frame.actors.ids.tolist().index(obj)
            assert at[obj] == (float(frame.actors.x_m[j]), float(frame.actors.y_m[j]))
