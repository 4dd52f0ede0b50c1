"""The ego's lane margin on real traffic: USA_US101-3_3, object 394 changing lanes 35 -> 33.

The ego (2.41 m wide) brakes in lane 31, off-centre to the right; 394 changes from lane 35
into lane 33 (between them) at 0.6 m/s sideways. From frame 18 it is in lane 33, not
crossing towards the ego (cut-in duty holds); the ego's stop sticks 0.04 m (frame 23) out of
lane 31 into lane 33, a sliver within the lane margin. At frame 17, 394 is over its left line
towards the ego's side (no cut-in duty): that stays a danger.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.commonroad import open_commonroad
from workbench.engines.reachsets.runner import ReachRunner

if TYPE_CHECKING:
    from pathlib import Path


def _unsafe(external_dir: Path, rules: str) -> dict[int, tuple[str, ...]]:
    drive = open_commonroad(external_dir / "commonroad_ngsim" / "USA_US101-3_3_T-1.xml")
    runner = ReachRunner(drive.lane_map, rules=rules, trajectory="auto")
    verdicts = runner.step_many(list(drive.frames()))
    return {k: v.culprits for k, v in enumerate(verdicts) if not v.is_safe}


@pytest.mark.parametrize("frame", [18, 23])
def test_a_sliver_of_the_ego_in_the_next_lane_is_no_danger(external_dir: Path, frame: int):
    assert frame not in _unsafe(external_dir, "public_road")


def test_the_lane_change_towards_the_ego_is_still_found(external_dir: Path):
    assert _unsafe(external_dir, "public_road").get(17) == ("394",)


def test_the_reference_rules_keep_every_frame_of_394(external_dir: Path):
    unsafe = _unsafe(external_dir, "reference")
    assert all(unsafe.get(k) == ("394",) for k in range(17, 24))
