"""The conformance command's fast paths against the general ones they replace.

``cases._inputs`` builds the engine inputs of a parsed case without a second validation; it
must give the arrays ``reach_inputs_from_arrays`` gives (same dtypes, values to the bit,
read-only). ``records.set_outlines`` reads the outlines of the clipper's cells straight from
its rings (``ReachResult.rings``); they must be the points the shapely geometries hold, to
the bit, and every cell flagged exact must be one (rule patches and GEOS cells are not).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets import ReachMethod, evaluate_frames
from reachsets.conformance import parse_case, parse_defaults, random_document
from reachsets.conformance.document import prepare_document, unique_ids
from reachsets.conformance.records import _geometry_outlines, _ring_outlines, set_outlines
from reachsets.errors import InputShapeError
from reachsets.inputs import ObjectStates
from tests.reachsets.conformance.direct import direct_inputs

_COORD = st.floats(-500.0, 500.0, allow_nan=False)
_SPEED = st.one_of(st.floats(-5.0, 40.0, allow_nan=False), st.just(-0.0), st.just(0))
_SIZE = st.one_of(st.none(), st.floats(0.1, 10.0), st.just(3))


@st.composite
def _case(draw: Any) -> dict[str, Any]:
    k = draw(st.integers(1, 6))
    ego = {key: draw(st.lists(_COORD, min_size=k, max_size=k)) for key in ("x", "y", "heading")}
    ego["speed"] = draw(st.lists(_SPEED, min_size=k, max_size=k))
    if draw(st.booleans()):
        ego["t_s"] = sorted(draw(st.lists(st.floats(0.0, 10.0), min_size=k, max_size=k)))
    if draw(st.booleans()):
        ego["length"] = draw(st.floats(1.0, 6.0))
    objects = []
    for n in range(draw(st.integers(0, 3))):
        obj = {"id": draw(st.sampled_from([f"o{n}", n, f"car-{n}-long-name"]))}
        obj |= {key: draw(_COORD) for key in ("x", "y", "yaw")} | {"speed": draw(_SPEED)}
        for key in ("length", "width"):
            size = draw(_SIZE)
            if size is not None:
                obj[key] = size
        objects.append(obj)
    return {"id": "c", "ego": ego, "objects": objects}


def _adapter(case: dict[str, Any], length_m: float, width_m: float) -> Any:
    ego = case["ego"]
    return direct_inputs(
        ego,
        case["objects"],
        ego_length_m=ego.get("length", length_m),
        ego_width_m=ego.get("width", width_m),
    )


def _same_array(got: Any, want: Any) -> None:
    assert isinstance(got, np.ndarray)
    assert got.dtype == want.dtype
    assert got.shape == want.shape
    assert not got.flags.writeable
    if got.dtype.kind == "f":  # to the bit, the sign of zero and NaN included
        assert got.tobytes() == want.tobytes()
    else:
        assert got.tolist() == want.tolist()


@settings(max_examples=200, deadline=None)
@given(_case())
def test_parsed_inputs_are_the_adapters(case: dict[str, Any]) -> None:
    defaults = parse_defaults({"defaults": {}})
    got = parse_case(case, defaults, 0).steps[0].inputs
    want = _adapter(case, defaults.ego_length_m, defaults.ego_width_m)
    for part in ("ego", "objects"):
        for field in dataclasses.fields(getattr(want, part)):
            a, b = getattr(getattr(got, part), field.name), getattr(getattr(want, part), field.name)
            if isinstance(b, np.ndarray):
                _same_array(a, b)
            else:
                assert a == b
                assert type(a) is type(b)
    assert got.track is None


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), method=st.sampled_from(list(ReachMethod)))
def test_ring_outlines_are_the_geometries_points(seed: int, method: ReachMethod) -> None:
    document = random_document(np.random.default_rng(seed), 24, methods=[method])
    prepared = prepare_document(document, "random", full_sets=True)
    defaults = prepared.defaults
    cases = [parse_case(c, defaults, k) for k, c in enumerate(prepared.cases)]
    inputs = [unique_ids(c.steps[0].inputs, f"{k}/") for k, c in enumerate(cases)]
    results, _ = evaluate_frames(inputs, defaults.params[method], defaults.start)
    exact_cells = 0
    for result in results:
        rings = result.rings
        assert rings is not None  # a track: every set went through the clipper
        cells = _ring_outlines(rings.cells, rings.start, rings.stop)
        shapes = _geometry_outlines(result.reach_sets.reshape(-1))
        exact = rings.cells.exact[rings.start : rings.stop].tolist()
        assert len(cells) == len(shapes) == len(exact)
        for ring_cell, shape_cell, is_exact in zip(cells, shapes, exact, strict=True):
            if is_exact:
                exact_cells += 1
                assert ring_cell == shape_cell  # floats compared exactly
        record = set_outlines(result, str)
        flat = [cell for obj in record["objects"] for cell in obj["outlines"]]
        assert flat == shapes
    assert exact_cells > 0


def test_of_frozen_shares_read_only_columns_and_refuses_writable_ones() -> None:
    column = np.array([1.0, 2.0])
    column.flags.writeable = False
    names = np.array(["a", "b"], dtype=np.str_)
    names.flags.writeable = False
    fields = [f.name for f in dataclasses.fields(ObjectStates)]
    objects = ObjectStates.of_frozen({f: names if f == "ids" else column for f in fields})
    assert objects.x_m is column
    assert len(objects) == 2
    with pytest.raises(InputShapeError, match="read-only"):
        ObjectStates.of_frozen({"ids": names, "x_m": np.array([1.0, 2.0])})
