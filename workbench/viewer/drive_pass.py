"""One pass over a drive for a replay: evaluate once, feed every consumer.

A :class:`DrivePass` builds the run (the driver over the drive and its engines), then each
chunk of frames and verdicts goes, once, to every consumer: the Rerun sink (scene and each
engine's geometry), the violation intervals, the incident detector and the culprits' boxes.
Where the recording goes is not its business (:mod:`workbench.viewer.outputs`); what the
caller does with the incidents (a replay's lanes, a review session, a clip) neither.
"""

from __future__ import annotations

import uuid
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import rerun as rr

from workbench.driver.run import DriveRun, EgoSize
from workbench.incidents import IncidentDetector, drive_content_hash
from workbench.replay.highlight import CulpritBoxes
from workbench.replay.incident_sink import send_incidents
from workbench.sinks.rerun_drive import SEND_FRAMES, RerunDriveSink
from workbench.sinks.violations import ViolationDetector

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator, Mapping, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.errors import LoaderError
    from workbench.driver.run import Chunk
    from workbench.engines.base import BoundRunner, EngineSpec
    from workbench.incidents import Incident, IncidentSettings
    from workbench.replay.short_labels import ShortLabels
    from workbench.sinks.violations import Violation

__all__ = [
    "APPLICATION_ID",
    "DrivePass",
    "FeedSettings",
    "PassWindow",
    "RecordingFeed",
    "ReplaySummary",
    "recording_id",
]

APPLICATION_ID = "rss-workbench"


def recording_id(drive: Drive, start_ns: int | None, end_ns: int | None) -> str:
    """The replay's recording id: the same drive and window give the same id."""
    key = f"{drive.info.path.resolve()}|{start_ns}|{end_ns}"
    return str(uuid.uuid5(uuid.NAMESPACE_URL, key))


@dataclass(frozen=True, slots=True)
class ReplaySummary:
    """What a replay did.

    Attributes:
        log: The drive file or directory.
        source_format: Format detected by the loader.
        frames: Frames sent.
        actors_seen: Distinct actor ids over the replayed frames.
        duration_s: Drive time covered by the frames sent.
        output: The ``.rrd`` path, the viewer URL, or ``"viewer"`` for a spawned viewer.
        elapsed_s: Wall-clock time for loading and logging.
        violations: Violation intervals found by the engines, if any ran.
        unsafe_frames: Unsafe frames per engine.
        stopped_by: The loader error that ended a truncated or corrupted log early; the
            output holds every frame read before it.
        incidents: The engines' incidents (worst first), shown as lanes and markers.
    """

    log: Path
    source_format: str
    frames: int
    actors_seen: int
    duration_s: float
    output: str
    elapsed_s: float
    violations: tuple[Violation, ...] = ()
    unsafe_frames: Mapping[str, int] = field(default_factory=dict)
    stopped_by: LoaderError | None = None
    incidents: tuple[Incident, ...] = ()

    @property
    def frames_per_s(self) -> float:
        """Throughput, load plus log."""
        return self.frames / self.elapsed_s if self.elapsed_s > 0 else float("inf")


@dataclass(frozen=True, slots=True)
class PassWindow:
    """Which frames a pass evaluates and sends.

    Attributes:
        start_ns: Only frames at or after this time.
        end_ns: Only frames before this time.
    """

    start_ns: int | None = None
    end_ns: int | None = None


@dataclass(frozen=True, slots=True)
class FeedSettings:
    """How a :class:`RecordingFeed` turns chunks into a recording and incidents.

    Attributes:
        incident_settings: How unsafe frames become incidents.
        send_frames: Frames per columnar batch sent to Rerun.
        labels: The drive's short-label table (a fresh one numbering culprits as they turn up
            by default; :class:`~workbench.sinks.rerun_drive.RerunDriveSink`).
        culprits: Collects the culprits' boxes (the caller may keep it); fresh by default.
    """

    incident_settings: IncidentSettings | None = None
    send_frames: int = SEND_FRAMES
    labels: ShortLabels | None = None
    culprits: CulpritBoxes | None = None


class RecordingFeed:
    """Consumers of one recording: each chunk to the Rerun sink, violations and incidents.

    Attributes:
        recording: The stream the scene and verdicts go to (attach it before the first chunk).
        recording_id: Its id (:func:`recording_id`).
        sink: The Rerun sink; its :attr:`~RerunDriveSink.labels` is the drive's short-label
            table after the chunks.
        violations: Violation intervals per engine.
        incidents: The incident detector (incidents, frame times, positions at their start).
        culprits: The culprits' boxes and the ego's positions at unsafe frames.
    """

    def __init__(
        self,
        drive: Drive,
        engines: Sequence[EngineSpec],
        rid: str,
        *,
        drive_hash: str,
        settings: FeedSettings | None = None,
    ) -> None:
        """Set up the consumers; nothing is sent before the first chunk.

        Args:
            drive: The drive the chunks come from (its info and map are sent first).
            engines: The engines whose verdicts come with each chunk.
            rid: The recording's id.
            drive_hash: The drive's content hash (the incidents' ids).
            settings: Incident settings, batch size, short labels, culprits' boxes.
        """
        settings = settings or FeedSettings()
        self._drive = drive
        self._names = tuple(spec.name for spec in engines)
        self.recording_id = rid
        self.recording = rr.RecordingStream(APPLICATION_ID, recording_id=rid)
        self.violations = ViolationDetector(drive.info.path.name)
        self.incidents = IncidentDetector(drive_hash, settings.incident_settings, engines=engines)
        self.sink = RerunDriveSink(
            self.recording,
            drive,
            engines,
            send_frames=settings.send_frames,
            labels=settings.labels,
        )
        culprits = settings.culprits
        self.culprits = culprits if culprits is not None else CulpritBoxes()

    @property
    def engine_names(self) -> tuple[str, ...]:
        """The engines evaluated, in order."""
        return self._names

    def add_chunk(self, chunk: Chunk) -> None:
        """Hand one evaluated chunk to every consumer."""
        self.sink.add_chunk(chunk)
        self.violations.add_chunk(chunk)
        self.incidents.add_chunk(chunk)
        if self._names:
            self.culprits.add_chunk(chunk)

    def found(self) -> tuple[Incident, ...]:
        """The incidents of the chunks added, worst first (none without engines)."""
        return tuple(self.incidents.incidents()) if self._names else ()

    def send_incidents(self, found: Sequence[Incident], verdicts: Mapping[str, str]) -> None:
        """Send the incidents' lanes, markers and highlights (``verdicts`` by incident id)."""
        if not self._names:
            return
        times = self.incidents.frame_times
        lights = self.culprits.layout(
            found, self.sink.labels, times, escape=rr.escape_entity_path_part
        )
        send_incidents(self.recording, found, verdicts, times, highlights=lights)


class DrivePass(RecordingFeed):
    """The driver's chunks over a drive, evaluated once, into one :class:`RecordingFeed`.

    Attributes:
        run: The driver (its :attr:`~DriveRun.stopped_by` after the pass).
        ego_start_m: The ego's ``(x, y)`` [m] at the first frame evaluated, if any.
    """

    def __init__(
        self,
        drive: Drive,
        engines: Sequence[BoundRunner] = (),
        *,
        window: PassWindow | None = None,
        ego_size: EgoSize | None = None,
        settings: FeedSettings | None = None,
    ) -> None:
        """Build the run and its consumers; the first chunk is evaluated (the camera's start).

        Args:
            drive: An opened drive; the caller closes it.
            engines: Runners evaluated on every frame (fresh: they carry the engines' state)
                with their specs.
            window: Frames evaluated and sent (the whole drive by default).
            ego_size: The user's ego size for every engine and the viewer.
            settings: The feed's settings (:class:`FeedSettings`).
        """
        window = window or PassWindow()
        self.run = DriveRun(
            drive, engines, start_ns=window.start_ns, end_ns=window.end_ns, ego_size=ego_size
        )
        self._chunks = iter(self.run)
        self._first = next(self._chunks, None)
        first = self._first.frames[0].ego if self._first is not None else None
        self.ego_start_m = (first.x_m, first.y_m) if first is not None else None
        path = drive.info.path
        super().__init__(
            drive,
            self.run.specs,
            recording_id(drive, window.start_ns, window.end_ns),
            drive_hash=drive_content_hash(path) if engines and path.exists() else "",
            settings=settings,
        )

    def stream(self, progress: Callable[[int], None] | None = None) -> None:
        """Evaluate every chunk once and hand it to each consumer; flush the Rerun sink.

        Args:
            progress: Called with the number of frames evaluated after each chunk.
        """
        for chunk in _with_first(self._first, self._chunks):
            self.add_chunk(chunk)
            if progress is not None:
                progress(self.violations.frames)
        self._first = None
        self.sink.close()

    def summary(
        self, output: str, elapsed_s: float, found: Sequence[Incident] = ()
    ) -> ReplaySummary:
        """What the pass sent to ``output`` in ``elapsed_s`` [s] of wall time."""
        unsafe = self.violations.unsafe_per_engine
        return ReplaySummary(
            log=self._drive.info.path,
            source_format=self._drive.info.source_format,
            frames=self.sink.frames,
            actors_seen=len(self.sink.actor_ids),
            duration_s=self.sink.duration_s,
            output=output,
            elapsed_s=elapsed_s,
            violations=tuple(self.violations.violations()),
            unsafe_frames={n: unsafe.get(n, 0) for n in self.engine_names},
            stopped_by=self.run.stopped_by,
            incidents=tuple(found),
        )


def _with_first(first: Chunk | None, rest: Iterator[Chunk]) -> Iterator[Chunk]:
    if first is not None:
        yield first
    yield from rest
