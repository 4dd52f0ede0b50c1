"""The one drive runner: a drive becomes chunks of (frames, typed verdicts per engine).

Every command that evaluates or shows a drive (``evaluate``, ``replay``, ``demo``, and the
incident, review and export commands to come) iterates a :class:`DriveRun` and hands its
chunks to sinks (:mod:`workbench.sinks`)::

    drive.frames(start, end) --> CHUNK_FRAMES frames --> runner.step_many(frames) per engine
                                   |                        |
                                   +-- Chunk(frames, {engine: verdicts}, {engine: spec}) --> sinks

Chunk policy: engines get :data:`CHUNK_FRAMES` consecutive frames per call (their batched
kernels' sweet spot; verdicts do not depend on it, every runner is tested against one
frame per call). Loader errors: a truncated or corrupted log yields every readable frame;
the :class:`~loaders.errors.LoaderError` that ended it is kept in :attr:`DriveRun.stopped_by`
after the last chunk, for the caller to report. Any other error propagates after the frames
read before it were evaluated and yielded.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

from loaders.errors import LoaderError
from workbench.driver.gc_policy import engine_gc

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    from loaders.drive import Drive
    from loaders.records import Frame
    from workbench.engines.base import BoundRunner, EngineSpec, Verdict

__all__ = ["CHUNK_FRAMES", "Chunk", "DriveRun", "EgoSize", "evaluate_chunk"]

#: Frames handed at once to the engines and then to the sinks.
CHUNK_FRAMES = 32


@dataclass(frozen=True, slots=True)
class EgoSize:
    """The user's ego size [m] (``--ego-size L,W,H``); ``None`` fields: the frame's (the log's)."""

    length_m: float | None = None
    width_m: float | None = None
    height_m: float | None = None

    def fields(self) -> dict[str, float]:
        """The ``EgoState`` fields to replace."""
        given = {"length_m": self.length_m, "width_m": self.width_m, "height_m": self.height_m}
        return {k: v for k, v in given.items() if v is not None}

    def apply(self, frame: Frame) -> Frame:
        """``frame`` with this size for its ego (fields that are ``None`` kept)."""
        given = self.fields()
        return dataclasses.replace(frame, ego=dataclasses.replace(frame.ego, **given))


@dataclass(frozen=True, slots=True)
class Chunk:
    """Consecutive frames and every engine's verdict on each.

    Attributes:
        frames: ``N`` frames in time order.
        verdicts: Per engine name (in the order the engines run), ``N`` verdicts.
        specs: Per engine name, the spec its runner was built from (what the sinks use).
    """

    frames: tuple[Frame, ...]
    verdicts: Mapping[str, tuple[Verdict, ...]]
    specs: Mapping[str, EngineSpec]

    def part(self, start: int, stop: int) -> Chunk:
        """Frames ``start:stop`` of the chunk and their verdicts."""
        verdicts = {n: v[start:stop] for n, v in self.verdicts.items()}
        return Chunk(self.frames[start:stop], verdicts, self.specs)


def evaluate_chunk(frames: Sequence[Frame], runners: Sequence[BoundRunner]) -> Chunk:
    """Run every engine on ``frames`` (advancing each runner's state)."""
    verdicts = {r.name: tuple(r.step_many(frames)) for r in runners}
    return Chunk(tuple(frames), verdicts, {r.name: r.spec for r in runners})


class DriveRun:
    """Iterates a drive's frames in chunks, evaluated by the engines.

    Iterate it once. The whole iteration runs under :func:`engine_gc`.
    """

    def __init__(
        self,
        drive: Drive,
        runners: Sequence[BoundRunner] = (),
        *,
        start_ns: int | None = None,
        end_ns: int | None = None,
        chunk_frames: int = CHUNK_FRAMES,
        ego_size: EgoSize | None = None,
    ) -> None:
        """Set up the run.

        Args:
            drive: An opened drive; the caller closes it.
            runners: Engine runners with their specs, each carrying its own state from chunk
                to chunk.
            start_ns: Only frames at or after this time.
            end_ns: Only frames before this time.
            chunk_frames: Frames per chunk (tests; the default is the policy).
            ego_size: The user's ego size, replacing the log's in every frame before any
                engine or sink sees it (``None`` or ``None`` fields: keep the log's).
        """
        self.drive = drive
        self.runners = tuple(runners)
        self._window = (start_ns, end_ns)
        self._chunk_frames = chunk_frames
        self._ego_size = ego_size if ego_size is not None and ego_size.fields() else None
        #: The loader error that ended a truncated or corrupted log, once iterated.
        self.stopped_by: LoaderError | None = None

    @property
    def engine_names(self) -> tuple[str, ...]:
        """Names of the engines that run, in order."""
        return tuple(r.name for r in self.runners)

    @property
    def specs(self) -> tuple[EngineSpec, ...]:
        """Specs of the engines that run, in order."""
        return tuple(r.spec for r in self.runners)

    def _sized(self, frame: Frame) -> Frame:
        return frame if self._ego_size is None else self._ego_size.apply(frame)

    def _read(self) -> Iterator[list[Frame]]:
        """Frames in chunks; a loader error ends the drive after the frames read before it."""
        chunk: list[Frame] = []
        try:
            for frame in self.drive.frames(*self._window):
                chunk.append(self._sized(frame))
                if len(chunk) == self._chunk_frames:
                    yield chunk
                    chunk = []
        except LoaderError as err:
            self.stopped_by = err
        except Exception:
            if chunk:
                yield chunk
            raise
        if chunk:
            yield chunk

    def __iter__(self) -> Iterator[Chunk]:
        """Chunks in time order; :attr:`stopped_by` is set once the drive ended early."""
        with engine_gc():
            for frames in self._read():
                yield evaluate_chunk(frames, self.runners)
