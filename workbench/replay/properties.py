"""Recording properties of a replay: the drive's metadata, decided here, sent by the sink.

Pure: no Rerun import. Properties appear in the viewer's recording panel and in
``property:<name>:<field>`` columns when an ``.rrd`` is read back.
"""

from __future__ import annotations

import platform
from importlib import metadata
from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.drive import DriveInfo

__all__ = ["PropertyValue", "drive_properties", "recording_name", "software_properties"]

#: Distributions whose versions decide the verdicts and the recording.
_VERSIONED = ("rss-workbench", "rerun-sdk", "numpy", "shapely", "mcap", "rosbags")

PropertyValue = str | int | float


def recording_name(info: DriveInfo) -> str:
    """Name shown for the recording: the log's file name and its format."""
    return f"{info.path.name} ({info.source_format})"


def drive_properties(info: DriveInfo) -> dict[str, dict[str, PropertyValue]]:
    """Property name to fields for a drive.

    ``drive`` holds what was detected (path, format, roles, clock, matching tolerance, frame
    count, map source, time span); ``notes`` holds the loader's free-form notes, if any.

    Args:
        info: What the loader detected about the drive.
    """
    roles = info.roles
    drive: dict[str, PropertyValue] = {
        "path": str(info.path),
        "format": info.source_format,
        "ego_topic": roles.ego,
        "object_topics": ", ".join(roles.objects),
        "plan_topic": roles.plan or "",
        "clock": info.clock,
        "match_tolerance_s": ns_to_s(info.match_tolerance_ns),
        "frame_count": int(info.frame_count),
        "map_source": info.map_source or "",
        "start_ns": int(info.start_ns),
        "end_ns": int(info.end_ns),
        "duration_s": info.duration_s,
    }
    out: dict[str, dict[str, PropertyValue]] = {"drive": drive}
    if info.notes:
        out["notes"] = {key: str(value) for key, value in sorted(info.notes.items())}
    return out


def _version(distribution: str) -> str:
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return "not installed"


def software_properties(engines: Sequence[str]) -> dict[str, dict[str, PropertyValue]]:
    """``software``: the engines that ran and the versions of what produced the recording.

    The engines are part of ``rss-workbench``: their version is the workbench's.
    """
    software: dict[str, PropertyValue] = {
        "engines": ", ".join(engines) or "none",
        "python": platform.python_version(),
    }
    for distribution in _VERSIONED:
        software[distribution.replace("-", "_")] = _version(distribution)
    return {"software": software}
