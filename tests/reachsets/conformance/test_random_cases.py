"""Random case documents: every case evaluates, the records equal calling ``evaluate_frames``
directly, and a sequence's records equal one ``evaluate_frames`` call over its steps."""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets import ReachMethod, ReachParams, evaluate_frames
from reachsets.conformance import evaluate_document, random_document
from reachsets.conformance.document import BATCH_CASES
from reachsets.inputs import TrackBounds
from tests.reachsets.conformance.direct import direct_inputs

if TYPE_CHECKING:
    from reachsets.engine import ReachResult


def _inputs(step: dict[str, Any], track: TrackBounds) -> Any:
    return direct_inputs(step["ego"], step["objects"], track=track)


def _expected(result: ReachResult) -> dict[str, Any]:
    """The verdict keys of a record, read straight off the engine's result."""
    return {
        "safe": result.is_safe,
        "collisions": [(c.object_id, c.step) for c in result.collisions],
        "t_offsets": [c.t_offset_s for c in result.collisions],
        "checked_ids": [str(i) for i in result.object_ids],
        "skipped_ids": list(result.skipped_ids),
        "rules": [(p.object_id, p.rule, p.step) for p in result.patches],
    }


def _got(record: dict[str, Any]) -> dict[str, Any]:
    return {
        "safe": record["safe"],
        "collisions": [(c["object_id"], c["step"]) for c in record["collisions"]],
        "t_offsets": [c["t_offset_s"] for c in record["collisions"]],
        "checked_ids": record["checked_ids"],
        "skipped_ids": record["skipped_ids"],
        "rules": [(p["object_id"], p["rule"], p["step"]) for p in record["patches"]],
    }


def _assert_same(record: dict[str, Any], result: ReachResult) -> None:
    want, got = _expected(result), _got(record)
    assert got["t_offsets"] == pytest.approx(want.pop("t_offsets"), abs=1e-6)
    del got["t_offsets"]
    assert got == want
    assert record["checked_objects"] == len(result.object_ids)


@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), full_sets=st.booleans())
def test_random_cases_equal_one_engine_call_per_case(seed: int, full_sets: bool) -> None:
    document = random_document(np.random.default_rng(seed), 7)
    text = json.dumps(document, allow_nan=False)  # a random document is strict JSON
    records = list(evaluate_document(json.loads(text), full_sets=full_sets))
    assert [r["id"] for r in records] == [c["id"] for c in document["cases"]]
    track = TrackBounds(
        document["defaults"]["track"]["left"], document["defaults"]["track"]["right"]
    )
    for case, record in zip(document["cases"], records, strict=True):
        assert record["ok"] is True, record
        params = ReachParams(method=ReachMethod(case["method"]), full_geometry=full_sets)
        (result,), _ = evaluate_frames([_inputs(case, track)], params, None)
        _assert_same(record, result)
        assert 1 <= len(case["objects"]) <= 3
        if full_sets:
            names = [o["object_id"] for o in record["sets"]["objects"]]
            assert names == record["checked_ids"]
        json.dumps(record, allow_nan=False)


@settings(max_examples=8, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), method=st.sampled_from(list(ReachMethod)))
def test_sequences_keep_their_memory(seed: int, method: ReachMethod) -> None:
    document = random_document(np.random.default_rng(seed), 0, methods=[method], sequences=2)
    records = list(evaluate_document(document))
    track = TrackBounds(
        document["defaults"]["track"]["left"], document["defaults"]["track"]["right"]
    )
    at = 0
    for case in document["cases"]:
        steps = case["sequence"]
        results, _ = evaluate_frames(
            [_inputs(s, track) for s in steps],
            ReachParams(method=method, full_geometry=False),
            None,
        )
        for k, result in enumerate(results):
            record = records[at + k]
            assert (record["sequence_id"], record["step"]) == (case["id"], k)
            _assert_same(record, result)
        at += len(steps)
    assert at == len(records)


def test_many_cases_span_several_chunks_and_all_methods() -> None:
    count = BATCH_CASES * 2 + 5
    document = random_document(np.random.default_rng(5), count, sequences=3)
    records = list(evaluate_document(document))
    assert len(records) == count + 3 * 4
    assert all(r["ok"] for r in records)
    assert {r["method"] for r in records} == {m.value for m in ReachMethod}
    unsafe = sum(not r["safe"] for r in records)
    assert 0 < unsafe < len(records)  # the generator makes both kinds of cases
    checked = [r["checked_objects"] for r in records]
    assert max(checked) >= 2


def test_the_generator_is_seeded_and_varied() -> None:
    a = random_document(np.random.default_rng(11), 20)
    b = random_document(np.random.default_rng(11), 20)
    c = random_document(np.random.default_rng(12), 20)
    assert a == b
    assert a != c
    left = np.asarray(a["defaults"]["track"]["left"])
    heading = np.arctan2(*np.diff(left, axis=0).T[::-1])
    assert np.ptp(np.unwrap(heading)) > math.radians(30)  # the strip has a curve
    assert any("t_s" in case["ego"] for case in a["cases"])
    assert any("t_s" not in case["ego"] for case in a["cases"])
