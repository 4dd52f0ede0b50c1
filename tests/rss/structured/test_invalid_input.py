"""Wrong input gives a typed error (structure) or a per-object invalid flag (values)."""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import numpy as np
import pytest

from rss.conformance import evaluate_document
from rss.conformance.cases import parse_case, parse_defaults
from rss.errors import RssCaseError, RssConstellationError
from rss.model import Constellation, LaneSegment, RoadSegment, SpeedInterval
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from rss.structured.states import InvalidReason

CASE: dict[str, Any] = {
    "id": "base",
    "kind": "structured",
    "constellation_type": "SameDirection",
    "road": {"length": 1000, "lane_widths": [3.5, 3.5]},
    "ego": {"s": 100, "y": 1.75, "length": 4, "width": 2, "v_lon": 10},
    "other": {"s": 150, "y": 1.75, "length": 4, "width": 2, "v_lon": 10},
}


def _constellation(case: dict[str, Any] | None = None) -> Constellation:
    parsed = parse_case(case or CASE, parse_defaults({}), "x")
    assert parsed.constellation is not None
    return parsed.constellation


def test_unknown_constellation_type_case() -> None:
    with pytest.raises(RssCaseError, match="unknown constellation_type"):
        parse_case(CASE | {"constellation_type": "Sideways"}, parse_defaults({}), "x")
    (record,) = evaluate_document({"cases": [CASE | {"constellation_type": "Sideways"}]})
    assert record["ok"] is False
    assert "Sideways" in record["error"]


def test_unknown_constellation_type_code() -> None:
    bad = dataclasses.replace(_constellation(), constellation_type=17)  # type: ignore[arg-type]
    with pytest.raises(RssConstellationError, match="constellation_type"):
        stack_constellations([bad])


def test_negative_lane_length() -> None:
    c = _constellation()
    lane = dataclasses.replace(c.ego_road[0].lanes[0], length_min_m=-5.0)
    road = (RoadSegment((lane, *c.ego_road[0].lanes[1:])),)
    with pytest.raises(RssConstellationError, match="length"):
        stack_constellations([dataclasses.replace(c, ego_road=road)])
    with pytest.raises(RssConstellationError, match="width"):
        stack_constellations(
            [dataclasses.replace(c, ego_road=(RoadSegment((LaneSegment(1, 1, 10, 10, 3, 2),)),))]  # type: ignore[arg-type]
        )


def test_brake_of_wrong_sign_in_case() -> None:
    (record,) = evaluate_document({"cases": [CASE | {"ego_dynamics": {"brake_min": 4.0}}]})
    assert record["ok"] is False
    assert "brakes are negative" in record["error"]


@pytest.mark.parametrize(
    ("speed", "reason"),
    [
        (SpeedInterval(math.nan, 10.0, 0.0, 0.0), InvalidReason.NonFiniteValue),
        (SpeedInterval(-1.0, 10.0, 0.0, 0.0), InvalidReason.SpeedOutOfRange),
        (SpeedInterval(5.0, 4.0, 0.0, 0.0), InvalidReason.SpeedOutOfRange),
        (SpeedInterval(0.0, 150.0, 0.0, 0.0), InvalidReason.SpeedOutOfRange),
    ],
)
def test_invalid_object_values_are_flagged(speed: SpeedInterval, reason: InvalidReason) -> None:
    good = _constellation()
    bad = dataclasses.replace(good, other=dataclasses.replace(good.other, object_id=2, speed=speed))
    result, _ = check_frame(stack_constellations([good, bad]), parse_defaults({}).ego)
    assert list(result.invalid) == [0, reason]
    assert not result.dangerous[1]


def test_object_outside_road_and_nan_position() -> None:
    off = CASE | {"other": CASE["other"] | {"s": 5000}}
    nan = json.loads(json.dumps(CASE | {"other": CASE["other"] | {"v_lon": float("nan")}}))
    records = list(evaluate_document({"cases": [off, nan]}))
    assert [r["ok"] for r in records] == [False, False]
    assert "NotInRoadArea" in records[0]["error"]
    assert "NonFiniteValue" in records[1]["error"]


def test_malformed_documents() -> None:
    with pytest.raises(RssCaseError):
        list(evaluate_document({"no_cases": []}))
    records = list(evaluate_document({"cases": [{"kind": "wormhole"}, {"kind": "structured"}]}))
    assert all(r["ok"] is False for r in records)


def test_empty_frame() -> None:
    batch = stack_constellations([])
    result, memory = check_frame(batch, parse_defaults({}).ego)
    assert bool(result.responses.is_safe[0])
    assert memory.size == 0
    assert np.isclose(result.responses.lon_max_mps2[0], 3.5)
