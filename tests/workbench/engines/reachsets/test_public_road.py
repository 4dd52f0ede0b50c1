"""The reach sets with the workbench's defaults on the samples: lane rules and braking check.

docs/samples.md: each scripted event starts after a free-flow stretch. With the defaults
(``public_road`` rules, ``auto`` trajectory) the engine must be safe before the event and
name the scripted actor during it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from loaders import open_drive
from tests.workbench.engines.helpers import record
from workbench.engines import build_runners
from workbench.engines.reachsets.options import ReachOptions, ReachRules, ReachTrajectory
from workbench.engines.reachsets.runner import ReachRunner

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
T0_NS = 1_700_000_000_000_000_000
LEAD = "00000000000000000000000000000001"
#: scenario -> (start of the scripted event [s] from docs/samples.md, scripted actor, end [s])
EVENTS = {
    "highway_cut_in": (5.0, "1", 20.0),
    "hard_braking_lead": (4.5, LEAD, 9.3),
    "wrong_way_oncoming": (3.5, "1", 10.9),
}


def _records(name: str, options: ReachOptions) -> list[tuple[float, dict[str, Any]]]:
    drive = open_drive(SAMPLES / name)
    try:
        (runner,) = build_runners(["reachsets"], drive.lane_map, {"reachsets": options})
        frames = list(drive.frames())
    finally:
        drive.close()
    out = []
    for k in range(0, len(frames), 32):
        chunk = frames[k : k + 32]
        out += [
            ((f.t_ns - T0_NS) / 1e9, record(v))
            for f, v in zip(chunk, runner.step_many(chunk), strict=True)
        ]
    return out


@pytest.fixture(scope="module")
def defaults() -> dict[str, list[tuple[float, dict[str, Any]]]]:
    return {name: _records(f"{name}.mcap", ReachOptions()) for name in EVENTS}


@pytest.mark.parametrize("name", list(EVENTS))
def test_safe_before_the_event_and_the_actor_named_during_it(name, defaults):
    start, actor, end = EVENTS[name]
    frames = defaults[name]
    assert all(r["is_safe"] for t, r in frames if t < start)
    during = [r for t, r in frames if start <= t <= end and not r["is_safe"]]
    assert during, "the scripted event is not flagged"
    assert all([c["object_id"] for c in r["collisions"]] == [actor] for r in during)
    assert all(r["trajectory"] == "braking_from_state" for _, r in frames)


def test_the_reference_settings_give_the_library_defaults():
    """``--reach-rules reference --reach-trajectory planned`` is the runner as before."""
    name = "highway_cut_in.mcap"
    reference = _records(
        name, ReachOptions(rules=ReachRules.reference, trajectory=ReachTrajectory.planned)
    )
    drive = open_drive(SAMPLES / name)
    try:
        runner = ReachRunner(drive.lane_map)
        plain = [record(v) for v in runner.step_many(list(drive.frames()))]
    finally:
        drive.close()
    assert [r for _, r in reference] == plain
    # frame 0 comes before the first plan message: speed and heading are held
    assert [r["trajectory"] for r in plain] == ["constant_speed"] + ["planned"] * (len(plain) - 1)
    # the reference rules flood the free-flow stretch (issue 19), the lane rules do not
    assert sum(not r["is_safe"] for t, r in reference if t < 5.0) > 0


def test_auto_rates_the_emergency_trajectory_of_a_log_that_has_one():
    frames = _records("racing_overtake.saa", ReachOptions())
    planned = _records("racing_overtake.saa", ReachOptions(trajectory=ReachTrajectory.planned))
    assert {r["trajectory"] for _, r in frames} == {"emergency"}
    assert frames == planned


def test_unknown_settings_are_one_line_errors():
    with pytest.raises(ValueError, match="reach rules 'bogus'"):
        ReachRunner(None, rules="bogus")
    drive = open_drive(SAMPLES / "hard_braking_lead.mcap")
    try:
        frame = next(iter(drive.frames()))
        with pytest.raises(ValueError, match="trajectory mode 'bogus'"):
            ReachRunner(drive.lane_map, trajectory="bogus").step_many([frame])
    finally:
        drive.close()
