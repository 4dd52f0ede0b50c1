"""Assert that a batched multi-frame check equals one-frame checks (shared by two test files)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.params import ObjectClass, RssParams
from rss.unstructured import UnstructuredMemory, check_unstructured, evaluate_frames

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.unstructured import (
        FrameInputs,
        TrajectorySets,
        UnstructuredResult,
    )

__all__ = [
    "GEOMETRY_TOL_M",
    "assert_frames_equal_one_by_one",
    "assert_same_memory",
    "assert_same_polygons",
    "assert_same_result",
    "assert_same_sets",
    "one_by_one",
]

#: Set geometry tolerance [m] (kernels on longer arrays may round the last bit differently).
GEOMETRY_TOL_M = 1e-9


def one_by_one(
    frames: Sequence[FrameInputs], memory: UnstructuredMemory | None = None
) -> tuple[list[UnstructuredResult], UnstructuredMemory | None]:
    """``F`` calls of :func:`check_unstructured`, the memory carried (default ego dynamics)."""
    ego = RssParams().for_class(ObjectClass.EGO)
    results = []
    for f in frames:
        ego_dyn = ego if f.ego_dynamics is None else f.ego_dynamics
        default_ego = ego if f.default_ego is None else f.default_ego
        result, memory = check_unstructured(
            f.ego, f.agents, ego_dyn, f.agent_dynamics, default_ego, memory
        )
        results.append(result)
    return results, memory


def _pieces(sets: TrajectorySets) -> list[tuple[int, bool, np.ndarray]]:
    """Every piece as ``(owner, brake, its points)`` in a canonical order."""
    out = [
        (int(sets.owner[i]), bool(sets.brake[i]), sets.coords[: sets.size[i], i])
        for i in range(sets.owner.size)
    ]
    return sorted(out, key=lambda p: (p[0], p[1], p[2].shape[0], *np.round(p[2], 6).ravel()))


def assert_same_sets(got: TrajectorySets, want: TrajectorySets) -> None:
    """The same pieces (any order), points equal to :data:`GEOMETRY_TOL_M`."""
    assert got.count == want.count
    a, b = _pieces(got), _pieces(want)
    assert [p[:2] for p in a] == [p[:2] for p in b]
    for (_, _, pa), (_, _, pb) in zip(a, b, strict=True):
        np.testing.assert_allclose(pa, pb, rtol=0.0, atol=GEOMETRY_TOL_M)


def assert_same_polygons(got: TrajectorySets, want: TrajectorySets) -> None:
    """The merged sets per agent from the hulls (cached ones included) agree to 1e-9 m²."""
    for brake in (True, False):
        for g, w in zip(got.polygons(brake=brake), want.polygons(brake=brake), strict=True):
            assert shapely.area(shapely.symmetric_difference(g, w)) <= GEOMETRY_TOL_M


def assert_same_result(got: UnstructuredResult, want: UnstructuredResult) -> None:
    """Flags, decisions, proper response equal; sets equal to the tolerance."""
    assert got.ok == want.ok
    np.testing.assert_array_equal(got.valid, want.valid)
    np.testing.assert_array_equal(got.object_id, want.object_id)
    for name in got.decisions.__dataclass_fields__:
        np.testing.assert_array_equal(
            getattr(got.decisions, name), getattr(want.decisions, name), err_msg=name
        )
    assert got.proper_response == want.proper_response
    assert_same_sets(got.ego_sets, want.ego_sets)
    assert_same_sets(got.agent_sets, want.agent_sets)
    assert_same_polygons(got.ego_sets, want.ego_sets)
    assert_same_polygons(got.agent_sets, want.agent_sets)


def assert_same_memory(got: UnstructuredMemory, want: UnstructuredMemory | None) -> None:
    """Every memory field equal (``None`` = empty)."""
    want = want or UnstructuredMemory.empty()
    for name in got.__dataclass_fields__:
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)


def assert_frames_equal_one_by_one(
    frames: Sequence[FrameInputs], memory: UnstructuredMemory | None = None
) -> list[UnstructuredResult]:
    """One batched call equals ``F`` single calls; returns the batched results."""
    batched, memory_after = evaluate_frames(frames, RssParams(), memory)
    single, want_memory = one_by_one(frames, memory)
    assert len(batched) == len(single)
    for got, want in zip(batched, single, strict=True):
        assert_same_result(got, want)
    assert_same_memory(memory_after, want_memory)
    return batched
