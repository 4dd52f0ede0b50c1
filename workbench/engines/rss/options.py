"""The options of the RSS engines (structured and unstructured): parameter profile and file.

``--rss-profile NAME`` picks a named parameter profile (``auto``: by the drive's road,
:mod:`workbench.engines.rss.auto_profile`); ``--rss-params FILE.toml`` overrides any of its
values (docs/rss.md). In a ``--settings`` file: ``[rss] profile = "highway"``,
``params = "dynamics.toml"`` (relative to the settings file).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path  # noqa: TC003 - the options' type hints are read at run time
from typing import TYPE_CHECKING

from rss.profiles import ProfileName
from workbench.engines.options import option
from workbench.engines.rss.auto_profile import AUTO
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.params import RssParams
    from workbench.driver.run import EgoSize
    from workbench.engines.base import EngineRunner, Verdict

__all__ = ["RssOptions", "SceneEgoRunner", "describe", "load_params", "scene_sized", "what_if"]

#: ``--rss-profile`` choices.
CHOICES = (AUTO, *ProfileName)


@dataclass(frozen=True, slots=True)
class RssOptions:
    """What the RSS engines read besides the drive.

    Attributes:
        params: ``--rss-params`` TOML over the profile; ``None``: the profile's values.
        profile: ``--rss-profile``: a profile name or ``auto``; ``None`` (not given):
            ``auto`` without a file, the file's profile (else ``adrss-5.0``) with one.
    """

    params: Path | None = option(
        None, flag="--rss-params", help="TOML with RSS dynamics and [scene] settings."
    )
    profile: str | None = option(
        None,
        flag="--rss-profile",
        record=lambda name: name or AUTO,
        help=(
            f"RSS parameter profile: {', '.join(ProfileName)}, or auto (highway on roads with "
            "speed limits >= 70 km/h, urban on other maps; docs/rss.md)."
        ),
    )

    def __post_init__(self) -> None:
        """Refuse an unknown profile name."""
        if self.profile is not None and self.profile not in CHOICES:
            msg = f"profile {self.profile!r} (--rss-profile): choose one of {', '.join(CHOICES)}"
            raise ValueError(msg)


def load_params(options: RssOptions, lane_map: LaneMap | None) -> RssParams:
    """The RSS parameters the options name for a drive with ``lane_map``.

    Without a file: the named profile; ``auto`` chooses by the drive's road
    (:func:`~workbench.engines.rss.auto_profile.auto_profile`, docs/rss.md). With a file: its
    tables over the profile it or ``--rss-profile`` names (a file naming none starts from
    ``adrss-5.0``, the library defaults, as before profiles existed).

    Raises:
        WorkbenchError: The file cannot be read.
        RssParameterError: The TOML is malformed or has an unknown table, key or bad value,
            or it names a profile contradicting ``--rss-profile``.
    """
    from rss.params import parse_rss_params, rss_params_from_mapping  # noqa: PLC0415
    from workbench.engines.rss.auto_profile import auto_profile  # noqa: PLC0415

    path, profile = options.params, options.profile
    if profile == AUTO or (profile is None and path is None):
        profile = auto_profile(lane_map)
    if path is None:
        return rss_params_from_mapping({}, profile=profile)
    try:
        text = path.read_text()
    except OSError as err:
        raise WorkbenchError(f"--rss-params {path}: {err.strerror}") from err
    return parse_rss_params(text, profile=profile)


class SceneEgoRunner:
    """An RSS runner whose scene ego has the size of its ``[scene]`` parameters.

    ``[scene] ego_length / ego_width / ego_height`` of ``--rss-params`` (DESIGN.md's pinned
    file format) size the ego of the RSS engines' scene creation only, as ad-rss takes the
    ego's size as a scene-creation input; every engine's and the viewer's ego size is the
    drive option ``--ego-size`` (else the log's).
    """

    def __init__(self, runner: EngineRunner, size: EgoSize) -> None:
        """Wrap ``runner``; its frames get ``size`` for their ego."""
        self.name = runner.name
        self._runner = runner
        self._size = size

    def step_many(self, frames: Sequence[Frame]) -> Sequence[Verdict]:
        """The wrapped runner's verdicts on the frames with the scene's ego size."""
        return self._runner.step_many([self._size.apply(f) for f in frames])


def scene_sized(runner: EngineRunner, params: RssParams) -> EngineRunner:
    """``runner``, wrapped in :class:`SceneEgoRunner` when ``params`` size the ego."""
    from workbench.driver.run import EgoSize  # noqa: PLC0415

    scene = params.scene
    size = EgoSize(scene.ego_length_m, scene.ego_width_m, scene.ego_height_m)
    return SceneEgoRunner(runner, size) if size.fields() else runner


def what_if(options: RssOptions) -> tuple[tuple[str, RssOptions], ...]:
    """The review's what-if variants: every named profile in turn (the file kept)."""
    return tuple((name, dataclasses.replace(options, profile=name)) for name in sorted(ProfileName))


def describe(lane_map: LaneMap | None, options: RssOptions) -> str:
    """``rss profile [auto -> ]NAME: summary (key values)`` for ``workbench info``."""
    from rss.params import ObjectClass  # noqa: PLC0415 - keeps CLI start-up light
    from rss.profiles import profile  # noqa: PLC0415

    params = load_params(options, lane_map)
    ego, car = params.for_class(ObjectClass.EGO), params.for_class(ObjectClass.CAR)
    still = params.standstill_speed_mps
    rule = f"; standstill rule {still:g} m/s" if still > 0.0 else ""
    chosen = "auto -> " if options.profile in {None, AUTO} and options.params is None else ""
    return (
        f"rss profile {chosen}{params.profile_label}: {profile(params.profile).summary} "
        f"(ego rho {ego.response_time_s:g} s, a_max {ego.accel_max_mps2:g}, "
        f"b_min {ego.brake_min_mps2:g}; car rho {car.response_time_s:g} s, "
        f"b_max {car.brake_max_mps2:g} m/s^2{rule})"
    )
