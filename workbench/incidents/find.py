"""Find a drive's incidents: open it, run the engines through the driver, merge the verdicts."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from workbench.driver.run import DriveRun
from workbench.drives import open_log
from workbench.incidents.content import drive_content_hash
from workbench.incidents.detect import IncidentDetector
from workbench.incidents.model import IncidentSettings

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    from loaders.drive import Drive, DriveInfo
    from loaders.errors import LoaderError
    from workbench.driver.run import EgoSize
    from workbench.engines.base import BoundRunner
    from workbench.incidents.model import Incident
    from workbench.quality import Finding

__all__ = ["IncidentReport", "IncidentRequest", "find_incidents"]


@dataclass(frozen=True, slots=True)
class IncidentRequest:
    """A drive and every setting that decides its verdicts and incidents.

    What every command that runs engines builds once from its options (``evaluate``,
    ``replay``, ``incidents``, ``review``, ``export``, ``demo``, ``batch``) and consumes:
    the drive, the drive-level options, the engines and each engine's own options object.
    It names no engine: the engines' options are whatever their specs declare.

    Attributes:
        log: The drive file or rosbag2 directory.
        engines: Engine names, in order.
        map_path: Lane map file (``--map``).
        profile: TOML topic profile.
        ego_id: CommonRoad ego id.
        ego_topic: Ego topic of a ROS/MCAP log.
        settings: Minimum duration and gap merging.
        ego_size: ``--ego-size`` for every engine and the viewer (``None``: the log's, else
            the loaders' default).
        options: Each registered engine's options object by engine name (an engine missing
            here runs with its defaults).
        url: The drive's fsspec URL when it is not a local path (``workbench batch``): the
            batch task fetches it where it runs and evaluates the local copy, ``log``
            (until then ``log`` is the URL's last component and is not opened).
    """

    log: Path
    engines: tuple[str, ...]
    map_path: Path | None = None
    profile: Path | None = None
    ego_id: str | None = None
    ego_topic: str | None = None
    settings: IncidentSettings = field(default_factory=IncidentSettings)
    ego_size: EgoSize | None = None
    options: Mapping[str, Any] = field(default_factory=dict)
    url: str | None = None

    @property
    def location(self) -> str:
        """The drive as its user named it: the URL, else the path."""
        return str(self.log) if self.url is None else self.url

    def options_of(self, name: str) -> Any:
        """Engine ``name``'s options object (its defaults when the request has none)."""
        from workbench.engines.registry import engine  # noqa: PLC0415

        own = self.options.get(name)
        return engine(name).options() if own is None else own

    def with_options(self, name: str, options: Any) -> IncidentRequest:
        """The same request with engine ``name``'s options replaced."""
        return dataclasses.replace(self, options={**self.options, name: options})

    def open_drive(self) -> Drive:
        """Open the drive with these settings (the caller closes it).

        Raises:
            WorkbenchError: The log does not exist.
            LoaderError: The loader cannot read it.
        """
        return open_log(
            self.log,
            map_path=self.map_path,
            profile=self.profile,
            ego_id=self.ego_id,
            ego_topic=self.ego_topic,
        )

    def engines_for(
        self, drive: Drive, *, full_geometry: bool = False
    ) -> tuple[list[BoundRunner], EgoSize | None]:
        """Fresh runners of the requested engines for an opened drive, and the ego size.

        Each runner is built from its engine's own options (an ``auto`` profile reads the
        drive's map). ``full_geometry``: compute what a viewer draws too (replays), not
        only the verdicts.

        Raises:
            WorkbenchError: Unknown engine or an engine's unreadable file.
        """
        from workbench.engines.registry import build_runners  # noqa: PLC0415

        runners = build_runners(
            list(self.engines), drive.lane_map, self.options, full_geometry=full_geometry
        )
        return runners, self.ego_size

    def record(self) -> dict[str, Any]:
        """The settings that produced the incidents, as stored beside every label.

        Every registered engine's options by their flag (``reach_method``), file options as
        the content hash of the file (``rss_params_sha256``).
        """
        from workbench.engines.registry import cli_options  # noqa: PLC0415

        options: dict[str, Any] = {}
        files = {"map": self.map_path, "profile": self.profile}
        for key, (declared, engines) in cli_options().items():
            value = getattr(self.options_of(engines[0]), declared.name)
            if declared.kind is Path:
                files[key] = value
            else:
                options[key] = declared.recorded(value)
        size = {} if self.ego_size is None else {"ego_size_m": [*self.ego_size.fields().values()]}
        return {
            "engines": list(self.engines),
            **options,
            "ego_id": self.ego_id,
            "ego_topic": self.ego_topic,
            **size,
            **{
                f"{name}_sha256": None if path is None else drive_content_hash(path)
                for name, path in files.items()
            },
            "min_duration_s": self.settings.min_duration_s,
            "merge_gap_s": self.settings.merge_gap_s,
        }

    def report(
        self, detector: IncidentDetector, info: DriveInfo, stopped_by: LoaderError | None
    ) -> IncidentReport:
        """The incidents ``detector`` found over one pass of this request's drive.

        Args:
            detector: Fed with every chunk of the pass (its drive hash is the report's).
            info: The drive's metadata after the pass.
            stopped_by: The loader error that ended the pass early, if any.
        """
        findings = detector.findings()
        return IncidentReport(
            log=self.log,
            drive_hash=detector.drive_hash,
            settings=self.record(),
            incidents=tuple(detector.incidents(findings)),
            frame_times=tuple(detector.frame_times),
            start_ns=info.start_ns,
            stopped_by=stopped_by,
            ego_at_start_m=dict(detector.ego_at_start_m),
            objects_at_start_m=dict(detector.objects_at_start_m),
            request=self,
            findings=findings,
            info=info,
        )


@dataclass(frozen=True, slots=True)
class IncidentReport:
    """A drive's incidents and what they were found with.

    Attributes:
        log: The drive.
        drive_hash: Content hash of the drive (:func:`drive_content_hash`).
        settings: :meth:`IncidentRequest.record`.
        incidents: Worst first.
        frame_times: ``(frame index, t_ns)`` of every frame evaluated.
        start_ns: The drive's first time stamp.
        stopped_by: The loader error that ended a truncated log early, if any.
        ego_at_start_m: Ego position ``(x, y)`` [m] at each incident's first frame.
        objects_at_start_m: Positions ``(x, y)`` [m] of the culprits at each incident's first
            frame, by object id.
        request: What the incidents were found with.
        findings: The drive's data-quality findings (:mod:`workbench.quality`).
        info: The drive's metadata after the pass (format, duration, loss notes).
    """

    log: Path
    drive_hash: str
    settings: dict[str, Any]
    incidents: tuple[Incident, ...]
    frame_times: tuple[tuple[int, int], ...]
    start_ns: int
    stopped_by: LoaderError | None = None
    ego_at_start_m: Mapping[int, tuple[float, float]] = field(default_factory=dict)
    objects_at_start_m: Mapping[int, Mapping[str, tuple[float, float]]] = field(
        default_factory=dict
    )
    request: IncidentRequest | None = None
    findings: tuple[Finding, ...] = ()
    info: DriveInfo | None = None

    def find(self, incident_id: str) -> Incident | None:
        """The incident of that id, if the drive has one."""
        return next((i for i in self.incidents if i.id == incident_id), None)


def find_incidents(
    request: IncidentRequest,
    progress: Callable[[int], None] | None = None,
    window: tuple[int | None, int | None] = (None, None),
) -> IncidentReport:
    """Evaluate the drive with the requested engines and merge the verdicts into incidents.

    Args:
        request: Drive and settings.
        progress: Called with the number of frames evaluated after each chunk.
        window: ``(start_ns, end_ns)``: only the frames in ``[start_ns, end_ns)``.

    Raises:
        WorkbenchError: Missing log, unknown engine, unreadable settings file.
        LoaderError: The log cannot be opened.
    """
    drive_hash = drive_content_hash(request.log) if request.log.exists() else ""
    drive = request.open_drive()
    try:
        runners, ego = request.engines_for(drive)
        run = DriveRun(drive, runners, start_ns=window[0], end_ns=window[1], ego_size=ego)
        detector = IncidentDetector(drive_hash, request.settings)
        for chunk in run:
            detector.add_chunk(chunk)
            if progress is not None:
                progress(len(detector.frame_times))
        info = drive.info
    finally:
        drive.close()
    return request.report(detector, info, run.stopped_by)
