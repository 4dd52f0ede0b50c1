"""Multi-object frames and multi-object drives against ad-rss; an invalid object is
skipped without failing the other objects of its frame."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rss.conformance.cases import ParsedCase, parse_case, parse_defaults
from rss.model import SpeedInterval
from tests.rss.oracle import AdRssOracle, compare_frames, load_ad_rss
from tests.rss.structured.generators import evaluate_ours, random_case, random_sequence, renumber

pytestmark = pytest.mark.oracle


def _frame_of(parsed: list[ParsedCase]) -> list[ParsedCase]:
    """One ego (id 0) with many others (ids 1..N)."""
    return [renumber(p, 0, i + 1) for i, p in enumerate(parsed)]


def test_multi_object_frames_agree() -> None:
    load_ad_rss()
    defaults = parse_defaults({})
    rng = np.random.default_rng(2024)
    for _ in range(40):
        oracle = AdRssOracle()  # independent frames: no shared history
        n = int(rng.integers(1, 40))
        parsed = _frame_of(
            [parse_case(random_case(rng, defaults, "c"), defaults, "c") for _ in range(n)]
        )
        (record,) = evaluate_ours(parsed, np.zeros(n, dtype=np.int64))
        frame = oracle.step([p.constellation for p in parsed if p.constellation], defaults.ego)
        assert not compare_frames(record, frame)


def test_multi_object_drive_agrees() -> None:
    """T frames of N objects: ours in ONE multi-frame call, ad-rss step by step."""
    load_ad_rss()
    defaults = parse_defaults({})
    rng = np.random.default_rng(77)
    for _ in range(6):
        n, steps = int(rng.integers(2, 12)), 6
        sequences = [random_sequence(rng, defaults, f"s{j}", steps) for j in range(n)]
        parsed, frames = [], []
        for t in range(steps):
            frame = _frame_of([parse_case(seq["steps"][t], defaults, "x") for seq in sequences])
            parsed += frame
            frames += [t] * n
        records = evaluate_ours(parsed, np.asarray(frames))
        oracle = AdRssOracle()
        for t in range(steps):
            answer = oracle.step(
                [p.constellation for p in parsed[t * n : (t + 1) * n] if p.constellation],
                defaults.ego,
            )
            assert not compare_frames(records[t], answer), t


def test_invalid_object_is_skipped_not_fatal() -> None:
    load_ad_rss()
    defaults = parse_defaults({})
    rng = np.random.default_rng(5)
    parsed = _frame_of(
        [parse_case(random_case(rng, defaults, "c"), defaults, "c") for _ in range(8)]
    )
    bad = parsed[3].constellation
    assert bad is not None
    broken = dataclasses.replace(
        bad, other=dataclasses.replace(bad.other, speed=SpeedInterval(float("nan"), 1.0, 0.0, 0.0))
    )
    with_bad = [*parsed[:3], dataclasses.replace(parsed[3], constellation=broken), *parsed[4:]]
    (record,) = evaluate_ours(with_bad, np.zeros(8, dtype=np.int64))
    flagged = [s for s in record["states"] if s["invalid"]]
    assert [s["object_id"] for s in flagged] == [4]
    assert flagged[0]["invalid"] == "NonFiniteValue"
    assert not flagged[0]["is_dangerous"]
    # ad-rss fails the whole world; without the bad object it agrees with our other answers
    assert (
        not AdRssOracle()
        .step([p.constellation for p in with_bad if p.constellation], defaults.ego)
        .ok
    )
    rest = [p for i, p in enumerate(parsed) if i != 3]
    answer = AdRssOracle().step([p.constellation for p in rest if p.constellation], defaults.ego)
    record["states"] = [s for s in record["states"] if not s["invalid"]]
    assert not compare_frames(record, answer)
