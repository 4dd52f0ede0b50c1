"""Loader frames -> engines -> ``FrameResult``: the one-way flow every sink consumes.

An engine runner wraps one pure engine, carrying its explicit state from frame to frame. It
returns the pinned per-frame JSON record of DESIGN.md and, for the sinks, the engine's full
result object (geometry for Rerun).
"""

from __future__ import annotations

import gc
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from collections.abc import Iterable, Iterator, Mapping, Sequence

    from loaders.records import Frame

__all__ = [
    "CHUNK_FRAMES",
    "ENGINE_GC_THRESHOLD",
    "EngineOutput",
    "EngineRunner",
    "FrameResult",
    "engine_gc",
    "evaluate_frames",
]

#: Frames handed at once to engines that evaluate consecutive frames in one batch.
CHUNK_FRAMES = 32

#: Young-generation threshold of Python's cyclic garbage collector while a drive is
#: evaluated (CPython's default is 700). Scene creation keeps tens of thousands of small
#: per-frame memo objects alive for one frame, none in reference cycles: at 700 the
#: collector runs mid-frame hundreds of times per chunk, promotes the memos and then
#: sweeps the whole heap, about 0.9 ms of a 6 ms frame (Town01, 50 objects; measured
#: with ``gc.callbacks``). At this threshold it runs only when 50,000 container objects
#: have accumulated: a few times per drive.
ENGINE_GC_THRESHOLD = 50_000


@contextmanager
def engine_gc() -> Iterator[None]:
    """Raise the young-generation GC threshold to :data:`ENGINE_GC_THRESHOLD` inside.

    Only the threshold changes (never lowered; the collector stays on, cyclic garbage is
    still collected). On exit the young generation is collected once, here rather than
    at the next allocation after it (so the drive pays for it and a benchmark times
    it), and the threshold is restored.
    """
    old = gc.get_threshold()
    gc.set_threshold(max(old[0], ENGINE_GC_THRESHOLD), *old[1:])
    try:
        yield
    finally:
        if gc.isenabled():
            gc.collect(0)
        gc.set_threshold(*old)


@dataclass(frozen=True, slots=True)
class EngineOutput:
    """One engine's verdict on one frame.

    Attributes:
        record: JSON-ready per-frame record (the pinned ``evaluate --per-frame`` keys).
        is_safe: The frame verdict.
        culprits: Ids of the objects that make the frame unsafe.
        label: Short reason (rule or response) for violation intervals.
        margin: Engine-specific severity; smaller is worse (e.g. time to first collision).
        detail: The engine's full result object, for sinks that draw geometry.
    """

    record: dict[str, Any]
    is_safe: bool
    culprits: tuple[str, ...] = ()
    label: str = ""
    margin: float = float("inf")
    detail: Any = None


class EngineRunner(Protocol):
    """A stateful wrapper of one pure engine."""

    name: str

    def step(self, frame: Frame) -> EngineOutput:
        """Evaluate one frame, advancing the engine's explicit state."""
        ...


@dataclass(frozen=True, slots=True)
class FrameResult:
    """All engine verdicts of one frame."""

    frame: int
    t_ns: int
    outputs: Mapping[str, EngineOutput]

    def without_detail(self) -> FrameResult:
        """The same verdicts without the engines' geometry (what violation detection needs).

        Keeping only this per frame keeps memory flat however long the drive is.
        """
        outputs = {
            name: EngineOutput(
                record=out.record,
                is_safe=out.is_safe,
                culprits=out.culprits,
                label=out.label,
                margin=out.margin,
            )
            for name, out in self.outputs.items()
        }
        return FrameResult(frame=self.frame, t_ns=self.t_ns, outputs=outputs)

    def record(self) -> dict[str, Any]:
        """The per-frame JSON line of ``workbench evaluate --per-frame``."""
        line: dict[str, Any] = {"t_ns": self.t_ns, "frame": self.frame}
        for name, out in self.outputs.items():
            line[name] = out.record
        return line


def evaluate_frames(
    frames: Iterable[Frame], engines: Sequence[EngineRunner]
) -> Iterator[tuple[Frame, FrameResult]]:
    """Run every engine on every frame, in order.

    Args:
        frames: Frames of one drive, in time order.
        engines: Engine runners; each keeps its own state across frames.

    Frames are taken ``CHUNK_FRAMES`` at a time; an engine with a ``step_many`` method gets
    them in one call (same results as ``step`` on each in turn). An error while reading
    frames is raised after the frames read before it have been evaluated and yielded.

    The whole drive runs under :func:`engine_gc`.

    Yields:
        Each frame with its result.
    """
    it = iter(frames)
    with engine_gc():
        while True:
            chunk: list[Frame] = []
            try:
                for frame in it:
                    chunk.append(frame)
                    if len(chunk) == CHUNK_FRAMES:
                        break
            except Exception:
                yield from _evaluate_chunk(chunk, engines)
                raise
            yield from _evaluate_chunk(chunk, engines)
            if len(chunk) < CHUNK_FRAMES:
                return


def _evaluate_chunk(
    chunk: Sequence[Frame], engines: Sequence[EngineRunner]
) -> Iterator[tuple[Frame, FrameResult]]:
    if not chunk:
        return
    outputs = {}
    for engine in engines:
        many = getattr(engine, "step_many", None)
        outputs[engine.name] = many(chunk) if many else [engine.step(f) for f in chunk]
    for j, frame in enumerate(chunk):
        found = {name: out[j] for name, out in outputs.items()}
        yield frame, FrameResult(frame=frame.index, t_ns=frame.t_ns, outputs=found)
