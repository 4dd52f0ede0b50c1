"""The shipped example cases: expected values hold and every evaluation agrees with ad-rss;
the per-step conformance path equals the batched multi-frame path."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

from rss.conformance import evaluate_document, frame_record
from rss.conformance.cases import ParsedCase, parse_case, parse_defaults
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from tests.rss.oracle import AdRssOracle, compare_frames, load_ad_rss
from tests.rss.structured.differential import run_random_sequences
from tests.rss.structured.generators import evaluate_ours, random_sequence, renumber

if TYPE_CHECKING:
    from rss.model import Constellation
    from rss.structured.memory import RssMemory

EXAMPLES = (
    Path(__file__).resolve().parents[4]
    / "shared"
    / "conformance"
    / "rss_cases_from_adrss_unit_tests.json"
)


@pytest.fixture(scope="module")
def document() -> dict[str, Any]:
    if not EXAMPLES.exists():
        pytest.skip(f"{EXAMPLES} not present")
    loaded: dict[str, Any] = json.loads(EXAMPLES.read_text())
    return loaded


def _pair(parsed: ParsedCase) -> Constellation:
    assert parsed.constellation is not None
    return parsed.constellation


def test_expected_values_hold(document: dict[str, Any]) -> None:
    records = list(evaluate_document(document))
    assert len(records) == 21
    checked = [r for r in records if "expected_check" in r]
    assert len(checked) == 20  # incl. 3 unstructured ones (rss.unstructured)
    assert all(r["expected_check"]["passed"] for r in checked), [
        r for r in checked if not r["expected_check"]["passed"]
    ]
    assert all(r["ok"] for r in records if r["kind"] == "unstructured")


def test_reference_answers_of_notes(document: dict[str, Any]) -> None:
    by_id = {r["id"]: r for r in evaluate_document(document)}
    gap58 = by_id["sd_follow_50kmh_gap58_unsafe"]
    assert gap58["states"][0]["longitudinal"]["safe_distance"] == pytest.approx(59.722994, abs=1e-6)
    assert gap58["proper_response"]["acceleration_restrictions"] == {
        "longitudinal": [-8.0, -4.0],
        "lateral_left": [-1000.0, 0.2],
        "lateral_right": [-1000.0, 0.2],
    }
    od = by_id["od_50kmh_gap196_brake_min_correct"]["states"][0]["longitudinal"]
    assert od["safe_distance"] == pytest.approx(196.823047, abs=1e-5)
    assert by_id["lat_cut_in_sequence#1"]["states"][0]["lateral_right"][
        "safe_distance"
    ] == pytest.approx(1.90625)
    step1 = by_id["intersection_ego_prio_sequence#1"]["proper_response"]
    assert step1["longitudinal_response"] == "None"
    assert step1["acceleration_restrictions"]["longitudinal"] == [-8.0, 2.0]


@pytest.mark.oracle
def test_examples_agree_with_ad_rss(document: dict[str, Any]) -> None:
    load_ad_rss()
    defaults = parse_defaults(document)
    records = iter(evaluate_document(document))
    compared = 0
    for case in document["cases"]:
        steps = case["steps"] if case["kind"] == "sequence" else [case]
        oracle = AdRssOracle()
        for k, step in enumerate(steps):
            record = next(records)
            if step["kind"] != "structured":
                continue
            parsed = parse_case(
                step, defaults, record["id"], None if len(steps) == 1 else case["id"], k
            )
            assert parsed.constellation is not None
            diffs = compare_frames(record, oracle.step([parsed.constellation], parsed.default_ego))
            assert not diffs, (record["id"], diffs)
            compared += 1
    assert compared == 12


def test_step_by_step_equals_multi_frame_batch() -> None:
    defaults = parse_defaults({})
    rng = np.random.default_rng(99)
    for i in range(25):
        seq = random_sequence(rng, defaults, f"s{i}", 6)
        stepwise = list(evaluate_document({"cases": [seq]}))
        parsed = [
            renumber(parse_case(s, defaults, "x", "s", k), 0, 1) for k, s in enumerate(seq["steps"])
        ]
        batched = evaluate_ours(parsed)
        for a, b in zip(stepwise, batched, strict=True):
            assert a["states"] == b["states"]
            assert a["proper_response"] == b["proper_response"]


def test_restart_from_stored_memory_equals_full_replay() -> None:
    """A replay restarted at step k with the memory after step k-1 gives the same answers."""
    defaults = parse_defaults({})
    rng = np.random.default_rng(3)
    for i in range(20):
        seq = random_sequence(rng, defaults, f"s{i}", 6)
        batches = [
            stack_constellations([_pair(parse_case(s, defaults, "x"))]) for s in seq["steps"]
        ]
        memory: RssMemory | None = None
        full: list[dict[str, Any]] = []
        memories: list[RssMemory | None] = []
        for b in batches:
            memories.append(memory)
            result, memory = check_frame(b, defaults.ego, memory)
            full.append(frame_record(result, b))
        k = int(rng.integers(1, 6))
        result, _ = check_frame(batches[k], defaults.ego, memories[k])
        assert frame_record(result, batches[k]) == full[k]


def test_run_random_sequences_smoke() -> None:
    load_ad_rss()
    report = run_random_sequences(1, 5)
    assert not report.failures
