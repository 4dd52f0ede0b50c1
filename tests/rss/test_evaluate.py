"""``rss.evaluate_frames``: one call over ``F`` frames equals scene creation + check per frame."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np

import rss.evaluate
from rss import RssParams, evaluate_frames
from rss.params import ObjectClass
from rss.scene import create_scene, prepare
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from tests.rss.scene.synthetic import WIDTH, ego, objects, straight_road

if TYPE_CHECKING:
    import pytest

    from rss.scene import PreparedGraph, SceneEgo, SceneObjects
    from rss.structured.engine import FrameResult
    from rss.structured.memory import RssMemory

PARAMS = RssParams()
EMPTY = objects()


def _drive() -> list[tuple[SceneEgo, SceneObjects]]:
    """A lead car the ego closes in on, a neighbour, and two frames without anyone."""
    frames = []
    for k in range(8):
        others = objects((70.0 + 0.5 * k, 0.0, 0.0, 4.0), (60.0, -WIDTH, 0.0, 10.0))
        frames.append((ego(50.0 + 1.5 * k, 0.0, speed=15.0), EMPTY if k in {3, 7} else others))
    return frames


def _one_by_one(
    graph: PreparedGraph, frames: list[tuple[SceneEgo, SceneObjects]]
) -> tuple[list[FrameResult | None], RssMemory | None]:
    """Scene creation and ``check_frame`` per frame, the memory forgotten without constellations."""
    default_ego = PARAMS.for_class(ObjectClass.EGO)
    results: list[FrameResult | None] = []
    memory = None
    for ego_state, others in frames:
        scene = create_scene(graph, ego_state, others, PARAMS.scene)
        if not scene.constellations:
            results.append(None)
            memory = None
            continue
        result, memory = check_frame(
            stack_constellations(scene.constellations), default_ego, memory
        )
        results.append(result)
    return results, memory


def _assert_same(got: Any, want: Any, path: str = "") -> None:
    """Equal records of arrays (recursively), or both ``None``."""
    if want is None or got is None:
        assert got is None, path
        assert want is None, path
        return
    if isinstance(want, np.ndarray):
        np.testing.assert_array_equal(got, want, err_msg=path)
        return
    for field in dataclasses.fields(want):
        _assert_same(getattr(got, field.name), getattr(want, field.name), f"{path}.{field.name}")


def test_chunk_equals_frame_by_frame() -> None:
    graph = prepare(straight_road())
    frames = _drive()
    verdicts, memory = evaluate_frames(frames, PARAMS, None, graph=graph)
    want, want_memory = _one_by_one(graph, frames)
    assert len(verdicts) == len(frames)
    assert any(v.result is not None and v.result.dangerous.any() for v in verdicts)
    for verdict, result in zip(verdicts, want, strict=True):
        _assert_same(verdict.result, result)
        count = len(verdict.scene.constellations)
        assert verdict.object_id.shape == verdict.constellation_type.shape == (count,)
        expected_ids = [c.other.object_id for c in verdict.scene.constellations]
        assert verdict.object_id.tolist() == expected_ids
    assert memory is None  # the last frame has no constellation
    assert want_memory is None


def test_restart_with_the_returned_memory() -> None:
    graph = prepare(straight_road())
    frames = _drive()[:7]
    whole, memory = evaluate_frames(frames, PARAMS, None, graph=graph)
    first, middle = evaluate_frames(frames[:5], PARAMS, None, graph=graph)
    rest, end = evaluate_frames(frames[5:], PARAMS, middle, graph=graph)
    assert middle is not None
    assert memory is not None
    _assert_same(end, memory)
    for got, want in zip([*first, *rest], whole, strict=True):
        _assert_same(got.result, want.result)


def test_frames_without_constellations() -> None:
    graph = prepare(straight_road())
    frames = [(ego(50.0, 0.0), EMPTY)] * 3
    verdicts, memory = evaluate_frames(frames, PARAMS, None, graph=graph)
    assert memory is None
    assert [v.result for v in verdicts] == [None] * 3
    assert all(v.object_id.size == 0 for v in verdicts)
    assert evaluate_frames([], PARAMS, None, graph=graph) == ([], None)
    _, memory = evaluate_frames(_drive()[:3], PARAMS, None, graph=graph)
    assert memory is not None
    _, after = evaluate_frames(frames, PARAMS, memory, graph=graph)
    assert after is None  # forgotten after frames without constellations


def test_a_malformed_constellation_is_left_out_with_its_reason_and_the_rest_is_checked(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    graph = prepare(straight_road())
    frames = _drive()[:3]
    good, _ = evaluate_frames(frames, PARAMS, None, graph=graph)
    assert all(len(v.object_id) == 2 for v in good)
    original = create_scene

    def one_bad_lane(*args: Any, **kwargs: Any) -> Any:
        scene = original(*args, **kwargs)
        first = scene.constellations[0]
        seg = first.ego_road[0]
        twice = dataclasses.replace(seg, lanes=(seg.lanes[0], seg.lanes[0], *seg.lanes[1:]))
        broken = dataclasses.replace(first, ego_road=(twice, *first.ego_road[1:]))
        return dataclasses.replace(scene, constellations=(broken, *scene.constellations[1:]))

    monkeypatch.setattr(rss.evaluate, "create_scene", one_bad_lane)
    got, _ = evaluate_frames(frames, PARAMS, None, graph=graph)
    for verdict, reference in zip(got, good, strict=True):
        assert len(verdict.rejected) == 1
        object_id, reason = verdict.rejected[0]
        assert object_id == int(reference.object_id[0])
        assert "lane" in reason
        assert verdict.object_id.tolist() == reference.object_id[1:].tolist()
        assert verdict.result is not None
