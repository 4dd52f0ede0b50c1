"""The structured RSS engine: ``(constellations, params, memory) -> (result, memory)``.

One call evaluates all constellations of one frame — or of ``F`` consecutive frames at
once — with numpy: extraction, checks, memory, response resolving. Invalid constellations
(NaN, negative or out-of-range speeds, regions outside the road area, ...) are flagged and
skipped instead of failing the whole frame as ad-rss does.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.structured.batch import take_rows
from rss.structured.checks import RawStates, check_all
from rss.structured.extraction import Relative, extract
from rss.structured.memory import RssMemory, apply_memory_both, is_dangerous
from rss.structured.merge import merge_similar
from rss.structured.response import ProperResponses, resolve
from rss.structured.responsibility import Responsibility, responsibility, swap_roles
from rss.structured.severity import Severity, severity
from rss.structured.small import SMALL_FRAME_MAX, check_frame_small
from rss.structured.small_arrays import dangerous, raw_states, relative, responses
from rss.structured.small_output import recall
from rss.structured.small_result import SmallMemory
from rss.structured.states import InvalidReason

if TYPE_CHECKING:
    from collections.abc import Callable

    from rss.arrays import BoolArray, IntArray
    from rss.dynamics import RssDynamics
    from rss.structured.batch import ConstellationBatch
    from rss.structured.small_output import Columns

__all__ = ["FrameResult", "check_frame", "check_frames", "select_frame"]


@dataclass(frozen=True)
class FrameResult:
    """Everything the engine decided for ``C`` constellations in ``F`` frames.

    Attributes:
        relative: Relative situation per constellation (``(C,)`` arrays).
        states: Memory-adjusted states per constellation.
        dangerous: ``(C,)`` dangerous (and valid) constellations.
        invalid: ``(C,)`` :class:`InvalidReason` codes (0 = evaluated).
        frame: ``(C,)`` frame number of each constellation.
        responses: The ego's proper response per frame (``(F,)`` arrays).
        responsibility: Who must act per constellation, from both sides (``None`` unless
            asked for: :func:`check_frames` ``with_responsibility=True``).
        severity: Severity facts per constellation (distance ratio, time to collision,
            required deceleration; asked for together with ``responsibility``).
    """

    relative: Relative
    states: RawStates
    dangerous: BoolArray
    invalid: IntArray
    frame: IntArray
    responses: ProperResponses
    responsibility: Responsibility | None = None
    severity: Severity | None = None


def check_frames(
    batch: ConstellationBatch,
    frame: IntArray,
    n_frames: int,
    default_ego: RssDynamics,
    memory: RssMemory | None = None,
    *,
    with_responsibility: bool = False,
) -> tuple[FrameResult, RssMemory]:
    """Evaluate the constellations of ``F`` consecutive frames in one vectorised call.

    Args:
        batch: ``C`` constellations of all frames.
        frame: ``(C,)`` frame number in ``0..F-1`` of each constellation.
        n_frames: ``F`` (frames without constellations are safe).
        default_ego: Default ego dynamics (seed of the acceleration restrictions).
        memory: Memory before frame 0; ``None`` = fresh start.
        with_responsibility: Also check every constellation from the other object's side
            (:mod:`rss.structured.responsibility`) and compute the severity facts
            (:mod:`rss.structured.severity`); the ego's verdicts do not change.

    Returns:
        ``(result, memory)``: the result and the memory after frame ``F-1``.
    """
    frame = np.asarray(frame, dtype=np.int64)
    batch, rel = merge_similar(batch, extract(batch), frame)
    raw = check_all(batch, rel)
    other_raw = check_all(*swap_roles(batch, rel)) if with_responsibility else None
    valid = rel.invalid == InvalidReason.Valid
    before = memory or RssMemory.empty()
    states, other, new_memory = apply_memory_both(batch, rel, raw, other_raw, valid, frame, before)
    dangerous = is_dangerous(states) & valid
    responses = resolve(batch, states, dangerous, frame, n_frames, default_ego)
    who = None if other is None else responsibility(states, other, dangerous, valid)
    facts = None if other is None else severity(batch, rel, states)
    result = FrameResult(rel, states, dangerous, rel.invalid, frame, responses, who, facts)
    return result, new_memory


def check_frame(
    batch: ConstellationBatch, default_ego: RssDynamics, memory: RssMemory | None = None
) -> tuple[FrameResult, RssMemory]:
    """Evaluate all constellations of one frame (see :func:`check_frames`).

    A frame of at most :data:`rss.structured.small.SMALL_FRAME_MAX` constellations is
    evaluated row by row (:mod:`rss.structured.small`) when it can be; the result is the
    same, its arrays built on first read (:class:`SmallFrameResult`).
    """
    if 0 < batch.size <= SMALL_FRAME_MAX:
        if isinstance(memory, SmallMemory):
            before = memory.before
        else:
            before = recall(memory) if memory is not None and memory.size else {}
        out = check_frame_small(batch, default_ego, before)
        if out is not None:
            after = SmallMemory(out.memory) if out.memory else RssMemory.empty()
            return SmallFrameResult(out), after
    return check_frames(batch, np.zeros(batch.size, dtype=np.int64), 1, default_ego, memory)


def _zeros(out: Columns) -> IntArray:
    """``(C,)`` zeros (invalid reasons, frame numbers of one frame)."""
    return np.zeros(out.size, dtype=np.int64)


_BUILDERS: dict[str, Callable[[Columns], Any]] = {
    "relative": relative,
    "states": raw_states,
    "dangerous": dangerous,
    "responses": responses,
    "invalid": _zeros,
    "frame": _zeros,
}


class SmallFrameResult(FrameResult):
    """The :class:`FrameResult` of a small frame; each field built on its first read.

    The row path (:mod:`rss.structured.small`) has computed every value; the arrays are
    built from its rows when read (:mod:`rss.structured.small_result` says why) and are
    then those :func:`check_frames` returns.
    """

    _out: Columns

    def __init__(self, out: Columns) -> None:
        # frozen: no ``object.__setattr__``; ``responsibility`` and ``severity`` keep the
        # class defaults (None)
        self.__dict__["_out"] = out


class _Built:
    """A field of :class:`SmallFrameResult` built on its first read and kept.

    A non-data descriptor: the first read calls it, it stores the array in the instance's
    ``__dict__``, where every later read finds it first (no ``__getattr__`` fallback, which
    raises and catches an ``AttributeError`` on every first read).
    """

    def __init__(self, name: str, build: Callable[[Columns], Any]) -> None:
        self.name = name
        self.build = build

    def __get__(self, result: SmallFrameResult | None, owner: type | None = None) -> Any:
        if result is None:
            return self
        value = result.__dict__[self.name] = self.build(result.__dict__["_out"])
        return value


for _name, _build in _BUILDERS.items():  # the dataclass fields' types stay FrameResult's
    setattr(SmallFrameResult, _name, _Built(_name, _build))


def select_frame(result: FrameResult, index: int) -> FrameResult:
    """The result of frame ``index`` alone, as :func:`check_frame` returns it (``F = 1``).

    Args:
        result: Result of :func:`check_frames` over ``F`` frames.
        index: Frame number in ``0..F-1``.

    Returns:
        Its constellations' rows (frame numbers 0) and its proper response (``(1,)``).
    """
    rows = np.flatnonzero(result.frame == index)
    return FrameResult(
        relative=take_rows(result.relative, rows),
        states=take_rows(result.states, rows),
        dangerous=result.dangerous[rows],
        invalid=result.invalid[rows],
        frame=np.zeros(rows.size, dtype=np.int64),
        responses=take_rows(result.responses, np.array([index])),
        responsibility=None
        if result.responsibility is None
        else take_rows(result.responsibility, rows),
        severity=None if result.severity is None else take_rows(result.severity, rows),
    )
