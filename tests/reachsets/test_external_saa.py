"""Agreement with ScenarioArchitect's own ``safety_dyn`` labels on the two TUM sample logs."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.scenario_architect import open_scenario_architect
from reachsets.engine import ReachResult, evaluate
from reachsets.params import ReachMethod, ReachParams
from workbench.reach_adapter import frame_to_reach_inputs

if TYPE_CHECKING:
    from pathlib import Path

pytestmark = pytest.mark.external

#: labelled steps per file (13 safe + 10 unsafe, 76 safe + 12 unsafe)
FILES = {"modena_T1_cutin_collision.saa": 23, "modena_T3_T4_catchingup_collision.saa": 88}


def _verdicts(path: Path, method: ReachMethod) -> list[tuple[float, bool | None, ReachResult]]:
    drive = open_scenario_architect(path)
    state = None
    out = []
    for frame in drive.frames():
        result, state = evaluate(
            frame_to_reach_inputs(frame, drive.lane_map), ReachParams(method=method), state
        )
        out.append((frame.t_ns / 1e9, frame.extras["labels"]["safety_dyn"], result))
    return out


@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("name", sorted(FILES))
def test_every_labelled_step_agrees(external_dir, name, method):
    rows = _verdicts(external_dir / "trajectory_supervisor" / name, method)
    labelled = [(t, lab, r.is_safe) for t, lab, r in rows if lab is not None]
    assert len(labelled) == FILES[name]
    disagree = [(t, lab, safe) for t, lab, safe in labelled if lab != safe]
    assert disagree == []
    # every unsafe verdict names the object and a time inside the horizon
    for _, _, r in rows:
        for c in r.collisions:
            assert c.object_id == "veh_2"
            assert 0.0 <= c.t_offset_s <= 4.0
