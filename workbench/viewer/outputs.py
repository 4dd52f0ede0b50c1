"""Replay a drive into Rerun: an ``.rrd`` file, a spawned viewer, or a local server.

Frames are read and sent in chunks (``CHUNK_FRAMES``) so memory stays flat for long drives.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import signal
import socket
import subprocess
import sys
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import rerun as rr

from loaders.errors import LoaderError
from workbench.errors import WorkbenchError
from workbench.evaluate.violations import detect_violations
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.engines import EngineResultSink
from workbench.replay.layout import layout_chunk, layout_map
from workbench.replay.properties import drive_properties, recording_name
from workbench.replay.sink import RerunSink

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence

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
        stopped_by: The loader error that ended a truncated or corrupted log early; the
            output holds every frame read before it.
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

    @property
    def frames_per_s(self) -> float:
        """Throughput, load plus log."""
        return self.frames / self.elapsed_s if self.elapsed_s > 0 else float("inf")


class _UntilLoaderError:
    """Iterates frames until the loader raises; keeps the error for the end of the replay.

    A truncated or corrupted log yields every readable frame and then a ``LoaderError``;
    stopping cleanly there lets the sink finish the file for the frames that were read.
    """

    def __init__(self, frames: Iterator[Frame]) -> None:
        self._frames = frames
        self.error: LoaderError | None = None

    def __iter__(self) -> Iterator[Frame]:
        try:
            yield from self._frames
        except LoaderError as err:
            self.error = err


def _chunks(frames: Iterable[Frame], size: int) -> Iterator[list[Frame]]:
    it = iter(frames)
    while chunk := list(itertools.islice(it, size)):
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


@contextlib.contextmanager
def _attached(
    rec: rr.RecordingStream,
    blueprint: rr.blueprint.Blueprint,
    *,
    out: Path | None,
    spawn: bool,
    serve: bool,
    ports: tuple[int, int],
    bind: str,
) -> Iterator[str]:
    """Set the stream's sink and yield where the data goes (path or URL).

    A server started for ``serve`` is stopped when the block ends.
    """
    if sum((out is not None, spawn, serve)) != 1:
        raise ReplayError("choose exactly one of an output file, spawn or serve")
    if out is not None:
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ReplayError(f"cannot create {out.parent}: {err.strerror}") from err
        rec.save(out, default_blueprint=blueprint)
        yield str(out)
        return
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
        yield "viewer"
        return
    url, server = _serve(rec, blueprint, ports=ports, bind=bind)
    try:
        yield url
    finally:
        rec.disconnect()
        _stop(server)


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _stop(proc: subprocess.Popen[bytes]) -> None:
    """Terminate the server's whole process group and wait until it is gone."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, sig)
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline:
            proc.poll()
            if not _group_alive(proc.pid):
                return
            time.sleep(0.05)


def _wait_for_port(host: str, port: int, proc: subprocess.Popen[bytes], timeout_s: float) -> None:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise ReplayError(f"the Rerun server exited with code {proc.returncode}")
        with contextlib.suppress(OSError), socket.create_connection((host, port), timeout=0.2):
            return
        time.sleep(0.1)
    raise ReplayError(f"the Rerun server did not listen on {host}:{port} within {timeout_s} s")


def _serve(
    rec: rr.RecordingStream,
    blueprint: rr.blueprint.Blueprint,
    *,
    ports: tuple[int, int],
    bind: str,
) -> tuple[str, subprocess.Popen[bytes]]:
    """Start ``rerun --serve-web --bind BIND`` and connect the stream to its gRPC proxy.

    The SDK's in-process web server has no bind option and listens on every interface; the
    viewer's own server binds both the gRPC proxy and the web page to ``bind``.
    """
    grpc_port, web_port = ports
    viewer = Path(sys.executable).with_name("rerun")
    exe = str(viewer) if viewer.exists() else "rerun"
    cmd = [exe, "--serve-web", "--bind", bind, "--port", str(grpc_port)]
    cmd += ["--web-viewer-port", str(web_port)]
    with _viewer_analytics_off():
        try:
            # Own session: the ``rerun`` entry point runs the viewer binary as a child, and the
            # whole group must stop with the replay.
            proc = subprocess.Popen(  # noqa: S603 - fixed argv, no shell
                cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True
            )
        except OSError as err:
            raise ReplayError(f"cannot start the Rerun server {exe}: {err.strerror}") from err
    host = "127.0.0.1" if bind in {"0.0.0.0", "::"} else bind  # noqa: S104 - compared, not bound
    try:
        _wait_for_port(host, grpc_port, proc, timeout_s=20.0)
    except ReplayError:
        _stop(proc)
        raise
    uri = f"rerun+http://{host}:{grpc_port}/proxy"
    rec.connect_grpc(uri, default_blueprint=blueprint)
    return f"http://{host}:{web_port}/?url={uri}", proc


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
    bind: str = LOCALHOST,
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
        bind: With ``serve``, the address the gRPC proxy and the web viewer listen on.
        engines: Engine runners evaluated on every frame; their verdicts and geometry are
            logged beside the scene and merged into violation intervals.

    Returns:
        Counts and timings of the replay.
    """
    t0 = time.perf_counter()
    guarded = _UntilLoaderError(iter(drive.frames(start_ns, end_ns)))
    chunks = _chunks(guarded, chunk_frames)
    first = next(chunks, None)
    ego_start = (first[0].ego.x_m, first[0].ego.y_m) if first else None
    rec = rr.RecordingStream(APPLICATION_ID, recording_id=_recording_id(drive, start_ns, end_ns))
    sink = RerunSink(rec)
    with _attached(
        rec,
        replay_blueprint(ego_start, engines=[e.name for e in engines]),
        out=out,
        spawn=spawn,
        serve=serve,
        ports=ports,
        bind=bind,
    ) as output:
        return _stream(
            drive,
            rec,
            sink,
            output=output,
            engines=engines,
            chunks=itertools.chain([first] if first else [], chunks),
            t0=t0,
            progress=progress,
            on_served=on_served if serve else None,
            stopped_by=lambda: guarded.error,
        )


def _stream(
    drive: Drive,
    rec: rr.RecordingStream,
    sink: RerunSink,
    *,
    output: str,
    engines: Sequence[EngineRunner],
    chunks: Iterator[list[Frame]],
    t0: float,
    progress: Callable[[int], None] | None,
    on_served: Callable[[str], None] | None,
    stopped_by: Callable[[], LoaderError | None],
) -> ReplaySummary:
    """Send the static data and every chunk; then hand a served URL to ``on_served``."""
    info = drive.info
    lane_map = drive.lane_map
    pairs = ((chunk, layout_chunk(chunk)) for chunk in chunks)
    head = next(pairs, None)
    sink.send_static(
        name=recording_name(info),
        start_ns=int(head[1].t_ns[0]) if head is not None else info.start_ns,
        properties=drive_properties(info),
        map_layout=layout_map(lane_map) if lane_map is not None else None,
    )
    engine_sink = EngineResultSink(rec, engines)
    frames = 0
    ids: set[str] = set()
    t_first = t_last = 0
    for chunk, layout in itertools.chain([head] if head is not None else [], pairs):
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
    if on_served is not None:
        on_served(output)
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
        stopped_by=stopped_by(),
    )
