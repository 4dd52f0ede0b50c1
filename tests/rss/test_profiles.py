"""Named parameter profiles: values from their sources, TOML selection and overrides."""

from __future__ import annotations

import pytest

from rss.errors import RssParameterError
from rss.params import ObjectClass, RssParams, parse_rss_params, rss_params_from_mapping
from rss.profiles import (
    LIBRARY_PROFILE,
    PROFILES,
    REVIEW_PROFILE,
    STANDSTILL_SPEED_MPS,
    URBAN_PROFILE,
)


def test_the_library_profile_is_the_conformance_reference() -> None:
    assert LIBRARY_PROFILE == "adrss-5.0"
    assert rss_params_from_mapping({}, profile="adrss-5.0") == RssParams()
    assert RssParams().profile_label == "adrss-5.0"


def test_carla_profile_has_carla_rsscheck_values() -> None:
    # LibCarla/source/carla/rss/RssCheck.cpp: GetDefaultVehicleDynamics, others rho 2 s,
    # GetDefaultPedestrianDynamics; step counts keep the struct default 0
    params = rss_params_from_mapping({}, profile="carla")
    ego, car = params.for_class(ObjectClass.EGO), params.for_class(ObjectClass.CAR)
    walker = params.for_class(ObjectClass.PEDESTRIAN)
    expected = (3.5, -8.0, -4.0, -3.0, 0.2, -0.8, 0.1, 100.0)
    for dyn, rho in ((ego, 1.0), (car, 2.0)):
        got = (
            dyn.accel_max_mps2,
            dyn.brake_max_mps2,
            dyn.brake_min_mps2,
            dyn.brake_min_correct_mps2,
            dyn.lat_accel_max_mps2,
            dyn.lat_brake_min_mps2,
            dyn.lateral_fluctuation_margin_m,
            dyn.max_speed_on_acceleration_mps,
        )
        assert got == expected
        assert dyn.response_time_s == rho
    assert (walker.accel_max_mps2, walker.brake_max_mps2, walker.response_time_s) == (
        2.0,
        -4.0,
        0.5,
    )
    assert ego.unstructured.vehicle_front_intermediate_yaw_rate_change_ratio_steps == 0
    assert (
        RssParams()
        .for_class(ObjectClass.EGO)
        .unstructured.vehicle_front_intermediate_yaw_rate_change_ratio_steps
        == 3
    )


def test_highway_profile_values() -> None:
    params = rss_params_from_mapping({}, profile="highway")
    ego, truck = params.for_class(ObjectClass.EGO), params.for_class(ObjectClass.TRUCK)
    assert (ego.response_time_s, truck.response_time_s) == (0.5, 1.0)
    assert (ego.accel_max_mps2, ego.brake_min_mps2, ego.brake_min_correct_mps2) == (2.0, -6.0, -5.0)
    assert truck.brake_max_mps2 == -8.0  # kept from adrss-5.0
    assert params.for_class(ObjectClass.PEDESTRIAN) == RssParams().for_class(ObjectClass.PEDESTRIAN)
    assert REVIEW_PROFILE == "highway"


def test_toml_profile_with_explicit_values_overriding() -> None:
    params = parse_rss_params('profile = "highway"\n[vehicle]\nresponse_time = 1.5\n')
    assert params.profile == "highway"
    assert params.overridden
    assert params.profile_label == "highway+file"
    assert params.for_class(ObjectClass.CAR).response_time_s == 1.5
    assert params.for_class(ObjectClass.CAR).brake_min_mps2 == -6.0  # from the profile


def test_toml_profile_must_agree_with_the_command_line() -> None:
    with pytest.raises(RssParameterError, match="contradicts"):
        parse_rss_params('profile = "carla"\n', profile="highway")
    assert parse_rss_params('profile = "carla"\n', profile="carla").profile == "carla"


@pytest.mark.parametrize("text", ['profile = "nope"\n', "profile = 3\n"])
def test_unknown_profile_is_a_typed_error(text: str) -> None:
    with pytest.raises(RssParameterError, match="profile"):
        parse_rss_params(text)


def test_every_profile_builds_and_is_documented() -> None:
    for name, prof in PROFILES.items():
        assert rss_params_from_mapping({}, profile=name).profile == name
        assert prof.summary
        assert prof.source


def test_urban_profile_values() -> None:
    params = rss_params_from_mapping({}, profile="urban")
    ego, car = params.for_class(ObjectClass.EGO), params.for_class(ObjectClass.CAR)
    assert (ego.response_time_s, car.response_time_s) == (0.5, 1.0)
    for dyn in (ego, car):
        # AASHTO stopping deceleration 3.4 m/s^2 (docs/rss.md, "urban")
        assert (dyn.accel_max_mps2, dyn.brake_min_mps2, dyn.brake_min_correct_mps2) == (
            2.0,
            -3.4,
            -3.0,
        )
        assert dyn.brake_max_mps2 == -8.0  # kept from adrss-5.0
        assert dyn.min_longitudinal_safety_distance_m == 0.0
    assert params.for_class(ObjectClass.PEDESTRIAN) == RssParams().for_class(ObjectClass.PEDESTRIAN)
    assert URBAN_PROFILE == "urban"


def test_standstill_rule_only_in_the_review_profiles() -> None:
    speeds = {
        name: rss_params_from_mapping({}, profile=name).standstill_speed_mps for name in PROFILES
    }
    assert speeds == {
        "adrss-5.0": 0.0,
        "carla": 0.0,
        "highway": STANDSTILL_SPEED_MPS,
        "urban": STANDSTILL_SPEED_MPS,
    }
    assert RssParams().standstill_speed_mps == 0.0
    assert parse_rss_params("[review]\nstandstill_speed = 0.3\n").standstill_speed_mps == 0.3
    off = parse_rss_params('profile = "urban"\n[review]\nstandstill_speed = 0\n')
    assert off.standstill_speed_mps == 0.0


@pytest.mark.parametrize(
    "text",
    [
        "[review]\nstandstill_speed = -1\n",
        "[review]\nstandstill_speed = true\n",
        "[review]\nx = 1\n",
    ],
)
def test_bad_review_table_is_a_typed_error(text: str) -> None:
    with pytest.raises(RssParameterError, match="review"):
        parse_rss_params(text)
