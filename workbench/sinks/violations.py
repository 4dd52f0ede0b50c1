"""Merge unsafe frames into violation intervals, one row per interval with a stable id.

A violation is a run of one engine's unsafe frames, whatever objects and causes
(``evaluate --violations``); an incident (:mod:`workbench.incidents`) is a run of one engine,
object and cause. Their ids cannot be taken for each other::

    violation  viol-rss-000123-1a2b3c4d     viol- + engine + start frame + 8 hex digits of
                                            sha256(log file name, engine, start frame)
    incident   rss-000123-1a2b3c4d5e        engine + start frame + 10 hex digits of
                                            sha256(drive content hash, engine, objects,
                                            cause, start frame)

A violation id names the interval of one run of ``evaluate`` on one log file; an incident
id is the key review labels are stored under (docs/review.md, "Ids").
"""

from __future__ import annotations

import csv
import hashlib
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError
from workbench.outputs import atomic_output, write_json
from workbench.sinks.runs import RunMerger

if TYPE_CHECKING:
    from collections.abc import Iterable, Mapping
    from pathlib import Path

    from workbench.driver.run import Chunk
    from workbench.engines.base import Verdict

__all__ = [
    "VIOLATION_ID_PREFIX",
    "Violation",
    "ViolationDetector",
    "detect_violations",
    "violation_id",
    "write_violations",
]


@dataclass(slots=True)
class Violation:
    """A run of consecutive unsafe frames of one engine.

    Attributes:
        id: Stable id ``viol-<engine>-<first frame>-<hash>`` (hash of the log name, engine
            and first frame; module docstring).
        log: Log file name.
        engine: Engine name.
        label: Rule or response that fired (first frame's label; others are in ``labels``).
        objects: Ids of the objects involved over the whole interval, sorted.
        start_frame: First unsafe frame.
        end_frame: Last unsafe frame (inclusive).
        start_ns: Time of the first unsafe frame.
        end_ns: Time of the last unsafe frame.
        worst_margin: Smallest engine margin within the interval.
        labels: Every label seen within the interval, sorted.
        profile: The parameter profile the engine's verdicts name (RSS: ``RssVerdict.profile``,
            e.g. ``highway``); ``""`` for engines whose verdicts name none.
    """

    id: str
    log: str
    engine: str
    label: str
    objects: list[str]
    start_frame: int
    end_frame: int
    start_ns: int
    end_ns: int
    worst_margin: float
    labels: list[str] = field(default_factory=list)
    profile: str = ""

    @property
    def frames(self) -> int:
        """Number of frames in the interval."""
        return self.end_frame - self.start_frame + 1


#: First characters of every violation id (no incident id starts so).
VIOLATION_ID_PREFIX = "viol-"


def violation_id(log: str, engine: str, start_frame: int) -> str:
    """Stable id ``viol-<engine>-<start frame>-<hash>`` of a violation interval."""
    digest = hashlib.sha256(f"{log}\0{engine}\0{start_frame}".encode()).hexdigest()
    return f"{VIOLATION_ID_PREFIX}{engine}-{start_frame:06d}-{digest[:8]}"


class ViolationDetector:
    """Merges consecutive unsafe frames of each engine into intervals, chunk by chunk.

    The runs come from :class:`~workbench.sinks.runs.RunMerger` keyed by engine; a frame the
    engine rated safe ends its interval. Memory stays flat however long the drive is.
    """

    def __init__(self, log: str) -> None:
        """Start empty; ``log`` is recorded in each violation (and part of its id)."""
        self.log = log
        self._runs: RunMerger[str] = RunMerger()
        #: Frames added so far.
        self.frames = 0
        #: Frames at least one engine rated unsafe.
        self.unsafe_frames = 0
        #: Unsafe frames per engine, in the order the engines first appeared.
        self.unsafe_per_engine: dict[str, int] = {}
        #: The parameter profile each engine's verdicts name (``profile``; ``""``: none).
        self.profiles: dict[str, str] = {}

    def add(self, frame: int, t_ns: int, verdicts: Mapping[str, Verdict]) -> None:
        """Add one frame's verdicts (frames in order)."""
        self.frames += 1
        self.unsafe_frames += not all(v.is_safe for v in verdicts.values())
        for engine, out in verdicts.items():
            self.unsafe_per_engine[engine] = self.unsafe_per_engine.get(engine, 0) + (
                not out.is_safe
            )
            if engine not in self.profiles:
                self.profiles[engine] = str(getattr(out, "profile", "") or "")
        self._runs.add(frame, t_ns, {e: v for e, v in verdicts.items() if not v.is_safe})

    def add_chunk(self, chunk: Chunk) -> None:
        """Add every frame of a driver chunk."""
        for k, frame in enumerate(chunk.frames):
            self.add(frame.index, frame.t_ns, {n: v[k] for n, v in chunk.verdicts.items()})

    def violations(self) -> list[Violation]:
        """Every interval so far (open ones included), by start frame, then engine."""
        found = [
            Violation(
                id=violation_id(self.log, run.key, run.start_frame),
                log=self.log,
                engine=run.key,
                label=run.causes[0] if run.causes else "",
                objects=sorted(run.objects),
                start_frame=run.start_frame,
                end_frame=run.end_frame,
                start_ns=run.start_ns,
                end_ns=run.end_ns,
                worst_margin=run.worst_margin,
                labels=sorted(run.causes),
                profile=self.profiles.get(run.key, ""),
            )
            for run in self._runs.runs()
        ]
        found.sort(key=lambda v: (v.start_frame, v.engine))
        return found


def detect_violations(
    frames: Iterable[tuple[int, int, Mapping[str, Verdict]]], log: str
) -> list[Violation]:
    """Violation intervals of ``(frame, t_ns, verdicts per engine)`` in frame order."""
    detector = ViolationDetector(log)
    for frame, t_ns, verdicts in frames:
        detector.add(frame, t_ns, verdicts)
    return detector.violations()


def write_violations(violations: list[Violation], path: Path) -> None:
    """Write the violations table as JSON (``.json``) or CSV (``.csv``), atomically.

    Raises:
        WorkbenchError: For any other suffix.
    """
    rows = [asdict(v) for v in violations]
    if path.suffix not in {".json", ".csv"}:
        msg = f"{path}: violations file must end in .json or .csv, not {path.suffix!r}"
        raise WorkbenchError(msg)
    if path.suffix == ".json":
        write_json(path, rows, "the violations")
        return
    names = list(Violation.__dataclass_fields__)
    with atomic_output(path, "the violations") as tmp, tmp.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=names)
        writer.writeheader()
        for row in rows:
            row["objects"] = " ".join(row["objects"])
            row["labels"] = " ".join(row["labels"])
            writer.writerow(row)
