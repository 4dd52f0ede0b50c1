"""Responsibility: the constellations checked from the other object's side.

Independent checks: swapping twice is the identity; the object side sees the same danger
(RSS distances are symmetric); a same-direction pair built with the roles really exchanged
(the other as ego in the case file, so extraction runs on the exchanged geometry) gives the
ego side exactly the responses our swapped arrays give the object side; and asking for
responsibility never changes the ego's result.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest

from rss.conformance.cases import ParsedCase, parse_case, parse_defaults
from rss.dynamics import DYNAMICS_KEYS, RssDynamics
from rss.structured.engine import check_frames
from rss.structured.extraction import extract
from rss.structured.memory import is_dangerous
from rss.structured.responsibility import Responsible, swap_roles
from rss.structured.stacking import stack_constellations
from tests.rss.structured.generators import random_case, renumber

DEFAULTS = parse_defaults({})


def _parsed(cases: list[dict[str, Any]]) -> list[ParsedCase]:
    out = [renumber(parse_case(c, DEFAULTS, "r"), 2 * i, 2 * i + 1) for i, c in enumerate(cases)]
    return [p for p in out if p.constellation is not None]


def _check(parsed: list[ParsedCase], *, responsibility: bool):
    batch = stack_constellations([p.constellation for p in parsed])  # type: ignore[misc]
    n = batch.size
    result, _ = check_frames(
        batch, np.arange(n), n, DEFAULTS.ego, with_responsibility=responsibility
    )
    return result


@pytest.mark.parametrize("seed", [3, 17])
def test_responsibility_changes_nothing_of_the_ego_side(seed: int) -> None:
    rng = np.random.default_rng(seed)
    parsed = _parsed([random_case(rng, DEFAULTS, f"c{i}") for i in range(300)])
    plain = _check(parsed, responsibility=False)
    both = _check(parsed, responsibility=True)
    assert plain.responsibility is None
    assert both.responsibility is not None
    np.testing.assert_array_equal(plain.dangerous, both.dangerous)
    np.testing.assert_array_equal(plain.states.lon_response, both.states.lon_response)
    np.testing.assert_array_equal(plain.states.left.response, both.states.left.response)
    for name in ("is_safe", "longitudinal_response", "lon_max_mps2", "lat_left_max_mps2"):
        np.testing.assert_array_equal(getattr(plain.responses, name), getattr(both.responses, name))
    # same direction, RSS danger is symmetric: the object side is endangered exactly when the
    # ego is; ad-rss' ego-centric opposite-direction / intersection checks may differ
    valid = both.invalid == 0
    side = both.responsibility
    same = np.array([p.constellation.constellation_type == 1 for p in parsed])  # type: ignore[union-attr]
    np.testing.assert_array_equal(side.object_dangerous[same], both.dangerous[same])
    np.testing.assert_array_equal(side.object_dangerous, is_dangerous(side.object_states) & valid)
    assert np.mean(side.object_dangerous != both.dangerous) < 0.05
    who = side.responsible
    either = both.dangerous | side.object_dangerous
    assert not who[~either].any()
    np.testing.assert_array_equal(who & 1 != 0, side.ego_must_act)
    np.testing.assert_array_equal(who & 2 != 0, side.object_must_act)


def test_swapping_twice_is_the_identity() -> None:
    rng = np.random.default_rng(5)
    parsed = _parsed([random_case(rng, DEFAULTS, f"c{i}") for i in range(100)])
    batch = stack_constellations([p.constellation for p in parsed])  # type: ignore[misc]
    rel = extract(batch)
    again, rel2 = swap_roles(*swap_roles(batch, rel))
    np.testing.assert_array_equal(again.constellation_type, batch.constellation_type)
    np.testing.assert_array_equal(again.ego.speed_lon_max_mps, batch.ego.speed_lon_max_mps)
    np.testing.assert_array_equal(rel2.lon_position, rel.lon_position)
    np.testing.assert_array_equal(rel2.lat_position, rel.lat_position)
    np.testing.assert_array_equal(rel2.ego_dist_to_enter_m, rel.ego_dist_to_enter_m)


def _same_direction(seed: int, count: int) -> list[dict[str, Any]]:
    rng = np.random.default_rng(seed)
    out: list[dict[str, Any]] = []
    while len(out) < count:
        case = random_case(rng, DEFAULTS, f"s{len(out)}", boundary=False)
        road = case.get("road", {})
        vehicle = case.get("other", {}).get("object_type") == "OtherVehicle"
        if (
            case["constellation_type"] == "SameDirection"
            and vehicle
            and set(road.get("lane_directions", [])) == {"Positive"}
        ):
            out.append(case)
    return out


def _full(base: RssDynamics, overrides: dict[str, float]) -> dict[str, float]:
    values = {key: float(getattr(base, name)) for key, name in DYNAMICS_KEYS.items()}
    return values | overrides


def test_object_side_equals_the_pair_built_with_roles_exchanged() -> None:
    cases = _same_direction(11, 120)
    exchanged = []
    for case in cases:
        swapped = copy.deepcopy(case)
        swapped["ego"], swapped["other"] = case["other"], case["ego"]
        swapped["other"]["object_type"] = "OtherVehicle"
        swapped["ego"].pop("object_type", None)
        # every value explicit: the case defaults differ by role (ego rho 1 s, others 2 s)
        swapped["ego_dynamics"] = _full(DEFAULTS.vehicle, case.get("other_dynamics", {}))
        swapped["other_dynamics"] = _full(DEFAULTS.ego, case.get("ego_dynamics", {}))
        exchanged.append(swapped)
    ours = _check(_parsed(cases), responsibility=True)
    theirs = _check(_parsed(exchanged), responsibility=False)
    assert ours.responsibility is not None
    side = ours.responsibility.object_states
    np.testing.assert_array_equal(ours.responsibility.object_dangerous, theirs.dangerous)
    np.testing.assert_array_equal(side.lon_response, theirs.states.lon_response)
    np.testing.assert_array_equal(side.left.response, theirs.states.left.response)
    np.testing.assert_array_equal(side.right.response, theirs.states.right.response)
    np.testing.assert_allclose(side.lon_safe_distance_m, theirs.states.lon_safe_distance_m)
    assert ours.dangerous.any()


def _following(ego_s: float, other_s: float, ctype: str = "SameDirection") -> dict[str, Any]:
    directions = ["Positive", "Negative"] if ctype == "OppositeDirection" else ["Positive"]
    other_y = 1.75  # head-on: the other drives in the ego's lane
    return {
        "kind": "structured",
        "constellation_type": ctype,
        "road": {
            "length": 1000.0,
            "lane_widths": [3.5] * len(directions),
            "lane_directions": directions,
        },
        "ego": {"s": ego_s, "y": 1.75, "length": 4.5, "width": 1.8, "v_lon": 20.0},
        "other": {
            "s": other_s,
            "y": other_y,
            "length": 4.5,
            "width": 1.8,
            "v_lon": 20.0,
            "object_type": "OtherVehicle",
        },
    }


def test_who_must_act_in_textbook_pairs() -> None:
    # 15 m apart at 20 m/s: dangerous under the reference dynamics in every pair below
    cases = [
        _following(100.0, 119.5),  # ego behind: the rear one (ego) brakes
        _following(119.5, 100.0),  # ego in front: the object brakes
        _following(100.0, 119.5, "OppositeDirection"),  # head-on: both brake
    ]
    result = _check(_parsed(cases), responsibility=True)
    assert result.responsibility is not None
    assert result.dangerous.tolist() == [True, True, True], result.states.lon_safe_distance_m
    codes = [Responsible(int(c)) for c in result.responsibility.responsible]
    assert codes == [Responsible.EGO, Responsible.OBJECT, Responsible.BOTH]
    assert [str(c) for c in codes] == ["ego", "object", "both"]
