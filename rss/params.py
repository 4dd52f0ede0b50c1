"""The frozen RSS parameter set: dynamics per object class plus scene settings, from TOML.

TOML layout (``--rss-params``, see ``conformance/rss_params_example.toml``)::

    [ego]         RssDynamics keys of the ego vehicle
    [vehicle]     defaults for every vehicle class ...
    [car] [truck] [bus] [motorcycle] [bicycle]   ... refined per class
    [pedestrian]  RssDynamics keys of pedestrians
    [scene]       restrict_speed_limit_mode, constellation_creation_mode,
                  ego_length, ego_width, ego_height, reproduce_adrss_5_0_defects
    [review]      standstill_speed (m/s, >= 0; 0 = off): the review profiles' standstill
                  rule (:mod:`rss.structured.standstill`)
    profile = "NAME"   (top level, optional) a named profile of :mod:`rss.profiles`

Keys not given keep the profile's values; without a profile the documented defaults
(profile ``adrss-5.0``): ad-rss-lib's unit-test dynamics for the ego (rho = 1 s) and for
vehicles (rho = 2 s), CARLA's pedestrian dynamics for pedestrians.
"""

from __future__ import annotations

import enum
import math
import tomllib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeVar

from rss.dynamics import RssDynamics
from rss.errors import RssParameterError
from rss.profiles import LIBRARY_PROFILE, merged_tables

if TYPE_CHECKING:
    from collections.abc import Mapping

_E = TypeVar("_E", bound=enum.StrEnum)

__all__ = [
    "DEFAULT_EGO_DYNAMICS",
    "DEFAULT_PEDESTRIAN_DYNAMICS",
    "DEFAULT_VEHICLE_DYNAMICS",
    "ConstellationCreationMode",
    "ObjectClass",
    "RestrictSpeedLimitMode",
    "RssParams",
    "SceneSettings",
    "parse_rss_params",
    "rss_params_from_mapping",
]

#: ad-rss unit-test ego dynamics (``TestSupport.cpp``): response time 1 s.
DEFAULT_EGO_DYNAMICS = RssDynamics(response_time_s=1.0)
#: ad-rss unit-test dynamics of other vehicles: response time 2 s.
DEFAULT_VEHICLE_DYNAMICS = RssDynamics()
#: CARLA RssSensor pedestrian dynamics.
DEFAULT_PEDESTRIAN_DYNAMICS = RssDynamics(
    accel_max_mps2=2.0,
    brake_max_mps2=-4.0,
    brake_min_mps2=-2.0,
    brake_min_correct_mps2=-2.0,
    lat_accel_max_mps2=0.001,
    lat_brake_min_mps2=-0.001,
    lateral_fluctuation_margin_m=0.1,
    response_time_s=0.5,
    max_speed_on_acceleration_mps=10.0,
)


class ObjectClass(enum.StrEnum):
    """Object classes that carry their own dynamics (TOML table names)."""

    EGO = "ego"
    CAR = "car"
    TRUCK = "truck"
    BUS = "bus"
    MOTORCYCLE = "motorcycle"
    BICYCLE = "bicycle"
    PEDESTRIAN = "pedestrian"
    UNKNOWN = "unknown"


_VEHICLE_CLASSES = (
    ObjectClass.CAR,
    ObjectClass.TRUCK,
    ObjectClass.BUS,
    ObjectClass.MOTORCYCLE,
    ObjectClass.BICYCLE,
    ObjectClass.UNKNOWN,
)


class RestrictSpeedLimitMode(enum.StrEnum):
    """How scene creation writes ``max_speed_on_acceleration`` from lane speed limits."""

    NONE = "None"
    EXACT_SPEED_LIMIT = "ExactSpeedLimit"
    INCREASED_SPEED_LIMIT_5 = "IncreasedSpeedLimit5"
    INCREASED_SPEED_LIMIT_10 = "IncreasedSpeedLimit10"


class ConstellationCreationMode(enum.StrEnum):
    """Which kind of constellation scene creation builds for an ego/object pair."""

    STRUCTURED = "Structured"
    UNSTRUCTURED = "Unstructured"


@dataclass(frozen=True)
class SceneSettings:
    """Scene-creation settings and the user's ego size.

    Attributes:
        restrict_speed_limit_mode: Speed-limit mode of scene creation.
        constellation_creation_mode: Structured or unstructured constellations.
        ego_length_m: Ego length, > 0; ``None``: the size every frame carries (the log's,
            or the loaders' default; docs/architecture.md, "the ego's size").
        ego_width_m: Ego width, > 0, or ``None`` (as ``ego_length_m``).
        ego_height_m: Ego height, > 0, or ``None`` (as ``ego_length_m``).
        reproduce_adrss_5_0_defects: Reproduce two documented defects of ad-rss 5.0 /
            ad-map 5.0 in scene creation (docs/rss_scene.md, compatibility mode): the
            swapped route headings of an object following the ego, and ad-map's
            intersection turn directions from its defective ENU headings (with the ad-map /
            ad-rss rules that only matter together with them). Off by default; for
            reproducing what an onboard ad-rss 5.0 reported.
    """

    restrict_speed_limit_mode: RestrictSpeedLimitMode = (
        RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_10
    )
    constellation_creation_mode: ConstellationCreationMode = ConstellationCreationMode.STRUCTURED
    ego_length_m: float | None = None
    ego_width_m: float | None = None
    ego_height_m: float | None = None
    reproduce_adrss_5_0_defects: bool = False


def _default_classes() -> dict[ObjectClass, RssDynamics]:
    classes = dict.fromkeys(_VEHICLE_CLASSES, DEFAULT_VEHICLE_DYNAMICS)
    classes[ObjectClass.EGO] = DEFAULT_EGO_DYNAMICS
    classes[ObjectClass.PEDESTRIAN] = DEFAULT_PEDESTRIAN_DYNAMICS
    return classes


@dataclass(frozen=True)
class RssParams:
    """Dynamics per object class and scene settings.

    Attributes:
        dynamics: Dynamics of every :class:`ObjectClass` (all present).
        scene: Scene-creation settings.
        profile: Name of the :mod:`rss.profiles` profile the values start from.
        overridden: ``True`` when a ``--rss-params`` file changed any of the profile's
            values (outputs then name the profile with ``+file``).
        standstill_speed_mps: The standstill rule's threshold [m/s]
            (:mod:`rss.structured.standstill`, ``[review] standstill_speed``); 0 = off, as
            in ad-rss (the ``adrss-5.0`` and ``carla`` profiles).
    """

    dynamics: Mapping[ObjectClass, RssDynamics] = field(default_factory=_default_classes)
    scene: SceneSettings = field(default_factory=SceneSettings)
    profile: str = LIBRARY_PROFILE
    overridden: bool = False
    standstill_speed_mps: float = 0.0

    @property
    def profile_label(self) -> str:
        """The profile as every output records it: ``NAME`` or ``NAME+file``."""
        return f"{self.profile}+file" if self.overridden else self.profile

    def for_class(self, object_class: ObjectClass) -> RssDynamics:
        """Return the dynamics of one object class."""
        return self.dynamics[object_class]


def parse_rss_params(text: str, *, profile: str | None = None) -> RssParams:
    """Parse an ``--rss-params`` TOML document.

    Args:
        text: TOML text.
        profile: Profile chosen outside the file (``--rss-profile``); the file's own
            ``profile`` key must then name the same one.

    Returns:
        The validated parameter set.

    Raises:
        RssParameterError: Invalid TOML, unknown table or key, invalid value.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise RssParameterError("<toml>", str(err), "not valid TOML") from err
    return rss_params_from_mapping(data, profile=profile)


def rss_params_from_mapping(data: Mapping[str, object], *, profile: str | None = None) -> RssParams:
    """Build the parameter set from a parsed TOML mapping (tables as nested mappings).

    The profile (``profile`` argument, else the mapping's ``profile`` key, else
    ``adrss-5.0``) gives the starting values; the mapping's tables override them key by
    key. ``[vehicle]`` applies to every vehicle class first; ``[car]`` etc. refine it.

    Raises:
        RssParameterError: Unknown profile, table or key, invalid value, or a file profile
            that contradicts ``profile``.
    """
    named = data.get("profile")
    if named is not None and not isinstance(named, str):
        raise RssParameterError("profile", named, "must be a profile name (a string)")
    if profile is not None and named is not None and named != profile:
        raise RssParameterError("profile", named, f"contradicts --rss-profile {profile}")
    name = profile or named or LIBRARY_PROFILE
    own = {k: v for k, v in data.items() if k != "profile"}
    overridden = bool(own)
    data = merged_tables(name, own)
    known = {c.value for c in ObjectClass} | {"vehicle", "scene", "review"}
    for table, content in data.items():
        if table not in known:
            raise RssParameterError(
                table, content, f"unknown table; expected one of {sorted(known)}"
            )
        if not isinstance(content, dict):
            raise RssParameterError(table, content, "must be a table")
    classes = _default_classes()
    vehicle = _table(data, "vehicle")
    for cls in _VEHICLE_CLASSES:
        base = classes[cls].with_overrides(vehicle, prefix="vehicle.")
        classes[cls] = base.with_overrides(_table(data, cls.value), prefix=f"{cls.value}.")
    for cls in (ObjectClass.EGO, ObjectClass.PEDESTRIAN):
        classes[cls] = classes[cls].with_overrides(_table(data, cls.value), prefix=f"{cls.value}.")
    scene = _scene(_table(data, "scene"))
    standstill = _review(_table(data, "review"))
    return RssParams(
        dynamics=classes,
        scene=scene,
        profile=name,
        overridden=overridden,
        standstill_speed_mps=standstill,
    )


def _review(table: Mapping[str, object]) -> float:
    """The ``[review]`` table's standstill threshold [m/s] (0 when not given)."""
    speed = 0.0
    for key, value in table.items():
        name = f"review.{key}"
        if key != "standstill_speed":
            raise RssParameterError(name, value, "unknown [review] key")
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        if not ok or not math.isfinite(float(value)) or not 0.0 <= float(value) <= 1.0:  # type: ignore[arg-type]
            raise RssParameterError(name, value, "must be a number in [0, 1] m/s")
        speed = float(value)  # type: ignore[arg-type]
    return speed


def _table(data: Mapping[str, object], name: str) -> dict[str, object]:
    content = data.get(name, {})
    assert isinstance(content, dict)
    return content


def _scene(table: Mapping[str, object]) -> SceneSettings:
    values: dict[str, object] = {}
    for key, value in table.items():
        name = f"scene.{key}"
        if key == "restrict_speed_limit_mode":
            values[key] = _enum_value(RestrictSpeedLimitMode, name, value)
        elif key == "constellation_creation_mode":
            values[key] = _enum_value(ConstellationCreationMode, name, value)
        elif key in {"ego_length", "ego_width", "ego_height"}:
            ok = isinstance(value, int | float) and not isinstance(value, bool)
            if not ok or not math.isfinite(float(value)) or float(value) <= 0.0:  # type: ignore[arg-type]
                raise RssParameterError(name, value, "must be a finite number > 0 m")
            values[f"{key}_m"] = float(value)  # type: ignore[arg-type]
        elif key == "reproduce_adrss_5_0_defects":
            if not isinstance(value, bool):
                raise RssParameterError(name, value, "must be true or false")
            values[key] = value
        else:
            raise RssParameterError(name, value, "unknown [scene] key")
    return SceneSettings(**values)  # type: ignore[arg-type]


def _enum_value(cls: type[_E], name: str, value: object) -> _E:
    try:
        return cls(str(value))
    except ValueError as err:
        raise RssParameterError(name, value, f"must be one of {[m.value for m in cls]}") from err
