"""Runs of unsafe frames per key: the one place that merges unsafe frames into intervals.

Violation intervals (:mod:`workbench.sinks.violations`, one key per engine) and incidents
(:mod:`workbench.incidents`, one key per engine, object and cause) are both runs of this
merger; only their keys and what they make of a finished run differ.

Gap merging: a run is *paused* at the first frame its key is not hit. A later hit extends
it when it comes at most ``gap_ns`` after that first safe frame, else a new run starts::

    frames      x  x  .  .  x  x  .  .  .  .  x         x: key hit, .: not hit
    gap_ns = 0  [run 1]     [run 2]           [run 3]   (any safe frame ends a run)
    gap = 2 dt  [run 1 ...........]           [run 3]   (two safe frames bridged)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Generic, TypeVar

if TYPE_CHECKING:
    from collections.abc import Hashable, Mapping

    from workbench.engines.base import Verdict

__all__ = ["Run", "RunMerger"]

K = TypeVar("K", bound="Hashable")


@dataclass(slots=True)
class Run(Generic[K]):
    """One run of frames in which ``key`` was hit (bridging short safe stretches).

    Attributes:
        key: What the run is of (engine name, or engine/object/cause).
        start_frame: First hit frame.
        end_frame: Last hit frame (inclusive).
        start_ns: Time of the first hit frame.
        end_ns: Time of the last hit frame.
        worst_margin: Smallest verdict margin over the hit frames.
        worst_frame: First hit frame with that margin (``-1`` before the first hit).
        unsafe_frames: Hit frames (fewer than ``end_frame - start_frame + 1`` when gaps
            were bridged).
        objects: Culprits of every hit frame.
        causes: Causes of the hit frames as text, in the order first seen (``""`` left out).
        extra: Whatever the owner attaches (e.g. incident fact collectors).
        paused_at_ns: Time of the first frame since the last hit that missed the key.
    """

    key: K
    start_frame: int
    end_frame: int
    start_ns: int
    end_ns: int
    worst_margin: float
    unsafe_frames: int = 1
    worst_frame: int = -1
    objects: set[str] = field(default_factory=set)
    causes: list[str] = field(default_factory=list)
    extra: list[Any] = field(default_factory=list)
    paused_at_ns: int | None = None

    def extend(self, frame: int, t_ns: int, verdict: Verdict) -> None:
        """Add one hit frame's verdict."""
        self.end_frame = frame
        self.end_ns = t_ns
        if self.worst_frame < 0 or verdict.margin < self.worst_margin:
            self.worst_frame = frame
        self.worst_margin = min(self.worst_margin, verdict.margin)
        self.objects.update(verdict.culprits)
        cause = str(verdict.cause)
        if cause and cause not in self.causes:
            self.causes.append(cause)
        self.paused_at_ns = None


class RunMerger(Generic[K]):
    """Merges the frames hitting each key into runs, frame by frame (frames in time order).

    Only open runs and finished ones are kept: memory grows with the runs, not the frames.
    """

    def __init__(self, gap_ns: int = 0) -> None:
        """Start empty; ``gap_ns``: longest safe stretch bridged (see the module docstring)."""
        if gap_ns < 0:
            raise ValueError(f"gap_ns must be >= 0, not {gap_ns}")
        self.gap_ns = gap_ns
        self._open: dict[K, Run[K]] = {}
        self._done: list[Run[K]] = []

    def _bridges(self, run: Run[K], t_ns: int) -> bool:
        return run.paused_at_ns is None or t_ns - run.paused_at_ns <= self.gap_ns

    def add(self, frame: int, t_ns: int, hits: Mapping[K, Verdict]) -> list[Run[K]]:
        """Add one frame: the keys it hits, each with the verdict that hit it.

        Returns:
            The runs this frame hit, in the order of ``hits`` (a run it started has
            ``unsafe_frames == 1``), for owners that keep ``extra`` per run.
        """
        for key in [k for k in self._open if k not in hits]:
            run = self._open[key]
            if run.paused_at_ns is None:
                run.paused_at_ns = t_ns
            if t_ns - run.paused_at_ns >= self.gap_ns:
                self._done.append(self._open.pop(key))
        hit: list[Run[K]] = []
        for key, verdict in hits.items():
            found = self._open.get(key)
            if found is not None and not self._bridges(found, t_ns):
                self._done.append(self._open.pop(key))
                found = None
            run = found or Run(key, frame, frame, t_ns, t_ns, verdict.margin, unsafe_frames=0)
            self._open[key] = run
            run.unsafe_frames += 1
            run.extend(frame, t_ns, verdict)
            hit.append(run)
        return hit

    def runs(self) -> list[Run[K]]:
        """Every run so far, finished and open, by start frame (then first seen)."""
        found = [*self._done, *self._open.values()]
        found.sort(key=lambda r: r.start_frame)
        return found
