"""Named RSS parameter profiles: documented ``--rss-params`` tables selectable by name.

A profile is a set of ``--rss-params`` tables (same keys as the TOML, see
:mod:`rss.params`); a TOML file may name one (``profile = "highway"``) and override any of
its values with its own tables. Sources and the reasons for every value are in docs/rss.md
("Parameter profiles").

========== ==================================================================================
name       what
========== ==================================================================================
adrss-5.0  ad-rss-lib 5.0 unit-test dynamics (``TestSupport.cpp``): ego rho = 1 s, other
           vehicles rho = 2 s, CARLA's pedestrians. The conformance reference and the
           library default (``RssParams()``).
carla      CARLA's ``RssCheck`` defaults (``LibCarla/source/carla/rss/RssCheck.cpp``): the
           same longitudinal / lateral values, the five unstructured settings CARLA sets and
           every intermediate step count at its struct default 0.
highway    Review of recorded drives on motorways: others rho = 1 s (reaction and brake
           response time of the German case law), ego rho = 0.5 s, accel_max 2 m/s^2 during
           the response time, brake_min -6 m/s^2, brake_min_correct -5 m/s^2; everything else
           as adrss-5.0. What ``--rss-profile auto`` (the ``evaluate`` / ``replay`` /
           ``demo`` default) picks on fast roads.
========== ==================================================================================
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.errors import RssParameterError

if TYPE_CHECKING:
    from collections.abc import Mapping

__all__ = [
    "LIBRARY_PROFILE",
    "PROFILES",
    "REVIEW_PROFILE",
    "STANDSTILL_SPEED_MPS",
    "URBAN_PROFILE",
    "Profile",
    "ProfileName",
    "merged_tables",
    "profile",
]


class ProfileName(enum.StrEnum):
    """The names of the parameter profiles (the one place they are spelled)."""

    ADRSS_5_0 = "adrss-5.0"
    CARLA = "carla"
    HIGHWAY = "highway"
    URBAN = "urban"


#: Profile of ``RssParams()`` and of the conformance checks.
LIBRARY_PROFILE = ProfileName.ADRSS_5_0
#: Profile of the review commands' ``auto`` choice on fast roads (docs/rss.md).
REVIEW_PROFILE = ProfileName.HIGHWAY
#: Profile of the review commands' ``auto`` choice in town (docs/rss.md).
URBAN_PROFILE = ProfileName.URBAN
#: Standstill threshold of the review profiles [m/s]: ad-rss 5.0's own standstill test
#: (unstructured constellations: both ``speed_range.max <= 0.1`` -> DriveAway).
STANDSTILL_SPEED_MPS = 0.1

Tables = dict[str, dict[str, object]]


@dataclass(frozen=True)
class Profile:
    """One named parameter profile.

    Attributes:
        name: ``--rss-profile`` / TOML ``profile`` value.
        summary: One line for ``workbench info`` and the docs.
        source: Where the values come from.
        tables: ``--rss-params`` tables (``ego``, ``vehicle``, ``pedestrian``, ...) applied
            over the library defaults; empty = the library defaults.
    """

    name: str
    summary: str
    source: str
    tables: Mapping[str, Mapping[str, object]]


_CARLA_UNSTRUCTURED: dict[str, object] = {
    # RssCheck.cpp sets these five (same as ad-rss' unit tests); the step counts keep the
    # ad-rss struct default 0.
    "pedestrian_turning_radius": 2.0,
    "drive_away_max_angle": 2.4,
    "vehicle_yaw_rate_change": 0.3,
    "vehicle_min_radius": 3.5,
    "vehicle_trajectory_calculation_step": 0.2,
    "vehicle_front_intermediate_yaw_rate_change_ratio_steps": 0,
    "vehicle_back_intermediate_yaw_rate_change_ratio_steps": 0,
    "vehicle_brake_intermediate_acceleration_steps": 0,
    "vehicle_continue_forward_intermediate_acceleration_steps": 0,
    "vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps": 0,
    "pedestrian_continue_forward_intermediate_heading_change_ratio_steps": 0,
    "pedestrian_continue_forward_intermediate_acceleration_steps": 0,
    "pedestrian_brake_intermediate_acceleration_steps": 0,
    "pedestrian_front_intermediate_heading_change_ratio_steps": 0,
    "pedestrian_back_intermediate_heading_change_ratio_steps": 0,
}

_HIGHWAY_VEHICLE: dict[str, object] = {
    "response_time": 1.0,
    "accel_max": 2.0,
    "brake_min": -6.0,
    "brake_min_correct": -5.0,
}

_URBAN_VEHICLE: dict[str, object] = {
    "response_time": 1.0,
    "accel_max": 2.0,
    "brake_min": -3.4,
    "brake_min_correct": -3.0,
}

_REVIEW: dict[str, object] = {"standstill_speed": STANDSTILL_SPEED_MPS}

PROFILES: dict[str, Profile] = {
    str(p.name): p
    for p in (
        Profile(
            name=ProfileName.ADRSS_5_0,
            summary="ad-rss 5.0 unit-test defaults (ego rho 1 s, others 2 s); conformance",
            source="ad-rss-lib 5.0 ad_rss/test/test_support/TestSupport.cpp; CARLA pedestrians",
            tables={},
        ),
        Profile(
            name=ProfileName.CARLA,
            summary="CARLA RssSensor defaults (RssCheck.cpp; unstructured step counts 0)",
            source="carla-simulator/carla LibCarla/source/carla/rss/RssCheck.cpp",
            tables={
                "ego": _CARLA_UNSTRUCTURED,
                "vehicle": _CARLA_UNSTRUCTURED,
                "pedestrian": _CARLA_UNSTRUCTURED,
            },
        ),
        Profile(
            name=ProfileName.HIGHWAY,
            summary="review of recorded drives on fast roads (auto's choice there)",
            source=(
                "docs/rss.md, Parameter profiles (legal reaction time; project calibration "
                "checked on NGSIM US-101)"
            ),
            tables={
                "ego": {**_HIGHWAY_VEHICLE, "response_time": 0.5},
                "vehicle": _HIGHWAY_VEHICLE,
                "review": _REVIEW,
            },
        ),
        Profile(
            name=ProfileName.URBAN,
            summary="review of recorded drives in town (auto's choice there)",
            source=(
                "docs/rss.md, Parameter profiles (legal reaction time; AASHTO stopping "
                "deceleration 3.4 m/s^2 checked on urban GPS data; NGSIM Lankershim/Peachtree)"
            ),
            tables={
                "ego": {**_URBAN_VEHICLE, "response_time": 0.5},
                "vehicle": _URBAN_VEHICLE,
                "review": _REVIEW,
            },
        ),
    )
}


def profile(name: str) -> Profile:
    """The profile called ``name``.

    Raises:
        RssParameterError: No such profile.
    """
    try:
        return PROFILES[name]
    except KeyError:
        raise RssParameterError("profile", name, f"must be one of {sorted(PROFILES)}") from None


def merged_tables(name: str, tables: Mapping[str, object]) -> dict[str, object]:
    """The profile's tables with ``tables`` (a parsed TOML) over them, key by key.

    Raises:
        RssParameterError: Unknown profile.
    """
    out: dict[str, object] = {t: dict(v) for t, v in profile(name).tables.items()}
    for table, content in tables.items():
        base = out.get(table)
        if isinstance(base, dict) and isinstance(content, dict):
            out[table] = {**base, **content}
        else:
            out[table] = content
    return out
