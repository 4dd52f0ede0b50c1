"""Responsibility, severity and proper-response compliance on the hard_braking_lead sample.

Expected values come from the frames' raw boxes and speeds (a straight road along x) and
from the scenario as docs/samples.md describes it (the lead brakes at -7 m/s² from 5 s, the
ego reacts 1 s later with -6 m/s²), never from the engine's own output.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

from loaders.open import open_drive
from rss.params import rss_params_from_mapping
from workbench.engines.rss.compliance import slope
from workbench.engines.rss.record import rss_record
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
LEAD = "00000000000000000000000000000001"
T0_NS = 1_700_000_000_000_000_000


@pytest.fixture(scope="module")
def braking() -> list[tuple[Frame, dict[str, Any]]]:
    drive = open_drive(SAMPLES / "hard_braking_lead.mcap")
    try:
        frames = list(drive.frames())
        runner = RssRunner(drive.lane_map, rss_params_from_mapping({}, profile="highway"))
        verdicts = []
        for k in range(0, len(frames), 32):
            verdicts.extend(runner.step_many(frames[k : k + 32]))
    finally:
        drive.close()
    _MARGINS.extend(v.margin for v in verdicts)
    return [(f, rss_record(v)) for f, v in zip(frames, verdicts, strict=True)]


_MARGINS: list[float] = []


def _t(frame: Frame) -> float:
    return (frame.t_ns - T0_NS) / 1e9


def test_severity_facts_from_the_raw_boxes(braking) -> None:
    checked = 0
    for frame, record in braking:
        facts = record["severity"].get(LEAD)
        if facts is None:
            continue
        actors = frame.actors
        i = list(actors.ids).index(LEAD)
        ego = frame.ego
        gap = actors.x_m[i] - ego.x_m - (actors.length_m[i] + ego.length_m) / 2.0
        closing = ego.speed_mps - float(np.hypot(actors.vx_mps[i], actors.vy_mps[i]))
        if closing > 0.05:
            assert facts["ttc_s"] == pytest.approx(gap / closing, rel=1e-3)
            assert facts["required_decel_mps2"] == pytest.approx(closing**2 / (2 * gap), rel=2e-3)
            checked += 1
        # the pair overlaps laterally: the ratio is the longitudinal one (highway profile:
        # rear rho 0.5 s, a_max 2, brake_min -6; lead brake_max -8)
        v, vf = ego.speed_mps, float(np.hypot(actors.vx_mps[i], actors.vy_mps[i]))
        reach = v + 2.0 * 0.5
        safe = v * 0.5 + 0.5 * 2.0 * 0.25 + reach**2 / 12.0 - vf**2 / 16.0
        assert facts["distance_ratio"] == pytest.approx(gap / safe, rel=2e-3)
    assert checked > 20


def test_the_ego_is_responsible_and_its_response_is_due_after_its_response_time(braking):
    duties = [
        (frame, record["compliance"][LEAD])
        for frame, record in braking
        if LEAD in record["compliance"]
    ]
    assert duties
    for _frame, entries in duties:
        assert [e["party"] for e in entries] == ["ego"]  # the rear vehicle brakes
        duty = entries[0]
        assert duty["due_t_ns"] - duty["since_t_ns"] == 500_000_000  # ego rho 0.5 s
        assert duty["required_max_mps2"] == -6.0  # BrakeMin: the ego's brake_min
    first = duties[0][1][0]
    assert 5.0 <= (first["since_t_ns"] - T0_NS) / 1e9 < 6.0


def test_measured_deceleration_and_shortfall(braking):
    by_time = {round(_t(f), 2): r["compliance"].get(LEAD, [None])[0] for f, r in braking}
    # the ego brakes at -6 m/s² from 6 s; its response is due one response time after the
    # danger began (5.4 s: the lead's own 5.4 s box, braking at -7 m/s² since 5 s, is
    # nearer than its 5.3 s box extrapolated at constant speed); once the fit of its
    # positions since then covers only the braking phase, it measures -6 and complies
    due_s = min((d["due_t_ns"] - T0_NS) / 1e9 for d in by_time.values() if d is not None)
    assert 5.5 <= due_s < 6.0
    for t in (7.0, 7.5):
        duty = by_time[t]
        assert duty is not None
        assert duty["measured_mps2"] == pytest.approx(-6.0, abs=1e-3)
        assert duty["shortfall_mps2"] == pytest.approx(0.0, abs=1e-3)
    # the first half second after the response was due is not judged
    for t in np.arange(due_s, due_s + 0.5 - 1e-6, 0.05):
        duty = by_time[round(float(t), 2)]
        assert duty is not None
        assert duty["measured_mps2"] is None
        assert duty["shortfall_mps2"] is None
    # half a second after it was due the fit spans the half second since: the samples before
    # the braking began (6 s) make the response short by the least-squares fit's difference
    # to -6
    judged_s = round(due_s + 0.5, 2)
    frames = [f for f, _ in braking if due_s - 1e-6 <= _t(f) <= judged_s + 1e-6]
    tau = np.array([_t(f) for f in frames]) - (due_s + judged_s) / 2.0
    x = np.array([f.ego.x_m for f in frames])
    expected = 2.0 * np.polyfit(tau, x, 2)[0]  # the ego drives along +x
    first = by_time[judged_s]
    assert first is not None
    assert first["measured_mps2"] == pytest.approx(expected, abs=1e-6)
    assert -6.0 < expected < -5.0
    assert first["shortfall_mps2"] == pytest.approx(expected + 6.0, abs=1e-6)


def test_margin_is_the_worst_distance_ratio(braking):
    assert len(_MARGINS) == len(braking)
    for (_, record), margin in zip(braking, _MARGINS, strict=True):
        if record["is_safe"]:
            assert margin == float("inf")
            continue
        ratios = [f["distance_ratio"] for f in record["severity"].values()]
        assert margin == pytest.approx(min(ratios), abs=1e-6)
        assert 0.0 <= margin < 1.0


def test_slope_is_the_least_squares_derivative():
    t = np.array([0, 50_000_000, 100_000_000, 150_000_000], dtype=np.int64)
    v = np.asarray(20.0 - 3.0 * t / 1e9, dtype=np.float64)
    assert slope(t, v) == pytest.approx(-3.0)
    noisy = np.asarray(v + np.array([0.01, -0.01, -0.01, 0.01]), dtype=np.float64)
    assert slope(t, noisy) == pytest.approx(-3.0, abs=1e-9)  # symmetric noise cancels
    assert slope(t[:1], v[:1]) is None
