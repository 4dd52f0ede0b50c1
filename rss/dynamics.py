"""RSS dynamics of one traffic participant (ad-rss ``RssDynamics``) with validation.

Field names carry units; the ad-rss / TOML key of each field is in :data:`DYNAMICS_KEYS`
(e.g. ``accel_max`` -> :attr:`RssDynamics.accel_max_mps2`). Brakes are negative
accelerations, as in ad-rss and in ``--rss-params`` files.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from rss.errors import RssParameterError

if TYPE_CHECKING:
    from collections.abc import Mapping

__all__ = [
    "DYNAMICS_KEYS",
    "UNSTRUCTURED_KEYS",
    "RssDynamics",
    "UnstructuredSettings",
]


@dataclass(frozen=True)
class UnstructuredSettings:
    """Trajectory-set settings of unstructured constellations (stored, used by issue 6).

    Defaults are those of ad-rss-lib's unit tests (``TestSupport.cpp``). Names are the
    ad-rss names; lengths in m, angles in rad, yaw-rate change in rad/s², step in s.
    """

    pedestrian_turning_radius: float = 2.0
    drive_away_max_angle: float = 2.4
    vehicle_yaw_rate_change: float = 0.3
    vehicle_min_radius: float = 3.5
    vehicle_trajectory_calculation_step: float = 0.2
    vehicle_front_intermediate_yaw_rate_change_ratio_steps: int = 3
    vehicle_back_intermediate_yaw_rate_change_ratio_steps: int = 0
    vehicle_brake_intermediate_acceleration_steps: int = 1
    vehicle_continue_forward_intermediate_acceleration_steps: int = 0
    vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps: int = 3
    pedestrian_continue_forward_intermediate_heading_change_ratio_steps: int = 3
    pedestrian_continue_forward_intermediate_acceleration_steps: int = 0
    pedestrian_brake_intermediate_acceleration_steps: int = 3
    pedestrian_front_intermediate_heading_change_ratio_steps: int = 4
    pedestrian_back_intermediate_heading_change_ratio_steps: int = 0


#: ad-rss / TOML key -> field of :class:`RssDynamics`.
DYNAMICS_KEYS: dict[str, str] = {
    "accel_max": "accel_max_mps2",
    "brake_max": "brake_max_mps2",
    "brake_min": "brake_min_mps2",
    "brake_min_correct": "brake_min_correct_mps2",
    "lat_accel_max": "lat_accel_max_mps2",
    "lat_brake_min": "lat_brake_min_mps2",
    "lateral_fluctuation_margin": "lateral_fluctuation_margin_m",
    "response_time": "response_time_s",
    "max_speed_on_acceleration": "max_speed_on_acceleration_mps",
    "min_longitudinal_safety_distance": "min_longitudinal_safety_distance_m",
}

#: Keys of :class:`UnstructuredSettings` (same spelling in TOML and ad-rss).
UNSTRUCTURED_KEYS: tuple[str, ...] = tuple(f.name for f in dataclasses.fields(UnstructuredSettings))


@dataclass(frozen=True)
class RssDynamics:
    """Worst-case dynamics one participant is assumed to respect (ad-rss ``RssDynamics``).

    Defaults are ad-rss-lib's unit-test values for a non-ego vehicle (response time 2 s).

    Attributes:
        accel_max_mps2: Max longitudinal acceleration during the response time, in [0, 100].
        brake_max_mps2: Max braking (negative), in [-100, brake_min].
        brake_min_mps2: Min braking of the responsible vehicle, in [brake_max, brake_min_correct].
        brake_min_correct_mps2: Min braking in the correct lane (opposite direction), in
            [brake_min, 0).
        lat_accel_max_mps2: Max lateral acceleration during the response time, in [0, 100].
        lat_brake_min_mps2: Min lateral braking (negative), in [-100, 0).
        lateral_fluctuation_margin_m: Lateral margin mu in [0, 1]; a pair adds ½(mu_a + mu_b).
        response_time_s: Response time rho in (0, 10].
        max_speed_on_acceleration_mps: Speed cap of the acceleration phase, in [0, 1000].
        min_longitudinal_safety_distance_m: Added to longitudinal safe distances, >= 0.
        unstructured: Trajectory-set settings (unstructured constellations).
    """

    accel_max_mps2: float = 3.5
    brake_max_mps2: float = -8.0
    brake_min_mps2: float = -4.0
    brake_min_correct_mps2: float = -3.0
    lat_accel_max_mps2: float = 0.2
    lat_brake_min_mps2: float = -0.8
    lateral_fluctuation_margin_m: float = 0.1
    response_time_s: float = 2.0
    max_speed_on_acceleration_mps: float = 100.0
    min_longitudinal_safety_distance_m: float = 0.0
    unstructured: UnstructuredSettings = field(default_factory=UnstructuredSettings)

    def __post_init__(self) -> None:
        """Validate every field against the ad-rss input ranges.

        Raises:
            RssParameterError: A value is NaN or outside its range, or a brake is positive.
        """
        self.validate()

    def validate(self, prefix: str = "") -> None:
        """Check every field against the ad-rss input ranges.

        Args:
            prefix: Prepended to field names in error messages (e.g. ``"vehicle."``).

        Raises:
            RssParameterError: The first violated rule.
        """
        checks: tuple[tuple[str, float, float, float, bool], ...] = (
            # key, value, lower, upper, upper bound exclusive
            ("accel_max", self.accel_max_mps2, 0.0, 100.0, False),
            ("brake_max", self.brake_max_mps2, -100.0, self.brake_min_mps2, False),
            (
                "brake_min",
                self.brake_min_mps2,
                self.brake_max_mps2,
                self.brake_min_correct_mps2,
                False,
            ),
            ("brake_min_correct", self.brake_min_correct_mps2, self.brake_min_mps2, 0.0, True),
            ("lat_accel_max", self.lat_accel_max_mps2, 0.0, 100.0, False),
            ("lat_brake_min", self.lat_brake_min_mps2, -100.0, 0.0, True),
            ("lateral_fluctuation_margin", self.lateral_fluctuation_margin_m, 0.0, 1.0, False),
            ("response_time", self.response_time_s, 0.0, 10.0, False),
            ("max_speed_on_acceleration", self.max_speed_on_acceleration_mps, 0.0, 1000.0, False),
            (
                "min_longitudinal_safety_distance",
                self.min_longitudinal_safety_distance_m,
                0.0,
                1e9,
                False,
            ),
        )
        for key, value, lower, upper, upper_open in checks:
            name = prefix + key
            if not isinstance(value, int | float) or isinstance(value, bool):
                raise RssParameterError(name, value, "must be a number")
            if not math.isfinite(value):
                raise RssParameterError(name, value, "must be finite")
            if key.startswith(("brake", "lat_brake")) and value >= 0.0:
                raise RssParameterError(name, value, "must be < 0 (brakes are negative)")
            if key == "response_time" and value <= 0.0:
                raise RssParameterError(name, value, "must be > 0 s")
            too_high = value >= upper if upper_open else value > upper
            if value < lower or too_high:
                bracket = ")" if upper_open else "]"
                raise RssParameterError(name, value, f"must be in [{lower:g}, {upper:g}{bracket}")

    def with_overrides(self, overrides: Mapping[str, object], prefix: str = "") -> RssDynamics:
        """Return a copy with ad-rss-named keys replaced (any subset, flat mapping).

        Args:
            overrides: ad-rss / TOML keys (``accel_max``, ``brake_min``, ...,
                ``drive_away_max_angle``, ...) to values.
            prefix: Prepended to key names in error messages.

        Returns:
            The validated copy.

        Raises:
            RssParameterError: Unknown key, wrong type or invalid value.
        """
        top: dict[str, object] = {}
        unstructured: dict[str, object] = {}
        for key, value in overrides.items():
            if key in DYNAMICS_KEYS:
                if not isinstance(value, int | float) or isinstance(value, bool):
                    raise RssParameterError(prefix + key, value, "must be a number")
                top[DYNAMICS_KEYS[key]] = float(value)
            elif key in UNSTRUCTURED_KEYS:
                unstructured[key] = _unstructured_value(prefix + key, value)
            else:
                raise RssParameterError(prefix + key, value, "unknown RssDynamics key")
        if unstructured:
            top["unstructured"] = dataclasses.replace(self.unstructured, **unstructured)  # type: ignore[arg-type]
        try:
            return dataclasses.replace(self, **top)  # type: ignore[arg-type]
        except RssParameterError as err:
            raise RssParameterError(prefix + err.field, err.value, err.reason) from err


def _unstructured_value(name: str, value: object) -> float | int:
    """Check one unstructured-settings value: step counts are ints >= 0, others floats > 0."""
    if name.endswith("_steps"):
        if not isinstance(value, int) or isinstance(value, bool) or value < 0:
            raise RssParameterError(name, value, "must be an integer >= 0")
        return value
    if not isinstance(value, int | float) or isinstance(value, bool) or not math.isfinite(value):
        raise RssParameterError(name, value, "must be a finite number")
    if value <= 0.0:
        raise RssParameterError(name, value, "must be > 0")
    return float(value)
