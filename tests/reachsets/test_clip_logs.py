"""Full sets with the clipper equal GEOS' on every frame of the racing sample and the TUM logs."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.scenario_architect import open_scenario_architect
from reachsets import evaluate_frames, reachable
from reachsets.params import ReachMethod, ReachParams
from tests.reachsets.helpers import same_sets
from workbench.engines.reachsets.adapter import frame_to_reach_inputs
from workbench.samples.racing import write_racing_sample

if TYPE_CHECKING:
    from pathlib import Path

    from reachsets.engine import ReachResult
    from reachsets.inputs import ReachInputs

TOL = 1e-9
TUM = ("modena_T1_cutin_collision.saa", "modena_T3_T4_catchingup_collision.saa")


def _inputs(path: Path) -> list[ReachInputs]:
    drive = open_scenario_architect(path)
    return [frame_to_reach_inputs(f, drive.lane_map) for f in drive.frames()]


def _frame_by_frame(
    inputs: list[ReachInputs], method: ReachMethod, monkeypatch: pytest.MonkeyPatch, *, clip: bool
) -> list[ReachResult]:
    monkeypatch.setattr(reachable, "SCALAR_CLIP", clip)
    params = ReachParams(method=method, full_geometry=True)
    state, out = None, []
    for inp in inputs:
        results, state = evaluate_frames([inp], params, state)
        out += results
    return out


def _assert_same(inputs: list[ReachInputs], method: ReachMethod, monkeypatch: pytest.MonkeyPatch):
    got = _frame_by_frame(inputs, method, monkeypatch, clip=True)
    want = _frame_by_frame(inputs, method, monkeypatch, clip=False)
    assert sum(r.sets.size for r in want) > 0
    for g, w in zip(got, want, strict=True):
        assert g.is_safe == w.is_safe
        assert g.collisions == w.collisions
        same_sets(g.sets, w.sets, TOL)


@pytest.mark.parametrize("method", list(ReachMethod))
def test_racing_sample_full_sets_equal_geos(tmp_path, method, monkeypatch):
    _assert_same(_inputs(write_racing_sample(tmp_path)[0]), method, monkeypatch)


@pytest.mark.external
@pytest.mark.parametrize("name", TUM)
@pytest.mark.parametrize("method", list(ReachMethod))
def test_tum_logs_full_sets_equal_geos(external_dir, name, method, monkeypatch):
    _assert_same(_inputs(external_dir / "trajectory_supervisor" / name), method, monkeypatch)
