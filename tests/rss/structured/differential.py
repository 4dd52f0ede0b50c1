"""Differential harness: random cases / sequences, our engine (batched) vs ad-rss.

Reusable from tests and by hand::

    RSS_FUZZ_SEED=1234 .venv/bin/pytest tests/rss -k fuzz_seed
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rss.conformance.cases import CaseDefaults, ParsedCase, parse_case, parse_defaults
from tests.rss.oracle import AdRssOracle, compare_frames
from tests.rss.structured.generators import evaluate_ours, random_cases, random_sequence, renumber

__all__ = ["Report", "run_random_cases", "run_random_sequences"]


@dataclass
class Report:
    """Outcome of a differential run."""

    cases: int = 0
    steps: int = 0
    dangerous: int = 0
    types: dict[str, int] = field(default_factory=dict)
    max_safe_distance_error_m: float = 0.0
    failures: list[str] = field(default_factory=list)

    def add(
        self, case_id: str, ours: dict[str, Any], diffs: list[str], oracle_states: dict[int, Any]
    ) -> None:
        """Record one compared frame."""
        self.steps += 1
        for st in ours["states"]:
            self.types[st["constellation_type"]] = self.types.get(st["constellation_type"], 0) + 1
            self.dangerous += int(st["is_dangerous"])
            ref = oracle_states.get(st["object_id"])
            if ref is None:
                continue
            for side in ("longitudinal", "lateral_left", "lateral_right"):
                a, b = st[side]["safe_distance"], ref[side]["safe_distance"]
                if a is not None and b is not None:
                    self.max_safe_distance_error_m = max(self.max_safe_distance_error_m, abs(a - b))
        if diffs:
            self.failures.append(f"{case_id}: {diffs}")


def run_random_cases(seed: int, count: int, defaults: CaseDefaults | None = None) -> Report:
    """Generate ``count`` cases with ``seed`` and compare every one with ad-rss."""
    defaults = defaults or parse_defaults({})
    rng = np.random.default_rng(seed)
    cases = random_cases(rng, defaults, count)
    parsed = [
        renumber(parse_case(c, defaults, c["id"]), 2 * i, 2 * i + 1) for i, c in enumerate(cases)
    ]
    ours = evaluate_ours(parsed)
    oracle = AdRssOracle()
    report = Report(cases=count)
    for case, p, record in zip(cases, parsed, ours, strict=True):
        assert p.constellation is not None
        frame = oracle.step([p.constellation], p.default_ego)
        report.add(
            f"seed {seed} {case['id']} {case}", record, compare_frames(record, frame), frame.states
        )
    return report


def run_random_sequences(seed: int, count: int, defaults: CaseDefaults | None = None) -> Report:
    """Generate ``count`` sequences (3-8 steps) and compare every step with ad-rss; ours
    evaluates all sequences in one multi-frame engine call."""
    defaults = defaults or parse_defaults({})
    rng = np.random.default_rng(seed)
    sequences = [
        random_sequence(rng, defaults, f"seq{i}", int(rng.integers(3, 9))) for i in range(count)
    ]
    parsed: list[ParsedCase] = []
    frames: list[int] = []
    for j, seq in enumerate(sequences):
        for k, step in enumerate(seq["steps"]):
            parsed.append(
                renumber(
                    parse_case(step, defaults, f"{seq['id']}#{k}", seq["id"], k), 2 * j, 2 * j + 1
                )
            )
            frames.append(len(frames))
    ours = iter(evaluate_ours(parsed, np.asarray(frames)))
    report = Report(cases=count)
    steps = iter(parsed)
    for seq in sequences:
        oracle = AdRssOracle()
        for _ in seq["steps"]:
            p, record = next(steps), next(ours)
            assert p.constellation is not None
            frame = oracle.step([p.constellation], p.default_ego)
            report.add(
                f"seed {seed} {p.case_id} {seq}",
                record,
                compare_frames(record, frame),
                frame.states,
            )
    return report
