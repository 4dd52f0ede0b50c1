"""Seeded random multi-step sequences vs the ad-rss binding (memory: 22.1b, drive-away)."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest
import shapely

from rss.params import DEFAULT_EGO_DYNAMICS
from rss.unstructured import UnstructuredResponse, check_unstructured
from tests.rss.oracle import load_ad_rss
from tests.rss.oracle_unstructured import UnstructuredAnswer, UnstructuredOracle
from tests.rss.unstructured.generators import random_sequence

SEQUENCES = 50
STEPS = 4
AGENTS = 2


def _fell_back(ref: UnstructuredAnswer) -> bool:
    """ad-rss replaced some continue-forward set by the brake set (its union failed)."""
    pairs = [(ref.ego_continue, ref.ego_brake)]
    pairs += [(ref.continue_forward[o], ref.brake[o]) for o in ref.brake]
    return any(shapely.equals(f, b) for f, b in pairs)


@pytest.fixture(autouse=True)
def _binding() -> None:
    load_ad_rss()


def test_random_sequences_agree_with_the_binding_step_by_step() -> None:
    seen: Counter[str] = Counter()
    compared = 0
    for seed in range(SEQUENCES):
        rng = np.random.default_rng(5000 + seed)
        oracle, memory = UnstructuredOracle(), None
        for step, (ego, agents, dynamics) in enumerate(random_sequence(rng, STEPS, AGENTS)):
            ref = oracle.evaluate(ego, agents, DEFAULT_EGO_DYNAMICS, dynamics, DEFAULT_EGO_DYNAMICS)
            ours, memory = check_unstructured(
                ego, agents, DEFAULT_EGO_DYNAMICS, dynamics, DEFAULT_EGO_DYNAMICS, memory
            )
            if not ref.ok or _fell_back(ref):
                # ad-rss union failure (docs: deviations): the frame failed, or T(C_f) fell
                # back to T(C_b), which changes the remembered 22.1b; the memories differ
                # from here on
                seen["binding union failure"] += 1
                break
            where = (seed, step)
            d = ours.decisions
            for i, oid in enumerate(agents.object_id):
                theirs = ref.states[int(oid)]
                mine = str(UnstructuredResponse(int(d.response[i])))
                assert (mine, bool(d.is_safe[i])) == (theirs["response"], theirs["is_safe"]), (
                    where,
                    int(oid),
                )
                if theirs["heading_range"] is not None:
                    assert [d.heading_begin_rad[i], d.heading_end_rad[i]] == pytest.approx(
                        theirs["heading_range"], abs=1e-9
                    ), where
                unsafe_conditions = not (
                    d.ego_must_brake[i] or d.other_must_brake[i] or d.both_brake_safe[i]
                )
                if mine == "DriveAway" and not (
                    ego.speed_max_mps[0] <= 0.1 and agents.speed_max_mps[i] <= 0.1
                ):
                    seen["drive-away kept or rule 2"] += 1
                if mine == "ContinueForward" and unsafe_conditions:
                    seen["rule 2 continue forward"] += 1
                seen[mine] += 1
                compared += 1
            pr = ref.proper_response
            assert (
                ours.proper_response.response
                == UnstructuredResponse[pr["response"].replace("None", "None_")]
            ), where
            assert [ours.proper_response.lon_min_mps2, ours.proper_response.lon_max_mps2] == (
                pytest.approx(pr["longitudinal"])
            ), where
            flat = [a for r in ours.proper_response.heading_ranges for a in r]
            assert flat == pytest.approx([a for r in pr["heading_ranges"] for a in r], abs=1e-9), (
                where
            )
    print(dict(seen))  # noqa: T201  (coverage of the memories, shown with -s)
    assert seen["binding union failure"] <= SEQUENCES // 10, seen
    assert compared >= SEQUENCES * STEPS * AGENTS * 0.8, seen
    # the memories were exercised, not just fresh decisions
    assert seen["DriveAway"] > 0, seen
    assert seen["drive-away kept or rule 2"] > 0, seen
    assert seen["Brake"] > 0, seen
