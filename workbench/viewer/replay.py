"""Replay a drive into Rerun: the driver's chunks into a recording, sent to one destination.

Frames are read, evaluated and sent in chunks so memory stays flat for long drives.
"""

from __future__ import annotations

import time
import uuid
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import rerun as rr

from workbench.driver.run import DriveRun, EgoSize
from workbench.incidents import IncidentDetector, drive_content_hash
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.highlight import CulpritBoxes
from workbench.replay.incident_sink import send_incidents
from workbench.sinks.rerun_drive import SEND_FRAMES, RerunDriveSink
from workbench.sinks.violations import ViolationDetector
from workbench.viewer.outputs import LOCALHOST, attached

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator, Mapping, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.errors import LoaderError
    from workbench.driver.run import Chunk
    from workbench.engines.base import EngineRunner
    from workbench.incidents import Incident, IncidentSettings
    from workbench.replay.short_labels import ShortLabels
    from workbench.sinks.violations import Violation
    from workbench.viewer.web_cursor import WebCursor

__all__ = ["APPLICATION_ID", "ReplaySummary", "recording_id", "replay_drive"]

APPLICATION_ID = "rss-workbench"


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


def recording_id(drive: Drive, start_ns: int | None, end_ns: int | None) -> str:
    """The replay's recording id: the same drive and window give the same id."""
    key = f"{drive.info.path.resolve()}|{start_ns}|{end_ns}"
    return str(uuid.uuid5(uuid.NAMESPACE_URL, key))


def replay_drive(
    drive: Drive,
    *,
    out: Path | None = None,
    spawn: bool = False,
    serve: bool = False,
    progress: Callable[[int], None] | None = None,
    start_ns: int | None = None,
    end_ns: int | None = None,
    ports: tuple[int, int] = (9876, 9090),
    on_served: Callable[[str], None] | None = None,
    engines: Sequence[EngineRunner] = (),
    bind: str = LOCALHOST,
    send_frames: int = SEND_FRAMES,
    ego_size: EgoSize | None = None,
    incident_settings: IncidentSettings | None = None,
    verdicts: Mapping[str, str] | None = None,
    connect: str | None = None,
    selection: tuple[int, int] | None = None,
    lead_in: tuple[int, int] | None = None,
    focus_m: tuple[tuple[float, float], Sequence[tuple[float, float]]] | None = None,
    web_cursor: WebCursor | None = None,
    culprits: CulpritBoxes | None = None,
    labels: ShortLabels | None = None,
) -> ReplaySummary:
    """Send a drive's map, frames and engine verdicts to exactly one destination.

    Args:
        drive: An opened drive; the caller closes it.
        out: Write an ``.rrd`` file here (parent directories are created).
        spawn: Start a native viewer and stream to it.
        serve: Host a gRPC server on 127.0.0.1 plus the web viewer.
        progress: Called with the number of frames read after each chunk.
        start_ns: Only frames at or after this time.
        end_ns: Only frames before this time.
        ports: ``(grpc_port, web_port)`` for ``serve``.
        on_served: With ``serve``, called with the viewer URL once everything was sent; the
            server lives until it returns (the CLI waits for Ctrl-C there).
        engines: Engine runners evaluated on every frame; their verdicts and geometry are
            logged beside the scene and merged into violation intervals.
        bind: With ``serve``, the address the gRPC proxy and the web viewer listen on.
        send_frames: Frames per columnar batch sent to Rerun.
        ego_size: The user's ego size for every engine and the viewer (``--rss-params``).
        incident_settings: How the engines' unsafe frames become incidents (lanes and
            markers sent after the last frame).
        verdicts: Review verdict per incident id, shown on the lanes and markers.
        connect: Stream to a running viewer's gRPC proxy (``rerun+http://HOST:PORT/proxy``).
        selection: ``(first, last)`` frame of an incident: the blueprint's time panel selects
            and loops over it (a clip's review blueprint).
        lead_in: ``(shown_from_ns, frame_offset)``: the frames before ``shown_from_ns`` warm
            the engines up but are not sent; frame numbers are shifted by ``frame_offset``
            (a clip numbered as its drive; :class:`~workbench.driver.run.DriveRun`).
        focus_m: With ``selection``: ``(ego, objects)`` positions ``(x, y)`` [m] at the
            incident's first frame; the camera frames them (else the ego at the first frame).
        web_cursor: With ``serve``: serves the web page so the review loop can move the
            browser's time cursor (:mod:`workbench.viewer.web_cursor`).
        culprits: Collects the culprits' boxes and the ego's positions at unsafe frames
            (the caller keeps it: the review camera looks there); a fresh one by default.
        labels: The drive's short object labels (``#1``), one table for the scene's
            highlights and every engine's labels: the review's (its incidents' objects
            numbered first, as its table shows them); by default a fresh table numbering
            each unsafe frame's culprits as they turn up, then the objects engines label.

    Returns:
        Counts and timings of the replay.
    """
    t0 = time.perf_counter()
    shown_from_ns, frame_offset = lead_in or (None, 0)
    run = DriveRun(
        drive,
        engines,
        start_ns=start_ns,
        end_ns=end_ns,
        ego_size=ego_size,
        shown_from_ns=shown_from_ns,
        frame_offset=frame_offset,
    )
    chunks = iter(run)
    first = next(chunks, None)
    ego_start = (first.frames[0].ego.x_m, first.frames[0].ego.y_m) if first else None
    rec = rr.RecordingStream(APPLICATION_ID, recording_id=recording_id(drive, start_ns, end_ns))
    ego_at, objects_at = focus_m or (ego_start, ())
    blueprint = replay_blueprint(
        ego_at, engines=run.engine_names, selection=selection, focus_m=objects_at
    )
    detector = ViolationDetector(drive.info.path.name)
    path = drive.info.path
    incidents = IncidentDetector(
        drive_content_hash(path) if engines and path.exists() else "", incident_settings
    )
    sink = RerunDriveSink(rec, drive, run.engine_names, send_frames=send_frames, labels=labels)
    culprits = culprits if culprits is not None else CulpritBoxes()
    try:
        with attached(
            rec,
            blueprint,
            out=out,
            spawn=spawn,
            serve=serve,
            ports=ports,
            bind=bind,
            connect=connect,
            web_cursor=web_cursor,
        ) as to:
            for chunk in _with_first(first, chunks):
                sink.add_chunk(chunk)
                detector.add_chunk(chunk)
                incidents.add_chunk(chunk)
                if engines:
                    culprits.add_chunk(chunk)
                if progress is not None:
                    progress(detector.frames)
            sink.close()
            found = tuple(incidents.incidents()) if engines else ()
            if engines:
                lights = culprits.layout(
                    found,
                    sink.labels,
                    incidents.frame_times,
                    escape=rr.escape_entity_path_part,
                )
                send_incidents(rec, found, verdicts or {}, incidents.frame_times, highlights=lights)
            if on_served is not None and serve:
                on_served(to)
            rec.disconnect()
    except BaseException:
        _drop_empty(out, sink.frames)
        raise
    if run.stopped_by is not None:
        _drop_empty(out, sink.frames)
    return ReplaySummary(
        log=drive.info.path,
        source_format=drive.info.source_format,
        frames=sink.frames,
        actors_seen=len(sink.actor_ids),
        duration_s=sink.duration_s,
        output=to,
        elapsed_s=time.perf_counter() - t0,
        violations=tuple(detector.violations()),
        unsafe_frames={n: detector.unsafe_per_engine.get(n, 0) for n in run.engine_names},
        stopped_by=run.stopped_by,
        incidents=found,
    )


def _drop_empty(out: Path | None, frames: int) -> None:
    """Remove the ``.rrd`` of a failed run that holds no frame (no empty file left behind)."""
    if out is not None and frames == 0:
        out.unlink(missing_ok=True)


def _with_first(first: Chunk | None, rest: Iterator[Chunk]) -> Iterator[Chunk]:
    if first is not None:
        yield first
        yield from rest
