"""Replay a drive into Rerun: an ``.rrd`` file, a spawned viewer, or a local server.

Frames are read and sent in chunks (``CHUNK_FRAMES``) so memory stays flat for long drives.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import sys
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import rerun as rr

from workbench.errors import WorkbenchError
from workbench.evaluate.violations import detect_violations
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.engines import EngineResultSink
from workbench.replay.layout import ChunkLayout, layout_chunk, layout_map
from workbench.replay.properties import drive_properties, recording_name
from workbench.replay.sink import RerunSink

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator, Mapping, Sequence

    from loaders.drive import Drive
    from loaders.records import Frame
    from workbench.evaluate.pipeline import EngineRunner
    from workbench.evaluate.violations import Violation

__all__ = [
    "APPLICATION_ID",
    "CHUNK_FRAMES",
    "LOCALHOST",
    "ReplayError",
    "ReplaySummary",
    "replay_drive",
]

APPLICATION_ID = "rss-workbench"
CHUNK_FRAMES = 500
#: ``--serve`` binds the gRPC server here; Rerun's own default is every interface.
LOCALHOST = "127.0.0.1"


class ReplayError(WorkbenchError):
    """The replay could not be written or served."""


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

    @property
    def frames_per_s(self) -> float:
        """Throughput, load plus log."""
        return self.frames / self.elapsed_s if self.elapsed_s > 0 else float("inf")


def _chunks(frames: Iterator[Frame], size: int) -> Iterator[list[Frame]]:
    while chunk := list(itertools.islice(frames, size)):
        yield chunk


def _recording_id(drive: Drive, start_ns: int | None, end_ns: int | None) -> str:
    key = f"{drive.info.path.resolve()}|{start_ns}|{end_ns}"
    return str(uuid.uuid5(uuid.NAMESPACE_URL, key))


@contextlib.contextmanager
def _viewer_analytics_off() -> Iterator[None]:
    """Keep Rerun's usage analytics off in viewers started from here.

    rerun-sdk 0.41 reads no ``RERUN_ANALYTICS`` variable: the viewer skips analytics when
    ``CI`` is set (or when ``rerun analytics disable`` was run). ``CI`` is set only while a
    viewer or web server starts, so the child inherits it, then restored; set
    ``WORKBENCH_RERUN_ANALYTICS=1`` to leave the environment alone.
    """
    if os.environ.get("WORKBENCH_RERUN_ANALYTICS") == "1" or "CI" in os.environ:
        yield
        return
    os.environ["CI"] = "1"
    try:
        yield
    finally:
        os.environ.pop("CI", None)


def _attach(
    rec: rr.RecordingStream,
    blueprint: rr.blueprint.Blueprint,
    *,
    out: Path | None,
    spawn: bool,
    serve: bool,
    ports: tuple[int, int],
) -> str:
    """Set the stream's sink; return where the data goes (path or URL)."""
    if sum((out is not None, spawn, serve)) != 1:
        raise ReplayError("choose exactly one of an output file, spawn or serve")
    if out is not None:
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ReplayError(f"cannot create {out.parent}: {err.strerror}") from err
        rec.save(out, default_blueprint=blueprint)
        return str(out)
    if spawn:
        # The viewer shipped with rerun-sdk sits next to this interpreter, which need not be
        # on PATH (``.venv/bin/workbench`` run without activating the venv).
        viewer = Path(sys.executable).with_name("rerun")
        try:
            with _viewer_analytics_off():
                rr.spawn(
                    recording=rec,
                    default_blueprint=blueprint,
                    executable_path=str(viewer) if viewer.exists() else None,
                )
        except RuntimeError as err:
            raise ReplayError(f"cannot start the Rerun viewer: {err}".splitlines()[0]) from err
        return "viewer"
    grpc_port, web_port = ports
    with _viewer_analytics_off():
        server = rr.GrpcServerSink(bind_ip=LOCALHOST, port=grpc_port)
        rec.set_sinks(server, default_blueprint=blueprint)
        rr.serve_web_viewer(web_port=web_port, open_browser=False, connect_to=server.uri)
    return f"http://{LOCALHOST}:{web_port}/?url={server.uri}"


def replay_drive(
    drive: Drive,
    *,
    out: Path | None = None,
    spawn: bool = False,
    serve: bool = False,
    progress: Callable[[int], None] | None = None,
    start_ns: int | None = None,
    end_ns: int | None = None,
    chunk_frames: int = CHUNK_FRAMES,
    ports: tuple[int, int] = (9876, 9090),
    on_served: Callable[[str], None] | None = None,
    engines: Sequence[EngineRunner] = (),
) -> ReplaySummary:
    """Send a drive's map and frames to exactly one destination.

    Args:
        drive: An opened drive; the caller closes it.
        out: Write an ``.rrd`` file here (parent directories are created).
        spawn: Start a native viewer and stream to it.
        serve: Host a gRPC server on 127.0.0.1 plus the web viewer.
        progress: Called with the number of frames sent after each chunk.
        start_ns: Only frames at or after this time.
        end_ns: Only frames before this time.
        chunk_frames: Frames per columnar batch.
        ports: ``(grpc_port, web_port)`` for ``serve``.
        on_served: With ``serve``, called with the viewer URL once everything was sent; the
            server lives until it returns (the CLI waits for Ctrl-C there).
        engines: Engine runners evaluated on every frame; their verdicts and geometry are
            logged beside the scene and merged into violation intervals.

    Returns:
        Counts and timings of the replay.
    """
    info = drive.info
    t0 = time.perf_counter()
    chunks = _chunks(iter(drive.frames(start_ns, end_ns)), chunk_frames)
    first = next(chunks, None)
    first_layout: ChunkLayout | None = layout_chunk(first) if first else None
    ego_start = None
    if first_layout is not None:
        x, y = first_layout.ego.centre_m[0, :2]
        ego_start = (float(x), float(y))
    rec = rr.RecordingStream(APPLICATION_ID, recording_id=_recording_id(drive, start_ns, end_ns))
    sink = RerunSink(rec)
    output = _attach(
        rec,
        replay_blueprint(ego_start, engines=[e.name for e in engines]),
        out=out,
        spawn=spawn,
        serve=serve,
        ports=ports,
    )
    lane_map = drive.lane_map
    sink.send_static(
        name=recording_name(info),
        start_ns=int(first_layout.t_ns[0]) if first_layout is not None else info.start_ns,
        properties=drive_properties(info),
        map_layout=layout_map(lane_map) if lane_map is not None else None,
    )
    engine_sink = EngineResultSink(rec, engines)
    frames = 0
    ids: set[str] = set()
    t_first = t_last = 0
    pairs = itertools.chain(
        [(first, first_layout)] if first and first_layout else [],
        ((chunk, layout_chunk(chunk)) for chunk in chunks),
    )
    for chunk, layout in pairs:
        sink.send_chunk(layout)
        engine_sink.send_chunk(chunk, layout)
        if frames == 0:
            t_first = int(layout.t_ns[0])
        t_last = int(layout.t_ns[-1])
        frames += len(layout)
        ids.update(layout.actors.ids_seen)
        if progress is not None:
            progress(frames)
    sink.flush()
    if serve and on_served is not None:
        on_served(output)
    if out is not None:
        rec.disconnect()
    return ReplaySummary(
        log=info.path,
        source_format=info.source_format,
        frames=frames,
        actors_seen=len(ids),
        duration_s=(t_last - t_first) / 1e9,
        output=output,
        elapsed_s=time.perf_counter() - t0,
        violations=tuple(detect_violations(engine_sink.results, info.path.name)),
        unsafe_frames=engine_sink.unsafe_frames,
    )
