"""``evaluate_document`` batches independent cases: the same records as one by one.

Each chunk's independent structured cases go through one multi-frame engine call (each
case its own frame, its ego renumbered so no memory carries between cases), its
independent unstructured cases through one ``evaluate_frames`` call (the other object
renumbered); sequences run step by step with their memory. The records must equal those
of the per-case path, in document order, malformed and rejected cases included.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest

from rss.conformance import document as doc_module
from rss.conformance import evaluate_document
from rss.conformance import unstructured as unstructured_module
from rss.conformance.cases import parse_defaults
from rss.structured.engine import check_frames
from rss.unstructured import evaluate_frames
from tests.rss.structured.generators import random_cases, random_sequence
from tests.rss.unstructured.generators import random_case


def _document(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    defaults = parse_defaults({})
    cases: list[Any] = []
    for i, case in enumerate(random_cases(rng, defaults, 60)):
        cases.append(case)
        if i % 9 == 0:
            cases.append(random_sequence(rng, defaults, f"seq{i}", 4))
        if i % 7 == 0:
            cases.append(random_case(rng, f"u{i}"))
    rejected = copy.deepcopy(next(c for c in cases if "road" in c))
    rejected["id"] = "negative-width"
    rejected["road"]["lane_widths"] = [-3.5] * len(rejected["road"]["lane_widths"])
    broken = random_case(rng, "broken-unstructured")
    broken["other"]["speed_min"] = -1.0  # invalid input: ok false from the engine
    malformed = random_case(rng, "malformed-unstructured")
    malformed["ego"].pop("x")
    cases[5:5] = [rejected, ["not", "a", "case"], broken, malformed]
    cases.insert(30, {"id": "unknown", "kind": "structured", "constellation_type": "Nope"})
    return {"cases": cases}


def _records(
    document: dict[str, Any], monkeypatch: pytest.MonkeyPatch, **names: int
) -> list[dict[str, Any]]:
    with monkeypatch.context() as patch:
        for name, value in names.items():
            patch.setattr(doc_module, name, value)
        return list(evaluate_document(document))


@pytest.mark.parametrize("seed", [11, 12])
def test_batched_records_equal_the_case_by_case_records(seed, monkeypatch) -> None:
    document = _document(seed)
    one_by_one = _records(document, monkeypatch, BATCH_MIN_CASES=10**9)
    assert _records(document, monkeypatch) == one_by_one
    assert _records(document, monkeypatch, BATCH_CASES=13, BATCH_MIN_CASES=2) == one_by_one
    errors = {r["id"]: r["error"] for r in one_by_one if not r["ok"]}
    assert "width" in errors["negative-width"]
    assert "Nope" in errors["unknown"]
    assert "invalid input" in errors["broken-unstructured"]
    assert "'x'" in errors["malformed-unstructured"]


def test_one_engine_call_per_chunk(monkeypatch) -> None:
    """The structured cases of a chunk really go through one multi-frame call."""
    document = {"cases": [c for c in _document(13)["cases"] if isinstance(c, dict)]}
    document["cases"] = [c for c in document["cases"] if c.get("id") != "negative-width"]
    calls: list[int] = []
    engine = check_frames

    def counting(batch, frame, n_frames, *args, **kwargs):
        calls.append(n_frames)
        return engine(batch, frame, n_frames, *args, **kwargs)

    frames: list[int] = []
    unstructured_engine = evaluate_frames

    def counting_frames(inputs, *args, **kwargs):
        frames.append(len(inputs))
        return unstructured_engine(inputs, *args, **kwargs)

    monkeypatch.setattr(doc_module, "check_frames", counting)
    monkeypatch.setattr(unstructured_module, "evaluate_frames", counting_frames)
    records = list(evaluate_document(document))
    structured = [c for c in document["cases"] if c.get("kind") == "structured"]
    assert calls == [len(structured) - 1]  # the malformed one is not parsed
    unstructured = sum(c.get("kind") == "unstructured" for c in document["cases"])
    assert frames == [unstructured - 1]  # the malformed one is left to the per-case path
    assert len(records) == len(document["cases"]) + sum(
        len(c["steps"]) - 1 for c in document["cases"] if c.get("kind") == "sequence"
    )
