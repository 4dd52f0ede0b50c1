"""Invalid agents are skipped per agent (never a failed frame); exports survive ``ad_rss``."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

import rss
from rss.model import ObjectType
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured import (
    UnstructuredAgents,
    UnstructuredMemory,
    UnstructuredResponse,
    UnstructuredResult,
    check_unstructured,
)
from tests.rss.oracle import load_ad_rss


def _rows(n: int) -> list[dict[str, float]]:
    return [
        {
            "object_id": i + 1,
            "object_type": int(ObjectType.OtherVehicle),
            "x_m": 6.0 + 7.0 * i,
            "y_m": 0.5 * i,
            "yaw_rad": np.pi,
            "speed_min_mps": 0.0,
            "speed_max_mps": 0.0,
            "length_m": 4.0,
            "width_m": 2.0,
        }
        for i in range(n)
    ]


def _ego(speed: float = 0.0, **extra: float) -> UnstructuredAgents:
    row = {**_rows(1)[0], "object_id": 0, "object_type": int(ObjectType.EgoVehicle)}
    row.update(x_m=0.0, y_m=0.0, yaw_rad=0.0, speed_min_mps=speed, speed_max_mps=speed)
    row.update(extra)
    return UnstructuredAgents.from_rows([row])


def _check(
    ego: UnstructuredAgents, agents: UnstructuredAgents, memory: UnstructuredMemory | None = None
) -> tuple[UnstructuredResult, UnstructuredMemory]:
    dyns = [DEFAULT_VEHICLE_DYNAMICS] * len(agents)
    return check_unstructured(ego, agents, DEFAULT_EGO_DYNAMICS, dyns, DEFAULT_EGO_DYNAMICS, memory)


BROKEN = [
    {"x_m": np.nan},
    {"speed_max_mps": np.inf},
    {"speed_min_mps": -1.0},
    {"speed_min_mps": 3.0, "speed_max_mps": 1.0},
    {"yaw_rad": 7.0},
    {"yaw_rate_radps": np.nan},
    {"length_m": 0.0},
    {"object_type": int(ObjectType.ArtificialObject)},
]


@pytest.mark.parametrize("broken", BROKEN, ids=",".join)
def test_an_invalid_agent_is_skipped_and_the_others_answered(broken: dict[str, float]) -> None:
    rows = _rows(3)
    rows[1].update(broken)
    result, _ = _check(_ego(), UnstructuredAgents.from_rows(rows))
    reference, _ = _check(_ego(), UnstructuredAgents.from_rows([rows[0], rows[2]]))
    assert not result.ok
    assert result.valid.tolist() == [True, False, True]
    assert result.decisions.response[1] == UnstructuredResponse.None_
    assert result.decisions.is_safe[1]
    for name in ("response", "is_safe", "heading_begin_rad"):
        np.testing.assert_array_equal(
            getattr(result.decisions, name)[[0, 2]], getattr(reference.decisions, name)
        )
    assert result.proper_response == reference.proper_response
    assert 2 not in result.proper_response.dangerous_objects
    assert not np.isin(result.agent_sets.owner, [1]).any()


def test_invalid_agents_keep_their_memory_and_the_others_update() -> None:
    agents = UnstructuredAgents.from_rows(_rows(2))
    first, memory = _check(_ego(), agents)  # both stopped and close: DriveAway
    assert first.decisions.response.tolist() == [UnstructuredResponse.DriveAway] * 2
    broken = _rows(2)
    broken[0]["x_m"] = np.nan
    broken[1]["x_m"] += 1.0  # the other moved: its drive-away state ends
    second, after = _check(_ego(speed=1.0), UnstructuredAgents.from_rows(broken), memory)
    assert second.valid.tolist() == [False, True]
    assert 1 in after.drive_away_ids.tolist()  # carried over unchanged
    row = after.drive_away_ids.tolist().index(1)
    assert (
        after.heading_begin_rad[row]
        == memory.heading_begin_rad[memory.drive_away_ids.tolist().index(1)]
    )


def test_an_invalid_ego_invalidates_every_agent_without_failing() -> None:
    agents = UnstructuredAgents.from_rows(_rows(2))
    _, memory = _check(_ego(), agents)
    result, after = _check(_ego(yaw_rad=np.nan), agents, memory)
    assert not result.ok
    assert not result.valid.any()
    assert result.proper_response.is_safe
    assert after.drive_away_ids.tolist() == memory.drive_away_ids.tolist()


def test_malformed_tables_raise() -> None:
    with pytest.raises(rss.RssError):
        UnstructuredAgents(**{**dataclasses.asdict(_ego()), "x_m": [0.0, 1.0]})


def test_rss_exports_the_unstructured_entry_points() -> None:
    assert rss.check_unstructured is check_unstructured
    assert {
        "check_unstructured",
        "UnstructuredAgents",
        "UnstructuredResult",
        "UnstructuredMemory",
    } <= set(rss.__all__)


def test_our_subpackage_still_works_after_importing_ad_rss() -> None:
    """The binding sets ``rss.unstructured`` (the attribute) to its own module on import.

    ``sys.modules["rss.unstructured"]``, ``from rss.unstructured import ...`` and the
    top-level exports stay ours; only attribute access ``rss.unstructured.X`` is shadowed.
    """
    load_ad_rss()
    ours = sys.modules["rss.unstructured"]
    assert Path(ours.__file__ or "").parent == Path(rss.__file__ or "").parent / "unstructured"
    from rss.unstructured import check_unstructured as again  # noqa: PLC0415

    assert again is check_unstructured is rss.check_unstructured
    result, _ = _check(_ego(), UnstructuredAgents.from_rows(_rows(1)))
    assert result.ok
