"""TOML topic profiles: override detected topic roles, the frame clock and the tolerance.

Example::

    [topics]
    ego = "/localization/kinematic_state"
    objects = ["/perception/object_recognition/tracking/objects"]
    plan = "/planning/scenario_planning/trajectory"
    imu = "/sensing/imu/imu_data"   # heading for a NavSatFix ego

    [tf]                            # ego from /tf: the chain map (or odom) -> vehicle
    map_frame = "map"
    odom_frame = "odom"
    vehicle_frame = "base_link"

    [frames]
    clock = "log_time"          # or "header"
    match_tolerance_s = 0.15
    invalid_ego = "raise"       # or "skip" (count skipped frames in DriveInfo.notes)

Every key is optional. ``match_tolerance_s`` may also stand at the top level.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from loaders.errors import ProfileError
from loaders.message_logs.decoders.ros_tf import TfFrames
from loaders.timebase import s_to_ns

__all__ = ["CLOCKS", "DEFAULT_TOLERANCE_NS", "INVALID_EGO_POLICIES", "Profile", "load_profile"]

#: Allowed values of ``[frames] clock``.
CLOCKS: tuple[str, ...] = ("log_time", "header")
#: Allowed values of ``[frames] invalid_ego``.
INVALID_EGO_POLICIES: tuple[str, ...] = ("raise", "skip")
#: Default object matching tolerance (0.15 s).
DEFAULT_TOLERANCE_NS = 150_000_000


@dataclass(frozen=True, slots=True)
class Profile:
    """A parsed topic profile; ``None`` topics mean "detect from message types".

    Attributes:
        ego: Ego topic.
        objects: Object topics.
        plan: Plan topic.
        clock: ``log_time`` (recording time) or ``header`` (message header stamps).
        match_tolerance_ns: Maximum age of an object message matched to a frame.
        invalid_ego: ``raise`` on a non-finite ego pose, or ``skip`` the frame.
        imu: IMU topic giving the heading of a ``NavSatFix`` ego (default: detected).
        tf: Frame names of the ``/tf`` chain.
        source: The TOML file, if the profile came from one.
    """

    ego: str | None = None
    objects: tuple[str, ...] | None = None
    plan: str | None = None
    clock: str = "log_time"
    match_tolerance_ns: int = DEFAULT_TOLERANCE_NS
    invalid_ego: str = "raise"
    imu: str | None = None
    tf: TfFrames = field(default_factory=TfFrames)
    source: Path | None = None


def _topic(path: Path, table: dict[str, Any], key: str) -> str | None:
    value = table.get(key)
    if value is None or isinstance(value, str):
        return value
    raise ProfileError(path, f"[topics] {key} must be a string", value=value)


def _objects(path: Path, table: dict[str, Any]) -> tuple[str, ...] | None:
    value = table.get("objects")
    if value is None:
        return None
    if isinstance(value, str):
        return (value,)
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return tuple(value)
    raise ProfileError(path, "[topics] objects must be a string or a list of strings", value=value)


def _choice(path: Path, table: dict[str, Any], key: str, allowed: tuple[str, ...]) -> str:
    value = table.get(key, allowed[0])
    if value not in allowed:
        raise ProfileError(path, f"[frames] {key} must be one of {', '.join(allowed)}", value=value)
    return str(value)


def _tolerance_ns(path: Path, data: dict[str, Any], frames: dict[str, Any]) -> int:
    value = frames.get("match_tolerance_s", data.get("match_tolerance_s"))
    if value is None:
        return DEFAULT_TOLERANCE_NS
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ProfileError(path, "match_tolerance_s must be a number", value=value)
    if not math.isfinite(value) or value < 0:
        raise ProfileError(path, "match_tolerance_s must be finite and >= 0", value=value)
    return s_to_ns(value)


def _tf(path: Path, table: dict[str, Any]) -> TfFrames:
    names = {"map_frame", "odom_frame", "vehicle_frame"}
    if unknown := sorted(set(table) - names):
        raise ProfileError(path, f"[tf] unknown keys: {', '.join(unknown)}")
    for key, value in table.items():
        if not isinstance(value, str) or not value.strip("/"):
            raise ProfileError(path, f"[tf] {key} must be a frame name", value=value)
    default = TfFrames()
    return TfFrames(
        map_frame=str(table.get("map_frame", default.map_frame)).lstrip("/"),
        odom_frame=str(table.get("odom_frame", default.odom_frame)).lstrip("/"),
        vehicle_frame=str(table.get("vehicle_frame", default.vehicle_frame)).lstrip("/"),
    )


def _table(path: Path, data: dict[str, Any], key: str) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise ProfileError(path, f"[{key}] must be a table", value=value)
    return value


def load_profile(path: str | Path) -> Profile:
    """Parse a TOML profile.

    Args:
        path: The ``.toml`` file.

    Returns:
        The profile.

    Raises:
        ProfileError: The file is missing, not TOML, or has keys of the wrong type/value.
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as err:
        raise ProfileError(path, f"cannot read profile: {err.strerror}") from err
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise ProfileError(path, f"not valid TOML: {err}") from err
    known = {"topics", "frames", "tf", "match_tolerance_s"}
    if unknown := sorted(set(data) - known):
        raise ProfileError(path, f"unknown keys: {', '.join(unknown)}")
    topics = _table(path, data, "topics")
    frames = _table(path, data, "frames")
    return Profile(
        ego=_topic(path, topics, "ego"),
        objects=_objects(path, topics),
        plan=_topic(path, topics, "plan"),
        clock=_choice(path, frames, "clock", CLOCKS),
        match_tolerance_ns=_tolerance_ns(path, data, frames),
        invalid_ego=_choice(path, frames, "invalid_ego", INVALID_EGO_POLICIES),
        imu=_topic(path, topics, "imu"),
        tf=_tf(path, _table(path, data, "tf")),
        source=path,
    )
