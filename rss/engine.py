"""The structured RSS engine: ``(constellations, params, memory) -> (result, memory)``.

One call evaluates all constellations of a frame with numpy (extraction, checks, memory,
response resolving). Invalid constellations (NaN, negative or out-of-range speeds,
regions outside the road area, ...) are flagged and skipped instead of failing the frame
as ad-rss does.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.checks import RawStates, check_all
from rss.extraction import Relative, extract
from rss.memory import RssMemory, apply_memory, is_dangerous
from rss.response import ProperResponse, resolve
from rss.states import InvalidReason

if TYPE_CHECKING:
    from rss.batch import BoolArray, ConstellationBatch, IntArray
    from rss.dynamics import RssDynamics

__all__ = ["FrameResult", "check_frame"]


@dataclass(frozen=True)
class FrameResult:
    """Everything the engine decided for one frame.

    Attributes:
        relative: Relative situation per constellation (``(C,)`` arrays).
        states: Memory-adjusted states per constellation.
        dangerous: ``(C,)`` dangerous (and valid) constellations.
        invalid: ``(C,)`` :class:`InvalidReason` codes (0 = evaluated).
        proper_response: The ego's proper response.
    """

    relative: Relative
    states: RawStates
    dangerous: BoolArray
    invalid: IntArray
    proper_response: ProperResponse


def check_frame(
    batch: ConstellationBatch, default_ego: RssDynamics, memory: RssMemory | None = None
) -> tuple[FrameResult, RssMemory]:
    """Evaluate all constellations of one frame.

    Args:
        batch: ``C`` constellations of the frame.
        default_ego: Default ego dynamics (seed of the acceleration restrictions).
        memory: Memory after the previous frame; ``None`` = fresh start.

    Returns:
        ``(result, memory)``: the frame's result and the memory to pass to the next frame.
    """
    rel = extract(batch)
    raw = check_all(batch, rel)
    valid = rel.invalid == InvalidReason.Valid
    states, new_memory = apply_memory(batch, rel, raw, valid, memory or RssMemory.empty())
    dangerous = is_dangerous(states) & valid
    response = resolve(batch, states, dangerous, default_ego)
    return FrameResult(rel, states, dangerous, rel.invalid, response), new_memory
