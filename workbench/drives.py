"""Opening drives and reading the user's run settings, for every command (library, not CLI)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from loaders.timebase import s_to_ns
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.drive import Drive
    from workbench.driver.run import EgoSize

__all__ = [
    "default_output",
    "open_log",
    "parse_ego_size",
    "window_ns",
]


def default_output(log: Path, out_dir: Path) -> Path:
    """``<out_dir>/<log stem>.rrd``; a rosbag2 directory keeps its whole name."""
    stem = log.name if log.is_dir() else log.stem
    return out_dir / f"{stem}.rrd"


def window_ns(
    drive: Drive, start_s: float | None, end_s: float | None
) -> tuple[int | None, int | None]:
    """Turn ``--start``/``--end`` seconds from the drive start into absolute nanoseconds."""
    t0 = drive.info.start_ns
    start = None if start_s is None else t0 + s_to_ns(start_s)
    end = None if end_s is None else t0 + s_to_ns(end_s)
    return start, end


def open_log(
    log: Path,
    *,
    map_path: Path | None,
    profile: Path | None,
    ego_id: str | None,
    ego_topic: str | None = None,
) -> Drive:
    """Open a drive with ``loaders.open_drive``, turning a missing path into a one-line error.

    Raises:
        WorkbenchError: ``log`` does not exist.
        LoaderError: The loader cannot read it (its own one-line message).
    """
    from loaders import open_drive  # noqa: PLC0415 - keeps CLI start-up light

    if not log.exists():
        raise WorkbenchError(f"{log}: no such file or directory")
    return open_drive(log, map=map_path, profile=profile, ego_id=ego_id, ego_topic=ego_topic)


def parse_ego_size(text: str) -> EgoSize:
    """``--ego-size L,W[,H]`` [m] as an :class:`EgoSize` (no height: the frame's).

    The ego's size of every engine and the viewer: this option, else the log's (CommonRoad
    obstacle shape, ScenarioArchitect vehicle, OSI host vehicle), else the one default
    ``loaders.records.DEFAULT_EGO_*`` (4.5 x 2.0 x 1.5 m).

    Raises:
        WorkbenchError: Not two or three positive, finite numbers.
    """
    from workbench.driver.run import EgoSize  # noqa: PLC0415 - keeps CLI start-up light

    parts = text.split(",")
    try:
        sizes = [float(p) for p in parts]
    except ValueError:
        sizes = []
    if len(sizes) not in {2, 3} or not all(0.0 < s < math.inf for s in sizes):
        msg = f"--ego-size {text!r}: give length,width[,height] in metres, e.g. 4.5,2.0,1.5"
        raise WorkbenchError(msg)
    return EgoSize(*sizes)
