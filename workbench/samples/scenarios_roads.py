"""Scenarios on roads without junctions: highway cut-in, hard-braking lead, wrong-way car."""

from __future__ import annotations

import numpy as np

from loaders.records import ObjectClass
from workbench.samples.geometry import Polyline, build_path
from workbench.samples.lanelet_map import MapBuilder
from workbench.samples.motion import LaneChange, Track, drive, time_axis
from workbench.samples.roads import RoadSpec, add_road
from workbench.samples.scenario import SIZE_M, RosLayout, Scenario, actor

__all__ = ["hard_braking_lead", "highway_cut_in", "highway_spec", "wrong_way_oncoming"]

_SOLID = ("line_thick", "solid")
_DASHED = ("line_thin", "dashed")
_BORDER: tuple[str, str | None] = ("road_border", None)


def highway_spec() -> RoadSpec:
    """A 3-lane one-way highway, 3.75 m lanes, 130 km/h (lanes numbered from the left)."""
    return RoadSpec(
        (5.625, 1.875, -1.875, -5.625),
        (_SOLID, _DASHED, _DASHED, _SOLID),
        (True, True, True),
        130.0,
        "nonurban",
    )


def highway_cut_in(seed: int = 1) -> Scenario:
    """3-lane highway; a car overtakes on the left and cuts in ~13 m ahead, then brakes."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    ref = build_path((0.0, 0.0), 0.0, [(400.0, 0.0), (400.0, 1 / 1000)], step_m=2.0)
    spec = highway_spec()
    lanes = add_road(b, ref, (0.0, 200.0, 400.0, 600.0, 800.0), spec)
    t = time_axis(20.0)
    left, mid, right = (spec.centre_offset_m(i) for i in range(3))
    ego = drive(ref, t, s0_m=30.0, v0_mps=25.0, offset_m=mid, phases=[(9.8, -2.5), (12.0, 0.0)])
    cutter = drive(
        ref,
        t,
        s0_m=29.0,
        v0_mps=28.0,
        offset_m=left,
        phases=[(5.0, -2.0), (6.25, 0.0), (9.0, -3.0), (11.0, 0.0)],
        lane_changes=[LaneChange(5.5, 3.0, mid - left)],
    )
    moto = drive(ref, t, s0_m=45.0, v0_mps=33.0, offset_m=left)
    fast = drive(ref, t, s0_m=60.0, v0_mps=30.0, offset_m=right)
    truck = drive(ref, t, s0_m=110.0, v0_mps=22.0, offset_m=right)
    rng_m = 80.0
    actors = (
        actor(rng, 1, ObjectClass.CAR, cutter, lanes[0] + lanes[1], ego=ego, range_m=rng_m),
        actor(rng, 2, ObjectClass.MOTORCYCLE, moto, lanes[0], ego=ego, range_m=rng_m),
        actor(rng, 3, ObjectClass.CAR, fast, lanes[2], ego=ego, range_m=rng_m),
        actor(rng, 4, ObjectClass.TRUCK, truck, lanes[2], ego=ego, range_m=rng_m),
    )
    return Scenario(
        name="highway_cut_in",
        summary=(
            "Ego in the middle lane of a 3-lane highway at 25 m/s (straight 400 m, then a "
            "R = 1000 m left curve). Car 1 overtakes on the left at 28 m/s and changes into "
            "the ego lane from t = 5.5 s to 8.5 s with an 11-13 m bumper gap, then brakes at "
            "-3 m/s2 from t = 9 s to 11 s (25.5 -> 19.5 m/s); the ego brakes at -2.5 m/s2 from "
            "t = 9.8 s to 12 s (25 -> 19.5 m/s) and follows about 8 m behind. A motorcycle "
            "(left lane, 33 m/s) and a car (right lane, 30 m/s) flow freely and leave the 80 m "
            "sensor range after a few seconds; a truck cruises in the right lane."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, lanes[1]),
        actors=actors,
        lane_map=b,
        layout=RosLayout("odometry", "/carla/ego_vehicle/odometry", "object_array", "path"),
        road_lanelets=12,
    )


def hard_braking_lead(seed: int = 2) -> Scenario:
    """Ego follows a lead car at 20 m/s, 28 m gap; the lead brakes at -7 m/s2 to a stop."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    ref = build_path((0.0, 0.0), 0.0, [(600.0, 0.0)], step_m=10.0)
    spec = RoadSpec((3.5, 0.0, -3.5), (_SOLID, _DASHED, _SOLID), (True, True), 80.0, "nonurban")
    lanes = add_road(b, ref, (0.0, 300.0, 600.0), spec)
    t = time_axis(15.0)
    left, right = spec.centre_offset_m(0), spec.centre_offset_m(1)
    ego = drive(ref, t, s0_m=30.0, v0_mps=20.0, offset_m=right, phases=[(6.0, -6.0)])
    lead = drive(ref, t, s0_m=30.0 + 4.6 + 28.0, v0_mps=20.0, offset_m=right, phases=[(5.0, -7.0)])
    bus = drive(ref, t, s0_m=80.0, v0_mps=16.0, offset_m=left)
    car = drive(ref, t, s0_m=10.0, v0_mps=24.0, offset_m=left, phases=[(5.5, -1.5), (7.5, 0.0)])
    actors = (
        actor(rng, 1, ObjectClass.CAR, lead, lanes[1], ego=ego, range_m=120.0),
        actor(rng, 2, ObjectClass.BUS, bus, lanes[0], ego=ego, range_m=120.0),
        actor(rng, 3, ObjectClass.CAR, car, lanes[0], ego=ego, range_m=120.0),
    )
    return Scenario(
        name="hard_braking_lead",
        summary=(
            "Straight 2-lane road. Ego (right lane) follows car 1 at 20 m/s with a 28 m "
            "bumper gap. At t = 5 s the lead brakes at -7 m/s2 to a stop (t = 7.9 s); the ego "
            "reacts 1 s later with -6 m/s2 and stops about 3 m behind it (t = 9.3 s). A bus "
            "and a car drive in the left lane."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, lanes[1]),
        actors=actors,
        lane_map=b,
        layout=RosLayout("odometry", "/localization/kinematic_state", "predicted", "trajectory"),
        road_lanelets=4,
    )


def wrong_way_oncoming(seed: int = 3) -> Scenario:
    """Rural two-lane road; an oncoming car drifts into the ego lane and returns."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    ref = build_path((0.0, 0.0), 0.0, [(300.0, 0.0), (300.0, -1 / 600)], step_m=2.0)
    spec = RoadSpec((3.5, 0.0, -3.5), (_BORDER, _DASHED, _BORDER), (False, True), 100.0, "nonurban")
    lanes = add_road(b, ref, (0.0, 200.0, 400.0, 600.0), spec)
    back = Polyline.from_points(ref.points_m[::-1])
    length = ref.length_m
    t = time_axis(20.0)
    ego = drive(
        ref,
        t,
        s0_m=20.0,
        v0_mps=20.0,
        offset_m=spec.centre_offset_m(1),
        phases=[(5.5, -3.0), (7.5, 0.0), (11.5, 1.5), (13.5, 0.0)],
    )
    oncoming = drive(
        back,
        t,
        s0_m=length - 430.0,
        v0_mps=20.0,
        offset_m=-1.75,
        lane_changes=[LaneChange(4.0, 2.5, 3.5), LaneChange(8.0, 2.5, -3.5)],
    )
    truck = drive(back, t, s0_m=length - 540.0, v0_mps=18.0, offset_m=-1.75)
    moto = drive(ref, t, s0_m=70.0, v0_mps=23.0, offset_m=spec.centre_offset_m(1))
    actors = (
        actor(rng, 1, ObjectClass.CAR, oncoming, lanes[0] + lanes[1], ego=ego, range_m=250.0),
        actor(rng, 2, ObjectClass.TRUCK, truck, lanes[0], ego=ego, range_m=250.0),
        actor(rng, 3, ObjectClass.MOTORCYCLE, moto, lanes[1], ego=ego, range_m=250.0),
    )
    return Scenario(
        name="wrong_way_oncoming",
        summary=(
            "Rural road, one lane per direction, straight then a R = 600 m right curve. The "
            "oncoming car 1 (20 m/s) drifts fully into the ego lane from t = 4 s to 6.5 s, "
            "stays there until t = 8 s and returns by t = 10.5 s; the cars pass each other "
            "at t = 10.9 s. The ego brakes at -3 m/s2 from t = 5.5 s to 7.5 s (20 -> 14 m/s). A "
            "truck follows the oncoming car; a motorcycle rides ahead of the ego."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, lanes[1]),
        actors=actors,
        lane_map=b,
        layout=RosLayout("pose", "/ego/pose", "detection3d", "path"),
        road_lanelets=6,
    )
