"""Start the review loop: one pass over the drive into a viewer, then the UI after the pass.

:func:`replayed` evaluates the drive once: that pass streams the scene and verdicts into the
viewer and finds the incidents (or, for a batch's results, takes the report read back from
them), so the engines run once per frame. The caller then builds the review session from
:attr:`LiveReplay.report` and runs the UI with :meth:`LiveReplay.review`, outside the pass,
while the viewer (a served one too) is still attached.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import TYPE_CHECKING
from urllib.parse import parse_qs, urlsplit

from workbench.errors import WorkbenchError
from workbench.incidents import IncidentReport
from workbench.review.app import ReviewApp
from workbench.review.viewer import RerunLink

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

    from workbench.incidents import IncidentRequest
    from workbench.replay.short_labels import ShortLabels
    from workbench.review.fleet import FleetSession
    from workbench.review.session import ReviewSession
    from workbench.review.viewer import ViewerLink
    from workbench.viewer.drive_pass import DrivePass
    from workbench.viewer.outputs import Destination
    from workbench.viewer.web_cursor import WebCursor

__all__ = ["SPAWN_URL", "LiveReplay", "drive_link", "replayed", "run_review"]

#: gRPC proxy of a viewer started by ``rr.spawn`` (its default port).
SPAWN_URL = "rerun+http://127.0.0.1:9876/proxy"


def run_review(session: ReviewSession | FleetSession, viewer: ViewerLink | None = None) -> None:
    """Run the terminal UI until the reviewer quits."""
    ReviewApp(session, viewer).run()


@dataclass(slots=True)
class LiveReplay:
    """A drive streamed into a viewer that stays attached, and the incidents of that pass.

    Attributes:
        report: The drive's incidents (found in the pass, or the batch's report).
        labels: The drive's short-label table as the viewer draws it (the session's).
        grpc_url: The viewer's gRPC proxy, for the review's stream.
        served: The web viewer's address (``serve``), else ``None``.
    """

    report: IncidentReport
    labels: ShortLabels
    grpc_url: str
    served: str | None
    _pass: DrivePass
    _web_cursor: WebCursor | None

    def link(self, session: ReviewSession) -> RerunLink:
        """Send the incidents' lanes with the session's verdicts; the viewer's link for the UI.

        The lanes show every incident of the drive; the session's (possibly filtered)
        incidents are what the UI walks. The caller closes the link.
        """
        from workbench.viewer.replay import APPLICATION_ID  # noqa: PLC0415 - Rerun with a viewer

        one = self._pass
        verdicts = {key: label.verdict for key, label in session.labels.items()}
        one.send_incidents(self.report.incidents, verdicts)
        if self.served is None:
            one.recording.disconnect()  # the review's own stream joins the same recording
        else:
            one.recording.flush()
        link = RerunLink(
            self.grpc_url,
            application_id=APPLICATION_ID,
            recording_id=one.recording_id,
            ego_start_m=one.ego_start_m,
            engines=one.engine_names,
            ego_at_m=session.report.ego_at_start_m,
            objects_at_m=session.report.objects_at_start_m,
            cursor=self._web_cursor,
            positions=one.culprits,
        )
        if self._web_cursor is not None:
            self._web_cursor.on_loaded = link.show_again
        return link

    def review(self, session: ReviewSession) -> None:
        """Run the UI over ``session`` with this viewer (:meth:`link`)."""
        link = self.link(session)
        try:
            run_review(session, link)
        finally:
            link.close()


@contextlib.contextmanager
def replayed(
    source: IncidentReport | IncidentRequest,
    destination: Destination,
    progress: Callable[[int], None] | None = None,
) -> Iterator[LiveReplay]:
    """Evaluate the drive once into a viewer; yield its incidents with the viewer attached.

    Args:
        source: What finds the incidents (they are found in the pass), or a report of them
            (a batch's: the pass only draws; its ``request`` says with what).
        destination: A spawned (``spawn``), served (``serve``, with its ``web_cursor``) or
            running (``connect``) viewer.
        progress: Called with the number of frames evaluated after each chunk.

    Raises:
        WorkbenchError: A report without the request it was found with.
        LoaderError: The drive cannot be read.
    """
    from workbench.replay.blueprint import replay_blueprint  # noqa: PLC0415 - Rerun only here
    from workbench.replay.incidents import short_labels  # noqa: PLC0415
    from workbench.viewer.drive_pass import DrivePass, FeedSettings  # noqa: PLC0415

    found = source if isinstance(source, IncidentReport) else None
    request = source.request if isinstance(source, IncidentReport) else source
    if request is None:
        raise WorkbenchError("this review session has no drive to replay")
    drive = request.open_drive()
    try:
        runners, ego = request.engines_for(drive, full_geometry=True)
        one = DrivePass(
            drive,
            runners,
            ego_size=ego,
            settings=FeedSettings(
                request.settings, labels=None if found is None else short_labels(found.incidents)
            ),
        )
        blueprint = replay_blueprint(one.ego_start_m, engines=one.engine_names)
        with destination.attach(one.recording, blueprint) as to:
            one.stream(progress)
            report = found or request.report(one.incidents, drive.info, one.run.stopped_by)
            served = to if destination.serve else None
            grpc_url = parse_qs(urlsplit(to).query)["url"][0] if served else to
            if to == "viewer":
                grpc_url = SPAWN_URL
            yield LiveReplay(report, one.sink.labels, grpc_url, served, one, destination.web_cursor)
    finally:
        drive.close()


@contextlib.contextmanager
def drive_link(
    report: IncidentReport, session: ReviewSession, destination: Destination
) -> Iterator[ViewerLink]:
    """A batch's drive drawn into the viewer (its incidents are ``report``'s); its link.

    For a review queue across drives: the UI is up, so no progress bar; the pass and the
    link end when the caller leaves the drive.
    """
    with replayed(report, destination) as live:
        link = live.link(session)
        try:
            yield link
        finally:
            link.close()
