"""Property tests: monotonicity of safe distances and invariance under mirroring the frame."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rss.conformance import frame_record
from rss.conformance.cases import parse_case, parse_defaults
from rss.dynamics import RssDynamics
from rss.structured.batch import stack_dynamics
from rss.structured.engine import check_frame
from rss.structured.formulas import (
    safe_lateral_distance,
    safe_longitudinal_distance_opposite,
    safe_longitudinal_distance_same,
)
from rss.structured.stacking import stack_constellations
from tests.rss.structured.generators import random_case

#: ad-physics' tolerant ``max(d, 0)`` keeps values in (-1 mm, 0): monotone up to 1 mm.
_SLACK = 1e-3

speeds = st.floats(0.0, 60.0)
response_times = st.floats(0.05, 10.0)
approach_speeds = st.floats(0.0, 3.0)


def _dyn(rho: float) -> object:
    return stack_dynamics([RssDynamics(response_time_s=rho)])


@settings(max_examples=300, deadline=None)
@given(speeds, speeds, response_times, response_times, st.floats(0.0, 10.0))
def test_longitudinal_safe_distance_monotone(
    v: float, v_other: float, rho: float, rho2: float, dv: float
) -> None:
    lo, hi = sorted((rho, rho2))
    a = np.array([v])
    o = np.array([v_other])
    same_lo = safe_longitudinal_distance_same(_dyn(lo), a, _dyn(2.0), o)  # type: ignore[arg-type]
    same_hi = safe_longitudinal_distance_same(_dyn(hi), a, _dyn(2.0), o)  # type: ignore[arg-type]
    assert same_hi[0] >= same_lo[0] - _SLACK
    faster = safe_longitudinal_distance_same(_dyn(lo), a + dv, _dyn(2.0), o)  # type: ignore[arg-type]
    assert faster[0] >= same_lo[0] - _SLACK
    opp_lo = safe_longitudinal_distance_opposite(_dyn(lo), a, _dyn(lo), o)  # type: ignore[arg-type]
    opp_hi = safe_longitudinal_distance_opposite(_dyn(hi), a, _dyn(hi), o)  # type: ignore[arg-type]
    assert opp_hi[0] >= opp_lo[0] - _SLACK
    opp_fast = safe_longitudinal_distance_opposite(_dyn(lo), a + dv, _dyn(lo), o)  # type: ignore[arg-type]
    assert opp_fast[0] >= opp_lo[0] - _SLACK


@settings(max_examples=300, deadline=None)
@given(approach_speeds, approach_speeds, response_times, response_times, st.floats(0.0, 2.0))
def test_lateral_safe_distance_monotone(
    v_left: float, v_right: float, rho: float, rho2: float, dv: float
) -> None:
    """Vehicles not moving apart laterally (a receding one may gain distance with time)."""
    lo, hi = sorted((rho, rho2))
    left, right = np.array([v_left]), np.array([-v_right])
    base = safe_lateral_distance(_dyn(lo), left, _dyn(lo), right)  # type: ignore[arg-type]
    slower_reaction = safe_lateral_distance(_dyn(hi), left, _dyn(hi), right)  # type: ignore[arg-type]
    assert slower_reaction[0] >= base[0] - _SLACK
    # approaching faster (left moves right, right moves left) never reduces it
    closer = safe_lateral_distance(_dyn(lo), left + dv, _dyn(lo), right - dv)  # type: ignore[arg-type]
    assert closer[0] >= base[0] - _SLACK


def _evaluate(case: dict[str, Any]) -> dict[str, Any]:
    defaults = parse_defaults({})
    parsed = parse_case(case, defaults, "p")
    batch = stack_constellations([parsed.constellation])  # type: ignore[list-item]
    result, _ = check_frame(batch, defaults.ego)
    return frame_record(result, batch)


def _mirror_lateral(case: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(case)
    road = out["road"]
    total = sum(road["lane_widths"])
    road["lane_widths"] = road["lane_widths"][::-1]
    road["lane_directions"] = road["lane_directions"][::-1]
    for obj in (out["ego"], out["other"]):
        obj["y"] = total - obj["y"]
        for key in [k for k in obj if k.startswith("v_lat")]:
            obj[key] = -obj[key]
        if "v_lat_min" in obj:
            obj["v_lat_min"], obj["v_lat_max"] = obj["v_lat_max"], obj["v_lat_min"]
    return out


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_invariant_under_lateral_mirror(seed: int) -> None:
    """Mirroring the road across its centre line swaps left and right, nothing else."""
    case = random_case(np.random.default_rng(seed), parse_defaults({}), "m", boundary=False)
    if "road" not in case:
        return
    edges = [
        obj["y"] + sign * obj["width"] / 2.0
        for obj in (case["ego"], case["other"])
        for sign in (-1, 1)
    ]
    # mirroring changes float rounding: edges within the 1 mm tolerance may flip overlaps
    assume(all(abs(a - b) > 2e-3 for a in edges[:2] for b in edges[2:]))
    a, b = _evaluate(case), _evaluate(_mirror_lateral(case))
    sa, sb = a["states"][0], b["states"][0]
    assert sa["is_dangerous"] == sb["is_dangerous"]
    assert sa["longitudinal"] == sb["longitudinal"]
    for x, y in (("lateral_left", "lateral_right"), ("lateral_right", "lateral_left")):
        assert sa[x]["is_safe"] == sb[y]["is_safe"]
        assert sa[x]["response"] == sb[y]["response"]
        if sa[x]["safe_distance"] is not None:
            assert abs(sa[x]["safe_distance"] - sb[y]["safe_distance"]) < 1e-6
    pa, pb = a["proper_response"], b["proper_response"]
    assert pa["longitudinal_response"] == pb["longitudinal_response"]
    assert pa["lateral_response_left"] == pb["lateral_response_right"]


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(1.0, 150.0))
def test_opposite_direction_ignores_in_front_or_behind(seed: int, gap: float) -> None:
    """Opposite direction: the safe distance does not depend on which side the other is."""
    case = random_case(np.random.default_rng(seed), parse_defaults({}), "o", boundary=False)
    if case["constellation_type"] != "OppositeDirection":
        return
    half = (case["ego"]["length"] + case["other"]["length"]) / 2.0
    ahead, behind = copy.deepcopy(case), copy.deepcopy(case)
    ahead["other"]["s"] = case["ego"]["s"] + half + gap
    behind["other"]["s"] = case["ego"]["s"] - half - gap
    la, lb = (
        _evaluate(ahead)["states"][0]["longitudinal"],
        _evaluate(behind)["states"][0]["longitudinal"],
    )
    assert la["safe_distance"] == lb["safe_distance"]
    assert la["is_safe"] == lb["is_safe"]
