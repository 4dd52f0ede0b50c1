"""Opening drives and reading the user's run settings, for every command (library, not CLI)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.timebase import s_to_ns
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.maps.model import LaneMap
    from rss.params import RssParams
    from workbench.driver.run import EgoSize

__all__ = [
    "default_output",
    "ego_size",
    "load_rss_params",
    "open_log",
    "rss_profile_line",
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


def load_rss_params(
    path: Path | None, profile: str | None = None, lane_map: LaneMap | None = None
) -> RssParams:
    """The RSS parameters of a command: ``--rss-profile NAME`` and ``--rss-params FILE.toml``.

    Without a file: the named profile; ``None`` or ``auto`` choose by the drive's road
    (:func:`workbench.engines.rss.auto_profile.auto_profile`, docs/rss.md). With a file: its
    tables over the profile it or ``--rss-profile`` names (a file naming none starts from
    ``adrss-5.0``, the library defaults, as before profiles existed).

    Args:
        path: ``--rss-params`` file, if any.
        profile: ``--rss-profile`` value, if given.
        lane_map: The drive's lane map (for ``auto``).

    Raises:
        WorkbenchError: The file cannot be read.
        RssParameterError: The TOML is malformed or has an unknown table, key or bad value,
            or the profile is unknown or contradicts the file's.
    """
    from rss.params import parse_rss_params, rss_params_from_mapping  # noqa: PLC0415
    from workbench.engines.rss.auto_profile import AUTO, auto_profile  # noqa: PLC0415

    if profile == AUTO or (profile is None and path is None):
        profile = auto_profile(lane_map)
    if path is None:
        return rss_params_from_mapping({}, profile=profile)
    try:
        text = path.read_text()
    except OSError as err:
        raise WorkbenchError(f"--rss-params {path}: {err.strerror}") from err
    return parse_rss_params(text, profile=profile)


def ego_size(params: RssParams | None) -> EgoSize | None:
    """The user's ego size of ``--rss-params [scene]`` (``None``: every frame keeps the log's)."""
    from workbench.driver.run import EgoSize  # noqa: PLC0415 - keeps CLI start-up light

    if params is None:
        return None
    scene = params.scene
    return EgoSize(scene.ego_length_m, scene.ego_width_m, scene.ego_height_m)


def rss_profile_line(params: RssParams) -> str:
    """``NAME: summary (key values)`` for ``workbench info``."""
    from rss.params import ObjectClass  # noqa: PLC0415 - keeps CLI start-up light
    from rss.profiles import profile  # noqa: PLC0415

    ego, car = params.for_class(ObjectClass.EGO), params.for_class(ObjectClass.CAR)
    still = params.standstill_speed_mps
    rule = f"; standstill rule {still:g} m/s" if still > 0.0 else ""
    return (
        f"{params.profile_label}: {profile(params.profile).summary} "
        f"(ego rho {ego.response_time_s:g} s, a_max {ego.accel_max_mps2:g}, "
        f"b_min {ego.brake_min_mps2:g}; car rho {car.response_time_s:g} s, "
        f"b_max {car.brake_max_mps2:g} m/s^2{rule})"
    )
