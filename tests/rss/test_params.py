"""Dynamics defaults, TOML loading and validation errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from rss.dynamics import RssDynamics
from rss.errors import RssParameterError
from rss.params import (
    DEFAULT_EGO_DYNAMICS,
    DEFAULT_PEDESTRIAN_DYNAMICS,
    ObjectClass,
    RestrictSpeedLimitMode,
    RssParams,
    parse_rss_params,
)

EXAMPLE = Path(__file__).resolve().parents[3] / "shared" / "conformance" / "rss_params_example.toml"


def test_documented_defaults() -> None:
    params = RssParams()
    assert DEFAULT_EGO_DYNAMICS.response_time_s == 1.0
    assert params.for_class(ObjectClass.TRUCK).response_time_s == 2.0
    assert params.for_class(ObjectClass.PEDESTRIAN) == DEFAULT_PEDESTRIAN_DYNAMICS
    assert DEFAULT_PEDESTRIAN_DYNAMICS.max_speed_on_acceleration_mps == 10.0
    assert params.scene.restrict_speed_limit_mode == RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_10
    assert params.scene.ego_length_m is None  # the frames' size (docs/architecture.md)


def test_example_toml_loads() -> None:
    if not EXAMPLE.exists():
        pytest.skip("example not present")
    params = parse_rss_params(EXAMPLE.read_text())
    assert params.for_class(ObjectClass.EGO).response_time_s == 1.0
    assert params.scene.ego_length_m == 4.5


def test_reproduce_adrss_5_0_defects_is_an_opt_in_bool() -> None:
    assert RssParams().scene.reproduce_adrss_5_0_defects is False
    on = parse_rss_params("[scene]\nreproduce_adrss_5_0_defects = true\n")
    assert on.scene.reproduce_adrss_5_0_defects is True
    off = parse_rss_params("[scene]\nreproduce_adrss_5_0_defects = false\n")
    assert off.scene.reproduce_adrss_5_0_defects is False
    assert on.scene.restrict_speed_limit_mode == RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_10


def test_vehicle_table_then_class_refinement() -> None:
    params = parse_rss_params(
        "[vehicle]\nresponse_time = 1.5\n[truck]\nbrake_min = -3.0\nbrake_min_correct = -2.0\n"
    )
    assert params.for_class(ObjectClass.CAR).response_time_s == 1.5
    truck = params.for_class(ObjectClass.TRUCK)
    assert (truck.response_time_s, truck.brake_min_mps2) == (1.5, -3.0)
    assert params.for_class(ObjectClass.PEDESTRIAN).response_time_s == 0.5


@pytest.mark.parametrize(
    ("toml", "field"),
    [
        ("[car]\nbrake_min = 4.0", "car.brake_min"),  # wrong sign
        ("[ego]\nbrake_max = -2.0", "ego.brake_max"),  # brake_max must be <= brake_min
        ("[ego]\nresponse_time = 0.0", "ego.response_time"),
        ("[ego]\naccel_max = nan", "ego.accel_max"),
        ("[ego]\nfoo = 1.0", "ego.foo"),
        ("[bogus]\nx = 1", "bogus"),
        ("[scene]\nrestrict_speed_limit_mode = 'Fast'", "scene.restrict_speed_limit_mode"),
        ("[scene]\nego_length = -1", "scene.ego_length"),
        ("[scene]\nreproduce_adrss_5_0_defects = 'yes'", "scene.reproduce_adrss_5_0_defects"),
        ("[scene]\nreproduce_adrss_5_0_defects = 1", "scene.reproduce_adrss_5_0_defects"),
        (
            "[pedestrian]\nvehicle_trajectory_calculation_step = 0",
            "pedestrian.vehicle_trajectory_calculation_step",
        ),
        ("[ego\n", "<toml>"),
    ],
)
def test_invalid_params_raise_typed_error(toml: str, field: str) -> None:
    with pytest.raises(RssParameterError) as info:
        parse_rss_params(toml)
    assert info.value.field == field


def test_direct_construction_validates() -> None:
    with pytest.raises(RssParameterError, match="brakes are negative"):
        RssDynamics(lat_brake_min_mps2=0.8)
    with pytest.raises(RssParameterError, match="finite"):
        RssDynamics(accel_max_mps2=float("nan"))
