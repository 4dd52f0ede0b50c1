"""Start the review loop: optionally replay the drive into a viewer, then run the UI."""

from __future__ import annotations

from typing import TYPE_CHECKING
from urllib.parse import parse_qs, urlsplit

from workbench.errors import WorkbenchError
from workbench.review.app import ReviewApp
from workbench.review.viewer import RerunLink

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from loaders.drive import Drive
    from workbench.driver.run import EgoSize
    from workbench.engines.base import EngineRunner
    from workbench.incidents import IncidentSettings
    from workbench.review.session import ReviewSession
    from workbench.review.viewer import ViewerLink

__all__ = ["SPAWN_URL", "review_in_viewer", "run_review"]

#: gRPC proxy of a viewer started by ``rr.spawn`` (its default port).
SPAWN_URL = "rerun+http://127.0.0.1:9876/proxy"


def run_review(session: ReviewSession, viewer: ViewerLink | None = None) -> None:
    """Run the terminal UI until the reviewer quits."""
    ReviewApp(session, viewer).run()


def review_in_viewer(
    session: ReviewSession,
    *,
    serve: bool,
    connect: str | None,
    bind: str,
    ports: tuple[int, int],
    announce: Callable[[str], None],
) -> None:
    """Replay the drive with its incidents into a viewer, then review with it following.

    The drive is opened again and evaluated with the settings the session's incidents were
    found with (``session.report.request``), now with the viewer's geometry. The viewer is
    spawned (native), served (web, on ``bind``) or already running (``connect``).

    Args:
        session: The review session.
        serve: Serve a web viewer (on ``bind``) instead of spawning a native one.
        connect: Use the running viewer at this gRPC proxy URL instead
            (``rerun+http://HOST:PORT/proxy``; e.g. ``rerun --headless --bind 127.0.0.1``).
        bind: Address ``serve`` listens on.
        ports: ``(grpc_port, web_port)`` of ``serve``.
        announce: Called with the web viewer URL (``serve``).
    """
    request = session.report.request
    if request is None:
        raise WorkbenchError("this review session has no drive to replay")
    drive = request.open_drive()
    try:
        runners, ego = request.engines_for(drive, full_geometry=True)
        _replay_and_review(
            session,
            drive,
            runners,
            serve=serve,
            connect=connect,
            bind=bind,
            ports=ports,
            incident_settings=request.settings,
            ego=ego,
            announce=announce,
        )
    finally:
        drive.close()


def _replay_and_review(
    session: ReviewSession,
    drive: Drive,
    runners: Sequence[EngineRunner],
    *,
    serve: bool,
    connect: str | None,
    bind: str,
    ports: tuple[int, int],
    incident_settings: IncidentSettings,
    ego: EgoSize | None,
    announce: Callable[[str], None],
) -> None:
    from workbench.replay.highlight import CulpritBoxes  # noqa: PLC0415
    from workbench.viewer.replay import (  # noqa: PLC0415 - Rerun only when a viewer is asked
        APPLICATION_ID,
        recording_id,
        replay_drive,
    )
    from workbench.viewer.web_cursor import WebCursor  # noqa: PLC0415

    web_cursor = WebCursor() if serve else None
    positions = CulpritBoxes()  # filled by the replay: where the camera looks

    first = next(iter(drive.frames()), None)
    ego_start = (first.ego.x_m, first.ego.y_m) if first is not None else None
    names = [r.name for r in runners]
    rid = recording_id(drive, None, None)
    verdicts = {key: label.verdict for key, label in session.labels.items()}

    def loop(grpc_url: str) -> None:
        link = RerunLink(
            grpc_url,
            application_id=APPLICATION_ID,
            recording_id=rid,
            ego_start_m=ego_start,
            engines=names,
            ego_at_m=session.report.ego_at_start_m,
            objects_at_m=session.report.objects_at_start_m,
            cursor=web_cursor,
            positions=positions,
        )
        if web_cursor is not None:
            web_cursor.on_loaded = link.show_again
        try:
            run_review(session, link)
        finally:
            link.close()

    def served(url: str) -> None:
        announce(url)
        loop(parse_qs(urlsplit(url).query)["url"][0])

    replay_drive(
        drive,
        spawn=not serve and connect is None,
        serve=serve,
        connect=connect,
        bind=bind,
        ports=ports,
        engines=runners,
        on_served=served,
        incident_settings=incident_settings,
        verdicts=verdicts,
        ego_size=ego,
        web_cursor=web_cursor,
        culprits=positions,
        labels=session.short_labels,
    )
    if not serve:
        loop(connect or SPAWN_URL)
