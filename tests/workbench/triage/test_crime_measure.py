"""The independent criticality measure: the plain rule on made-up tracks, CriMe on NGSIM.

The numpy side (``conflicts.py``) and the benign-step facts (``benign.py``) are checked on
tracks built here, with hand-computed TTC, deceleration, gaps and clearances. CriMe's side
(``crime_side.py``) needs commonroad-crime, which lives in the side venv of ``make
oracle-crime``: there, on each of the 11 NGSIM scenarios, it must pick our loader's default ego
and flag the same pair-steps as the recompute on at least ``MIN_AGREEMENT`` of those both
computed (only near the ego's path, as the acceptance test does). In the project venv those
skip; in the side venv a missing commonroad-crime fails.
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders.commonroad import commonroad_ego_candidates
from loaders.commonroad_scenario import Track
from tests.conftest import EXTERNAL_DIR
from tests.workbench.triage import crime_side
from tests.workbench.triage.benign import pair_facts, rectangle_gap_m
from tests.workbench.triage.conflicts import PairStep, _pair_step, conflicts, in_path_limit_m

if TYPE_CHECKING:
    from pathlib import Path

SCENARIOS = sorted(p.name for p in (EXTERNAL_DIR / "commonroad_ngsim").glob("*.xml")) or [
    "(none found)"
]
#: Share of the pair-steps both sides computed that they must flag alike.
MIN_AGREEMENT = 0.99
IN_CRIME_ENV = os.environ.get("WORKBENCH_ORACLE_ENV") == "crime"


def _track(track_id: str, x_m: list[float], y_m: float, speed_mps: float) -> Track:
    n = len(x_m)
    speed = np.full(n, speed_mps)
    return Track(
        id=track_id,
        kind="car",
        dynamic=True,
        length_m=4.0,
        width_m=2.0,
        steps=np.arange(n, dtype=np.int64),
        x_m=np.array(x_m, dtype=float),
        y_m=np.full(n, y_m),
        yaw_rad=np.zeros(n),
        speed_mps=speed,
        vx_mps=speed,
        vy_mps=np.zeros(n),
        accel_mps2=np.zeros(n),
    )


def _steps(ego: Track, other: Track) -> list[PairStep]:
    limit = in_path_limit_m(ego, other)
    return [s for i in range(len(ego.steps)) for s in _pair_step(ego, i, other, i, limit)]


def test_leader_closing_in_path_is_a_conflict() -> None:
    # Ego at 10 m/s, leader at 5 m/s with its centre 10 m ahead: gap 6 m, closing 5 m/s.
    ego = _track("1", [0.0, 1.0, 2.0], 0.0, 10.0)
    leader = _track("2", [10.0, 10.5, 11.0], 0.3, 5.0)
    steps = _steps(ego, leader)
    first = steps[0]
    assert first.in_path
    assert first.gap_m == pytest.approx(6.0)
    assert first.ttc_s == pytest.approx(6.0 / 5.0)
    assert first.decel_mps2 == pytest.approx(25.0 / 12.0)
    found = conflicts(steps)
    assert [(c.object_id, c.first_step, c.last_step) for c in found] == [("2", 0, 2)]
    assert found[0].min_gap_m == pytest.approx(5.0)  # 11 - 2 - 4 at the last step
    assert found[0].record(0)["frames"] == [0, 2]


def test_adjacent_lane_and_opening_are_not_conflicts() -> None:
    ego = _track("1", [0.0, 1.0], 0.0, 10.0)
    beside = _track("2", [6.0, 6.5], 2.6, 5.0)  # 2.6 m > (2 + 2) / 2 + 0.5 = 2.5 m
    faster = _track("3", [6.0, 7.5], 0.0, 15.0)
    assert not any(s.in_path for s in _steps(ego, beside))
    assert all(math.isinf(s.ttc_s) for s in _steps(ego, faster))
    assert conflicts([*_steps(ego, beside), *_steps(ego, faster)]) == []


def test_benign_facts() -> None:
    box = np.array([[2.0, 1.0], [2.0, -1.0], [-2.0, -1.0], [-2.0, 1.0]])
    assert rectangle_gap_m(box, box + np.array([7.0, 0.0])) == pytest.approx(3.0)
    assert rectangle_gap_m(box, box + np.array([1.0, 0.5])) == 0.0
    ego = _track("1", [0.0, 0.0, 0.0], 0.0, 0.2)
    queued = _track("2", [5.0, 5.0, 5.0], 0.0, 0.3)
    assert all(f.both_stand for f in pair_facts(ego, queued, (0, 2, 0.1)))
    moving = _track("1", [0.0, 1.0, 2.0], 0.0, 10.0)
    far = _track("2", [25.0, 27.0, 29.0], 0.0, 20.0)
    assert all(f.far_opening and f.benign for f in pair_facts(moving, far, (0, 2, 0.1)))
    side = _track("2", [0.0, 1.0, 2.0], 3.8, 10.0)  # 3.8 - 1 - 1 = 1.8 m clear
    facts = pair_facts(moving, side, (0, 2, 0.1))
    assert all(f.lateral_clear_m == pytest.approx(1.8) and f.laterally_clear for f in facts)
    ahead = _track("2", [8.0, 8.5, 9.0], 0.0, 5.0)
    assert not any(f.benign for f in pair_facts(moving, ahead, (0, 2, 0.1)))


def _needs_crime() -> None:
    if not crime_side.available():
        if IN_CRIME_ENV:
            pytest.fail("commonroad-crime is missing from the side venv (make oracle-crime)")
        pytest.skip("commonroad-crime lives in the side venv: make oracle-crime")


@pytest.mark.oracle
@pytest.mark.external
@pytest.mark.parametrize("name", SCENARIOS)
def test_crime_agrees_with_recompute(external_dir: Path, name: str) -> None:
    _needs_crime()
    xml = external_dir / "commonroad_ngsim" / name
    verdict = crime_side.drive_verdict(xml)
    assert verdict["ego"] == commonroad_ego_candidates(xml)[0]
    agreement = verdict["agreement"]
    counts = verdict["pair_steps"]
    # Every pair-step asked for was computed by CriMe or its error counted.
    assert counts["crime"] + sum(verdict["crime_errors"].values()) == counts["asked"]
    assert agreement["compared"] == counts["crime"]
    assert agreement["agree"] >= MIN_AGREEMENT, (name, agreement, verdict["crime_only"])
    for conflict in verdict["conflicts"]:
        assert conflict["min_ttc_s"] <= 1.5 or conflict["max_required_decel_mps2"] >= 3.4
