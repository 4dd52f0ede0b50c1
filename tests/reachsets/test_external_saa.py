"""Agreement with ScenarioArchitect's ``safety_dyn`` labels and with the reference's measured
verdicts (``reference/trajectory-supervisor-reach-sets-notes.md`` §5.2 and §9) on the two TUM
sample logs."""

from __future__ import annotations

from functools import cache
from typing import TYPE_CHECKING

import pytest

from loaders.scenario_architect import open_scenario_architect
from reachsets import evaluate_frames
from reachsets.params import F1Params, ReachMethod, ReachParams
from tests.reachsets.helpers import evaluate_one
from workbench.engines.reachsets.adapter import frame_to_reach_inputs

if TYPE_CHECKING:
    from pathlib import Path

    from reachsets.engine import ReachResult

pytestmark = pytest.mark.external

#: labelled steps per file (13 safe + 10 unsafe, 76 safe + 12 unsafe)
T1, T34 = "modena_T1_cutin_collision.saa", "modena_T3_T4_catchingup_collision.saa"
FILES = {T1: 23, T34: 88}

# Facts from the reference notes (measured on the reference, emergency plan, defaults):
#: first unsafe step per method (§9)
REF_FIRST_UNSAFE_S = {
    T1: {"simple": 0.0, "turn": 2.4, "bound": 2.4},
    T34: {"simple": 12.4, "turn": 12.6, "bound": 12.6},
}
#: unsafe steps with ``turn``, F1 on or off (§5.2)
REF_TURN_UNSAFE = {T1: 52, T34: 17}
#: steps at which an F1 patch fired (§5.2)
REF_F1_PATCH_STEPS = {T1: 0, T34: 1}
#: Known open difference: on T1 the reference flags ``turn``/``bound`` from 2.4 s, we from
#: 2.6 s (2.4 and 2.5 s stay safe here; the next reach set misses the ego by 1.5 / 0.4 m).
T1_ONSET_GAP = pytest.mark.xfail(
    strict=True, reason="T1 turn/bound: reference unsafe from 2.4 s, ours from 2.6 s"
)


@cache
def _verdicts(
    path: Path, method: ReachMethod, *, f1: bool = True
) -> tuple[tuple[float, bool | None, ReachResult], ...]:
    drive = open_scenario_architect(path)
    params = ReachParams(method=method, f1=F1Params(enabled=f1))
    state = None
    out = []
    for frame in drive.frames():
        result, state = evaluate_one(frame_to_reach_inputs(frame, drive.lane_map), params, state)
        out.append((round(frame.t_ns / 1e9, 2), frame.extras["labels"]["safety_dyn"], result))
    return tuple(out)


def _unsafe(rows: tuple[tuple[float, bool | None, ReachResult], ...]) -> list[float]:
    return [t for t, _, r in rows if not r.is_safe]


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


def _expect_t1_gap(name: str, method: ReachMethod) -> list[pytest.MarkDecorator]:
    return [T1_ONSET_GAP] if name == T1 and method != ReachMethod.SIMPLE else []


@pytest.mark.parametrize(
    ("name", "method"),
    [
        pytest.param(n, m, marks=_expect_t1_gap(n, m), id=f"{n[:9]}-{m.value}")
        for n in (T1, T34)
        for m in ReachMethod
    ],
)
def test_first_unsafe_step_matches_reference(external_dir, name, method):
    rows = _verdicts(external_dir / "trajectory_supervisor" / name, method)
    assert _unsafe(rows)[0] == pytest.approx(REF_FIRST_UNSAFE_S[name][method.value])


@pytest.mark.parametrize(
    "name", [pytest.param(T1, marks=T1_ONSET_GAP, id="T1"), pytest.param(T34, id="T3_T4")]
)
def test_turn_unsafe_count_matches_reference(external_dir, name):
    rows = _verdicts(external_dir / "trajectory_supervisor" / name, ReachMethod.TURN)
    assert len(_unsafe(rows)) == REF_TURN_UNSAFE[name]


@pytest.mark.parametrize("name", [T1, T34])
def test_turn_verdicts_do_not_depend_on_f1(external_dir, name):
    path = external_dir / "trajectory_supervisor" / name
    on = _verdicts(path, ReachMethod.TURN)
    off = _verdicts(path, ReachMethod.TURN, f1=False)
    assert _unsafe(on) == _unsafe(off)


@pytest.mark.parametrize("name", [T1, T34])
def test_f1_patch_fires_at_reference_step_count(external_dir, name):
    rows = _verdicts(external_dir / "trajectory_supervisor" / name, ReachMethod.TURN)
    fired = [t for t, _, r in rows if any(p.rule.startswith("f1.") for p in r.patches)]
    assert len(fired) == REF_F1_PATCH_STEPS[name]


@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("name", [T1, T34])
def test_verdict_only_mode_matches_full_geometry(external_dir, name, method):
    drive = open_scenario_architect(external_dir / "trajectory_supervisor" / name)
    fast = ReachParams(method=method, full_geometry=False)
    state = None
    got = []
    for frame in drive.frames():
        result, state = evaluate_one(frame_to_reach_inputs(frame, drive.lane_map), fast, state)
        got.append(result.collisions)
    full = _verdicts(external_dir / "trajectory_supervisor" / name, method)
    assert got == [r.collisions for _, _, r in full]


@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("name", [T1, T34])
def test_batched_replay_matches_frame_by_frame(external_dir, name, method):
    """``evaluate_frames`` over the whole log (verdict only) gives the frame-by-frame results."""
    drive = open_scenario_architect(external_dir / "trajectory_supervisor" / name)
    frames = [frame_to_reach_inputs(f, drive.lane_map) for f in drive.frames()]
    results, _ = evaluate_frames(frames, ReachParams(method=method, full_geometry=False), None)
    full = _verdicts(external_dir / "trajectory_supervisor" / name, method)
    assert [r.collisions for r in results] == [r.collisions for _, _, r in full]
    assert [[p.rule for p in r.patches] for r in results] == [
        [p.rule for p in r.patches] for _, _, r in full
    ]
