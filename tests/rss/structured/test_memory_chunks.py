"""The memory carried between engine calls: frame by frame, in chunks and in one call agree.

Several pairs share each frame (one ego, one key per sequence), some pairs skip frames.
One ``check_frames`` call over all frames is the reference (its memory scan is compared with
ad-rss in ``test_differential_sequences``); chaining calls with the returned memory must
give the same states, responses and memory.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pytest

from rss.conformance.cases import parse_case, parse_defaults
from rss.structured.engine import check_frames, select_frame
from rss.structured.stacking import stack_constellations
from tests.equality import assert_same
from tests.rss.structured.generators import random_sequence, renumber

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.model import Constellation
    from rss.structured.engine import FrameResult
    from rss.structured.memory import RssMemory

N_PAIRS = 12
N_FRAMES = 7


def _frames(seed: int) -> tuple[list[list[Constellation]], RssDynamics]:
    """Per frame, the constellations of the pairs present in it; the default ego."""
    defaults = parse_defaults({})
    rng = np.random.default_rng(seed)
    frames: list[list[Constellation]] = [[] for _ in range(N_FRAMES)]
    default_ego = defaults.ego
    for j in range(N_PAIRS):
        seq = random_sequence(rng, defaults, f"seq{j}", N_FRAMES)
        for k, step in enumerate(seq["steps"]):
            parsed = renumber(parse_case(step, defaults, f"seq{j}#{k}", seq["id"], k), 0, j + 1)
            default_ego = parsed.default_ego
            if (j + 2 * k) % 5 and parsed.constellation is not None:
                frames[k].append(parsed.constellation)
    return frames, default_ego


def _run(
    frames: list[list[Constellation]], default_ego: RssDynamics, memory: RssMemory | None
) -> tuple[FrameResult, RssMemory]:
    counts = [len(f) for f in frames]
    batch = stack_constellations([c for f in frames for c in f])
    frame_of = np.repeat(np.arange(len(frames)), counts)
    return check_frames(batch, frame_of, len(frames), default_ego, memory)


@pytest.mark.parametrize("chunk", [1, 2, 4])
@pytest.mark.parametrize("seed", [3, 17, 2026])
def test_chained_calls_equal_one_call(seed, chunk):
    frames, default_ego = _frames(seed)
    whole, final = _run(frames, default_ego, None)
    memory: RssMemory | None = None
    dangerous = 0
    for lo in range(0, N_FRAMES, chunk):
        part, memory = _run(frames[lo : lo + chunk], default_ego, memory)
        for k in range(len(frames[lo : lo + chunk])):
            assert_same(select_frame(part, k), select_frame(whole, lo + k), f"frame {lo + k}")
            dangerous += int(select_frame(part, k).dangerous.sum())
    assert memory is not None
    assert_same(memory, final)
    assert memory.size > N_PAIRS // 2
    assert dangerous > 0
