"""The small-frame path (``rss.structured.small``) against the batched engine.

``check_frame`` evaluates frames of up to ``SMALL_FRAME_MAX`` constellations row by row;
every field of its result and memory must equal what ``check_frames`` computes for the
same frame and memory (integers and flags exactly, distances within 1e-9 m: nothing here
depends on this CPU's last bits). Frames the small path does not cover (an invalid row,
the ego's id as an object's) must be handed to the batched engine.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rss.conformance.cases import ParsedCase, parse_case, parse_defaults
from rss.model import Constellation, SpeedInterval
from rss.structured.batch import take_rows
from rss.structured.engine import FrameResult, check_frame, check_frames
from rss.structured.memory import RssMemory
from rss.structured.small import SMALL_FRAME_MAX, check_frame_small
from rss.structured.small_input import packed
from rss.structured.small_output import recall
from rss.structured.stacking import stack_constellations
from rss.structured.standstill import apply_standstill
from tests.rss.structured.generators import random_case, random_sequence, renumber

_DEFAULTS = parse_defaults({})
_STILL_MPS = 3.0  # standstill threshold of the random drives: some objects stand, some move


def _fields(record: Any, prefix: str = "") -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for field in dataclasses.fields(record):
        value = getattr(record, field.name)
        if dataclasses.is_dataclass(value):
            out |= _fields(value, f"{prefix}{field.name}.")
        elif value is not None:
            out[prefix + field.name] = value
    return out


def _assert_same(ours: Any, batched: Any) -> None:
    a, b = _fields(ours), _fields(batched)
    assert a.keys() == b.keys()
    for name, value in a.items():
        expected = b[name]
        assert value.dtype == expected.dtype, name
        assert value.shape == expected.shape, name
        if value.dtype.kind == "f":
            np.testing.assert_allclose(value, expected, rtol=0.0, atol=1e-9, err_msg=name)
        else:
            np.testing.assert_array_equal(value, expected, err_msg=name)


def _batched(frame: list[Constellation], memory: RssMemory | None) -> tuple[FrameResult, RssMemory]:
    batch = stack_constellations(frame)
    return check_frames(batch, np.zeros(batch.size, dtype=np.int64), 1, _DEFAULTS.ego, memory)


def _one_ego(parsed: list[ParsedCase]) -> list[Constellation]:
    """One ego (id 0) with the others numbered 1..N."""
    out = []
    for i, p in enumerate(parsed):
        c = renumber(p, 0, i + 1).constellation
        assert c is not None
        out.append(c)
    return out


def _drive(seed: int, n_objects: int, steps: int) -> list[list[Constellation]]:
    rng = np.random.default_rng(seed)
    sequences = [random_sequence(rng, _DEFAULTS, f"s{j}", steps) for j in range(n_objects)]
    return [
        _one_ego([parse_case(seq["steps"][t], _DEFAULTS, "x") for seq in sequences])
        for t in range(steps)
    ]


def _plain(memory: RssMemory) -> RssMemory:
    """The same memory as a plain :class:`RssMemory` (as the batched engine returns one)."""
    return RssMemory(**{f.name: getattr(memory, f.name) for f in dataclasses.fields(RssMemory)})


@settings(max_examples=60, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(1, 24),
    st.integers(1, 5),
    st.sampled_from(["stacking", "arrays", "standstill"]),
    st.booleans(),
)
def test_drive_frame_by_frame_equals_batched(
    seed: int, n_objects: int, steps: int, via: str, plain_memory: bool
) -> None:
    """Random drives (all constellation types), memory carried frame by frame on both paths.

    The row path reads the rows the stacking step packed, or (a batch it did not stack)
    the batch's arrays, or (the standstill rule's copy of a stacked batch) the stacked
    rows with the copy's types and dynamics; the memory goes back as returned or as a
    plain ``RssMemory``.
    """
    ours_memory: RssMemory | None = None
    batched_memory: RssMemory | None = None
    for frame in _drive(seed, n_objects, steps):
        stacked = stack_constellations(frame)
        batch = stacked
        if via == "arrays":  # a new batch object: no packed rows kept for it
            batch = take_rows(batch, np.arange(batch.size))
        if via == "standstill":
            batch = apply_standstill(stacked, _STILL_MPS)
            if batch is not stacked:  # objects and road areas packed once, shared
                assert packed(batch).lanes is packed(stacked).lanes
        if plain_memory and ours_memory is not None:
            ours_memory = _plain(ours_memory)
        ours, ours_memory = check_frame(batch, _DEFAULTS.ego, ours_memory)
        batched, batched_memory = check_frames(
            batch, np.zeros(batch.size, dtype=np.int64), 1, _DEFAULTS.ego, batched_memory
        )
        _assert_same(ours, batched)
        _assert_same(ours_memory, batched_memory)


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 12), st.permutations(range(6)))
def test_fields_read_in_any_order(seed: int, n_objects: int, order: list[int]) -> None:
    """Each field of a small frame's result, read first or last, equals the batched one."""
    frame = _drive(seed, n_objects, 1)[0]
    ours, _ = check_frame(stack_constellations(frame), _DEFAULTS.ego)
    batched, _ = _batched(frame, None)
    names = [f.name for f in dataclasses.fields(FrameResult)][:6]
    for k in order:
        a, b = getattr(ours, names[k]), getattr(batched, names[k])
        if isinstance(a, np.ndarray):
            np.testing.assert_array_equal(a, b, err_msg=names[k])
        else:
            _assert_same(a, b)
    assert ours.responsibility is None
    assert ours.severity is None


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 12))
def test_valid_frames_take_the_small_path(seed: int, n_objects: int) -> None:
    """A frame of valid constellations with distinct keys is evaluated row by row."""
    rng = np.random.default_rng(seed)
    parsed = [
        parse_case(random_case(rng, _DEFAULTS, "c"), _DEFAULTS, "c") for _ in range(n_objects)
    ]
    frame = _one_ego(parsed)
    batch = stack_constellations(frame)
    batched, _ = _batched(frame, None)
    if (batched.invalid == 0).all():
        assert check_frame_small(batch, _DEFAULTS.ego, {}) is not None
    assert n_objects <= SMALL_FRAME_MAX


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(1, 12),
    st.integers(1, 4),
    st.integers(0, 11),
    st.sampled_from(["same", "wider"]),
)
def test_similar_rows_merged_as_batched(
    seed: int, n_objects: int, steps: int, which: int, how: str
) -> None:
    """Two rows of one key (the same, or speeds widened): merged as the batched engine does.

    Every such frame of valid rows takes the row path (``rss.structured.small_merge``).
    """
    ours_memory: RssMemory | None = None
    batched_memory: RssMemory | None = None
    for frame in _drive(seed, n_objects, steps):
        twin = frame[which % len(frame)]
        if how == "wider":
            s = twin.other.speed
            speed = SpeedInterval(
                max(0.0, s.lon_min_mps - 1.0),
                min(100.0, s.lon_max_mps + 1.0),
                max(-100.0, s.lat_min_mps - 0.1),
                min(100.0, s.lat_max_mps + 0.1),
            )
            twin = dataclasses.replace(twin, other=dataclasses.replace(twin.other, speed=speed))
        frame_twice = [*frame, twin]
        before_ours = ours_memory
        ours, ours_memory = check_frame(
            stack_constellations(frame_twice), _DEFAULTS.ego, ours_memory
        )
        batched, batched_memory = _batched(frame_twice, batched_memory)
        _assert_same(ours, batched)
        _assert_same(ours_memory, batched_memory)
        if (batched.invalid == 0).all():
            before = {} if before_ours is None else recall(before_ours)
            assert check_frame_small(stack_constellations(frame_twice), _DEFAULTS.ego, before)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 10), st.sampled_from(["nan", "same_id"]))
def test_uncovered_frames_go_to_the_batched_engine(seed: int, n_objects: int, how: str) -> None:
    """A non-finite speed, the ego's id as an object's: the batched engine takes the frame."""
    frames = _drive(seed, n_objects, 2)
    first = frames[0]
    if how == "nan":
        other = dataclasses.replace(first[0].other, speed=SpeedInterval(np.nan, 1.0, 0.0, 0.0))
        frame = [dataclasses.replace(first[0], other=other), *first[1:]]
    else:
        other = dataclasses.replace(first[0].other, object_id=first[0].ego.object_id)
        frame = [dataclasses.replace(first[0], other=other), *first[1:]]
    batch = stack_constellations(frame)
    assert check_frame_small(batch, _DEFAULTS.ego, {}) is None
    _, memory = check_frame(stack_constellations(frames[1]), _DEFAULTS.ego)
    ours, ours_memory = check_frame(batch, _DEFAULTS.ego, memory)
    batched, batched_memory = _batched(frame, memory)
    _assert_same(ours, batched)
    _assert_same(ours_memory, batched_memory)


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 12))
def test_each_call_builds_its_own_arrays(seed: int, n_objects: int) -> None:
    """Two calls on one batch (memory carried): fresh, contiguous arrays, nothing shared.

    Writing into the first result's arrays leaves the second result (and the batched
    engine's answer for the same frame and memory) untouched.
    """
    batch = stack_constellations(_drive(seed, n_objects, 1)[0])
    first, memory = check_frame(batch, _DEFAULTS.ego)
    second, _ = check_frame(batch, _DEFAULTS.ego, memory)
    a = _fields(first)
    for name, value in a.items():  # before any field of the second result is built
        assert value.flags.c_contiguous, name
        value[...] = 0 if value.dtype.kind != "b" else not value.all()
    batched, _ = check_frames(
        batch, np.zeros(batch.size, dtype=np.int64), 1, _DEFAULTS.ego, _plain(memory)
    )
    _assert_same(second, batched)
    b = _fields(second)
    assert all(a[name] is not b[name] for name in a)
