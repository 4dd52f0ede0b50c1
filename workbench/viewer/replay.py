"""Replay a drive into Rerun: one pass of the driver's chunks, sent to one destination.

The jobs are apart: :class:`~workbench.viewer.drive_pass.DrivePass` builds the run and feeds
each chunk once to the Rerun sink, the violation intervals and the incident detector;
:class:`~workbench.viewer.outputs.Destination` is where the recording goes. Frames are read,
evaluated and sent in chunks so memory stays flat for long drives.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from workbench.replay.blueprint import replay_blueprint
from workbench.sinks.rerun_drive import SEND_FRAMES
from workbench.viewer.drive_pass import (
    APPLICATION_ID,
    DrivePass,
    FeedSettings,
    PassWindow,
    ReplaySummary,
    recording_id,
)
from workbench.viewer.outputs import LOCALHOST, Destination

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from workbench.driver.run import EgoSize
    from workbench.engines.base import BoundRunner
    from workbench.incidents import IncidentSettings
    from workbench.replay.highlight import CulpritBoxes
    from workbench.replay.short_labels import ShortLabels

__all__ = ["APPLICATION_ID", "ReplaySummary", "drop_empty", "recording_id", "replay_drive"]


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
    engines: Sequence[BoundRunner] = (),
    bind: str = LOCALHOST,
    send_frames: int = SEND_FRAMES,
    ego_size: EgoSize | None = None,
    incident_settings: IncidentSettings | None = None,
    connect: str | None = None,
    selection: tuple[int, int] | None = None,
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
        connect: Stream to a running viewer's gRPC proxy (``rerun+http://HOST:PORT/proxy``).
        selection: ``(first, last)`` frame of an incident: the blueprint's time panel selects
            and loops over it (a clip's review blueprint).
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
    destination = Destination(
        out=out,
        spawn=spawn,
        serve=serve,
        connect=connect,
        bind=bind,
        ports=ports,
    )
    one = DrivePass(
        drive,
        engines,
        window=PassWindow(start_ns, end_ns),
        ego_size=ego_size,
        settings=FeedSettings(incident_settings, send_frames, labels, culprits),
    )
    blueprint = replay_blueprint(one.ego_start_m, engines=one.engine_names, selection=selection)
    try:
        with destination.attach(one.recording, blueprint) as to:
            one.stream(progress)
            found = one.found()
            one.send_incidents(found, {})
            if on_served is not None and serve:
                on_served(to)
            one.recording.disconnect()
    except BaseException:
        drop_empty(out, one.sink.frames)
        raise
    if one.run.stopped_by is not None:
        drop_empty(out, one.sink.frames)
    return one.summary(to, time.perf_counter() - t0, found)


def drop_empty(out: Path | None, frames: int) -> None:
    """Remove the ``.rrd`` of a failed run that holds no frame (no empty file left behind)."""
    if out is not None and frames == 0:
        out.unlink(missing_ok=True)
