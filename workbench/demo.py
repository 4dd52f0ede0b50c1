"""The demo run: every sample log of a directory evaluated, replayed into ``.rrd``, summarised.

Library side of ``workbench demo`` (the CLI only parses options and prints the table); the
benchmarks use :func:`find_sample_logs` too.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from loaders import is_drive_path
from workbench.drives import default_output
from workbench.engines.registry import user_errors

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from workbench.driver.run import EgoSize
    from workbench.engines.base import BoundRunner
    from workbench.incidents import IncidentRequest
    from workbench.viewer.replay import ReplaySummary

__all__ = ["DemoRow", "find_sample_logs", "output_names", "primary_logs", "replay_one"]

#: Which log keeps the plain ``<stem>.rrd`` name when several share a stem (lowest first).
_NAME_PRIORITY = {".mcap": 0, "": 1, ".bag": 2, ".xml": 3}


def _drive_key(log: Path) -> str:
    """Name of the drive a log holds: ``x.mcap``, ``x.bag`` and ``x_rosbag2/`` hold drive ``x``."""
    return log.name.removesuffix(log.suffix).removesuffix("_rosbag2")


def primary_logs(logs: list[Path]) -> set[Path]:
    """One log per drive to evaluate: the ``.mcap`` if there is one, else a rosbag2, else a bag."""
    best: dict[str, Path] = {}
    for log in sorted(logs, key=lambda p: (_NAME_PRIORITY.get(p.suffix.lower(), 9), p.name)):
        best.setdefault(_drive_key(log), log)
    return set(best.values())


def find_sample_logs(samples_dir: Path) -> list[Path]:
    """Drives directly in ``samples_dir``, sorted by name.

    Drives are ``*.mcap``, ``*.bag``, bare rosbag2 ``*.db3``, CommonRoad ``*.xml`` and
    ScenarioArchitect ``*.saa``/``*.scn`` files and rosbag2 directories (a directory holding
    ``metadata.yaml``).
    """
    found = [p for p in samples_dir.iterdir() if is_drive_path(p)]
    return sorted(found, key=lambda p: p.name)


def output_names(logs: list[Path]) -> dict[Path, str]:
    """``.rrd`` file name per log, never the same for two logs.

    A log gets ``<stem>.rrd``, or ``<stem>_<suffix>.rrd`` when its stem is already taken; an
    ``.mcap`` keeps the plain name first, then a rosbag2 directory, then a ``.bag``.
    """
    taken: set[str] = set()
    names: dict[Path, str] = {}
    for log in sorted(logs, key=lambda p: (_NAME_PRIORITY.get(p.suffix.lower(), 9), p.name)):
        stem = default_output(log, log.parent).stem
        if stem in taken:
            stem = f"{stem}_{log.suffix.lstrip('.').lower() or 'dir'}"
        taken.add(stem)
        names[log] = f"{stem}.rrd"
    return names


@dataclass(frozen=True, slots=True)
class DemoRow:
    """One line of the summary table; ``error`` is set when the log could not be replayed."""

    log: str
    source_format: str = ""
    frames: int = 0
    actors: int = 0
    duration_s: float = 0.0
    frames_per_s: float = 0.0
    output: str = ""
    unsafe: dict[str, int] | None = None
    violations: int | None = None
    error: str = ""


def replay_one(
    request: IncidentRequest,
    target: Path,
    replay: Callable[[Drive, Path, Sequence[BoundRunner], EgoSize | None], ReplaySummary],
) -> DemoRow:
    """Evaluate and replay the request's log into ``target`` with its engines.

    ``replay(drive, target, runners, ego_size)`` does the replay. Errors of the user's input
    become the row's ``error``; the other logs go on.
    """
    log, engine_names = request.log, request.engines
    try:
        drive = request.open_drive()
        try:
            runners, ego_size = request.engines_for(drive, full_geometry=True)
            s = replay(drive, target, runners, ego_size)
        finally:
            drive.close()
    except user_errors() as err:
        return DemoRow(log=log.name, error=str(err))
    if s.stopped_by is not None and not s.frames:
        return DemoRow(log=log.name, error=f"no frame read (no {target.name}): {s.stopped_by}")
    if s.stopped_by is not None:
        return DemoRow(
            log=log.name, error=f"{s.frames} frames kept in {target}, then: {s.stopped_by}"
        )
    return DemoRow(
        log=log.name,
        source_format=s.source_format,
        frames=s.frames,
        actors=s.actors_seen,
        duration_s=s.duration_s,
        frames_per_s=s.frames_per_s,
        output=target.name,
        unsafe=dict(s.unsafe_frames) if engine_names else None,
        violations=len(s.violations) if engine_names else None,
    )
