"""The reach-set case format: parsing, typed errors, records, ``expected`` checks."""

from __future__ import annotations

import copy
import json
import math
from typing import Any

import pytest
import shapely

from reachsets import ReachMethod, ReachParams, evaluate_frames
from reachsets.conformance import (
    ReachCaseError,
    check_expected,
    evaluate_document,
    parse_defaults,
)
from tests.reachsets.conformance.direct import direct_inputs

#: A straight track 20 m wide along +x; the ego at 10 m/s, one object 12 m ahead standing
#: in its lane (the ego drives into it) and one far behind (skipped: followers are responsible).
TRACK = {"left": [[0.0, 10.0], [400.0, 10.0]], "right": [[0.0, -10.0], [400.0, -10.0]]}
EGO = {
    "x": [50.0, 60.0, 70.0, 80.0, 90.0],
    "y": [0.0] * 5,
    "heading": [0.0] * 5,
    "speed": [10.0] * 5,
    "t_s": [0.0, 1.0, 2.0, 3.0, 4.0],
}
AHEAD = {"id": "lead", "x": 62.0, "y": 0.0, "yaw": 0.0, "speed": 0.0, "length": 4.5, "width": 2}
BEHIND = {"id": 7, "x": 10.0, "y": 0.0, "yaw": 0.0, "speed": 5.0}


def _document(**case: Any) -> dict[str, Any]:
    base = {"id": "c", "ego": EGO, "objects": [AHEAD, BEHIND]}
    return {"defaults": {"track": TRACK, "method": "simple"}, "cases": [base | case]}


def _direct(method: str, objects: list[dict[str, Any]], *, track: bool = True) -> Any:
    inputs = direct_inputs(
        EGO,
        objects,
        track_left_m=TRACK["left"] if track else None,
        track_right_m=TRACK["right"] if track else None,
    )
    results, _ = evaluate_frames([inputs], ReachParams(method=ReachMethod(method)), None)
    return results[0]


@pytest.mark.parametrize("method", [m.value for m in ReachMethod])
def test_record_matches_the_engine(method: str) -> None:
    (record,) = evaluate_document(_document(method=method))
    direct = _direct(method, [AHEAD, BEHIND])
    assert record["ok"] is True
    assert record["method"] == method
    assert record["safe"] is direct.is_safe is False
    assert record["collisions"] == [
        {"object_id": c.object_id, "t_offset_s": pytest.approx(c.t_offset_s), "step": c.step}
        for c in direct.collisions
    ]
    assert record["checked_ids"] == ["lead"]
    assert record["checked_objects"] == 1
    assert record["skipped_ids"] == ["7"]
    assert "sets" not in record


def test_full_sets_give_the_reduced_outlines_and_the_same_verdict() -> None:
    (verdict,) = evaluate_document(_document(method="turn"))
    (full,) = evaluate_document(_document(method="turn"), full_sets=True)
    assert {k: v for k, v in full.items() if k != "sets"} == verdict
    direct = _direct("turn", [AHEAD, BEHIND])
    sets = full["sets"]
    assert sets["t_s"] == pytest.approx(list(direct.occupancy.t_s))
    (entry,) = sets["objects"]
    assert entry["object_id"] == "lead"
    assert len(entry["outlines"]) == len(sets["t_s"])
    for geometry, rings in zip(direct.reach_sets[0], entry["outlines"], strict=True):
        if geometry is None:
            assert rings == []
            continue
        area = sum(shapely.Polygon(list(zip(*r, strict=True))).area for r in rings)
        assert (
            area >= geometry.area - 1e-4
        )  # exteriors only (holes not subtracted), 1e-6 m rounding
        assert area == pytest.approx(
            sum(shapely.Polygon(p.exterior).area for p in shapely.get_parts(geometry)), abs=1e-3
        )
    assert "NaN" not in json.dumps(full)


def test_expected_block_is_checked() -> None:
    direct = _direct("simple", [AHEAD, BEHIND])
    first = direct.collisions[0]
    good = {"safe": False, "object_id": "lead", "t_offset_s": first.t_offset_s, "step": first.step}
    (record,) = evaluate_document(_document(expected=good))
    assert record["expected_check"] == {"passed": True, "failures": []}
    bad = good | {"safe": True, "step": first.step + 1}
    (record,) = evaluate_document(_document(expected=bad))
    assert record["expected_check"]["passed"] is False
    assert len(record["expected_check"]["failures"]) == 2
    safe_case = {"safe": True, "collisions": []}
    assert check_expected(safe_case, {"object_id": "x"})["failures"] == ["object_id: no collision"]


def test_sequence_records_carry_ids_and_equal_one_engine_call() -> None:
    steps = [{"ego": EGO, "objects": [AHEAD]}, {"ego": EGO, "objects": [AHEAD | {"x": 70.0}]}]
    document = _document(sequence=steps)
    del document["cases"][0]["ego"], document["cases"][0]["objects"]
    records = list(evaluate_document(document))
    assert [(r["id"], r["sequence_id"], r["step"]) for r in records] == [
        ("c#0", "c", 0),
        ("c#1", "c", 1),
    ]
    assert all(r["ok"] for r in records)


def test_params_overrides_reach_the_engine() -> None:
    document = _document()
    document["defaults"]["params"] = {"t_max_s": 2.0, "f1": {"enabled": False}}
    defaults = parse_defaults(document)
    assert defaults.params[ReachMethod.BOUND].t_max_s == 2.0
    assert defaults.params[ReachMethod.BOUND].f1.enabled is False
    assert defaults.params[ReachMethod.BOUND].method is ReachMethod.BOUND
    (record,) = evaluate_document(document, full_sets=True)
    assert record["sets"]["t_s"][-1] == 2.0
    assert defaults.start.track is not None  # the track is built once, here


@pytest.mark.parametrize(
    ("mutate", "field", "reason"),
    [
        (lambda c: c["ego"].update(speed=[1, 2]), "ego.speed", "expected 5 values"),
        (lambda c: c["ego"].update(x=[]), "ego.x", "non-empty list"),
        (lambda c: c["objects"][0].update(yaw="left"), "objects.0.yaw", "expected a number"),
        (lambda c: c["objects"][0].update(x=math.inf), "objects.0.x", "finite"),
        (lambda c: c["objects"][0].update(y=10**400), "objects.0.y", "finite"),
        (lambda c: c["ego"].update(x=[1.0, 2.0, math.inf, 4.0, 5.0]), "ego.x.2", "finite"),
        (lambda c: c["ego"].update(y=[0.0, 1e308, 1e308, 0.0, True]), "ego.y.4", "a number"),
        (lambda c: c["objects"][1].update(id="lead"), "objects.1.id", "unique"),
        (lambda c: c["objects"][0].update(colour="red"), "objects.0.colour", "unknown key"),
        (lambda c: c.update(method="fast"), "method", "simple, turn, bound"),
        (lambda c: c.update(expected={"safe": "no"}), "expected.safe", "true or false"),
        (lambda c: c.update(sequence=[]), "sequence", "non-empty list"),
        (lambda c: c["ego"].update(t_s=[0.0, 1.0, 0.5, 3.0, 4.0]), "ego.t_s", "non-decreasing"),
        (lambda c: c["ego"].update(width=0), "ego.width", "positive size"),
        (lambda c: c["objects"][0].update(length=-4.0), "objects.0.length", "positive size"),
        (lambda c: c["ego"].update(heading=[math.nan] * 5), "ego.heading.0", "finite"),
    ],
)
def test_malformed_case_gives_a_one_line_record(mutate: Any, field: str, reason: str) -> None:
    document = copy.deepcopy(_document())
    mutate(document["cases"][0])
    document["cases"].append(copy.deepcopy(_document())["cases"][0] | {"id": "fine"})
    bad, fine = evaluate_document(document, "cases.json")
    assert bad["ok"] is False
    assert fine["ok"] is True
    assert bad["id"] == "c"
    assert "\n" not in bad["error"]
    assert bad["error"].startswith(f"reach-set cases cases.json, case 'c', {field}=")
    assert reason in bad["error"]


@pytest.mark.parametrize(
    ("document", "field"),
    [
        ({"cases": {}}, "cases"),
        ([], "document"),
        ({"cases": [], "defaults": {"params": {"method": "turn"}}}, "params.method"),
        ({"cases": [], "defaults": {"params": {"dt_s": -1}}}, "params.dt_s"),
        ({"cases": [], "defaults": {"params": {"arc_points": 2.5}}}, "params.arc_points"),
        ({"cases": [], "defaults": {"params": {"road": {"nope": 1}}}}, "params.road.nope"),
        ({"cases": [], "defaults": {"track": {"left": [[0, 0]]}}}, "track.left"),
        ({"cases": [], "defaults": {"colour": 1}}, "colour"),
        ({"cases": [], "defaults": {"ego": {"length": 0}}}, "ego.length"),
    ],
)
def test_malformed_document_raises_a_typed_error(document: Any, field: str) -> None:
    with pytest.raises(ReachCaseError) as info:
        list(evaluate_document(document, "x.json"))
    assert info.value.field == field
    assert info.value.source == "x.json"
    assert "\n" not in str(info.value)


def test_without_a_track_every_object_not_behind_is_checked() -> None:
    document = _document()
    del document["defaults"]["track"]
    (record,) = evaluate_document(document)
    direct = _direct("simple", [AHEAD, BEHIND], track=False)
    assert record["checked_ids"] == [str(i) for i in direct.object_ids]
    assert record["safe"] is direct.is_safe


@pytest.mark.parametrize("full_sets", [False, True])
def test_a_case_without_objects_is_safe(full_sets: bool) -> None:
    document = _document(objects=[])
    document["cases"].append(document["cases"][0] | {"id": "d", "objects": [BEHIND]})
    records = list(evaluate_document(document, full_sets=full_sets))
    assert [(r["ok"], r["safe"], r["checked_objects"]) for r in records] == [(True, True, 0)] * 2
    assert records[1]["skipped_ids"] == ["7"]
    if full_sets:
        assert records[0]["sets"]["objects"] == []
