"""Urban scenarios: intersection with right of way, pedestrian crossing, parking lot."""

from __future__ import annotations

import math

import numpy as np

from loaders.records import ObjectClass
from workbench.samples.geometry import build_path
from workbench.samples.lanelet_map import MapBuilder
from workbench.samples.motion import Track, drive, splice, time_axis
from workbench.samples.roads import RoadSpec, add_road
from workbench.samples.scenario import SIZE_M, RosLayout, Scenario, actor

__all__ = ["parking_lot", "pedestrian_crossing", "urban_intersection"]

_EDGE: tuple[str, str | None] = ("road_border", None)
_SOLID = ("line_thin", "solid")
_DASHED = ("line_thin", "dashed")
_VIRTUAL: tuple[str, str | None] = ("virtual", None)
_HALF_PI = math.pi / 2


def _arc_points(centre: tuple[float, float], radius: float, a0: float, a1: float) -> np.ndarray:
    angles = np.linspace(a0, a1, 13)
    return np.stack([centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)], -1)


def urban_intersection(seed: int = 4) -> Scenario:
    """4-way junction; the ego on the side road yields, then turns left onto the main road."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    main = RoadSpec((3.5, 0.0, -3.5), (_EDGE, _DASHED, _EDGE), (False, True), 50.0, "urban")
    side = RoadSpec((3.5, 0.0, -3.5), (_EDGE, _SOLID, _EDGE), (False, True), 30.0, "urban")
    w, arm = 3.5, 146.5
    west = add_road(b, build_path((-150.0, 0.0), 0.0, [(arm, 0.0)], 10.0), (0, arm), main)
    east = add_road(b, build_path((w, 0.0), 0.0, [(arm, 0.0)], 10.0), (0, arm), main)
    south = add_road(b, build_path((0.0, -150.0), _HALF_PI, [(arm, 0.0)], 10.0), (0, arm), side)
    north = add_road(b, build_path((0.0, w), _HALF_PI, [(arm, 0.0)], 10.0), (0, arm), side)
    ew_mid = b.line([(-w, 0.0), (w, 0.0)], *_VIRTUAL)
    ns_mid = b.line([(0.0, -w), (0.0, w)], *_VIRTUAL)
    eb = b.lanelet(ew_mid, b.line([(-w, -w), (w, -w)], *_VIRTUAL), speed_limit_kmh=50.0)
    wb = b.lanelet(ew_mid, b.line([(w, w), (-w, w)], *_VIRTUAL), speed_limit_kmh=50.0)
    nb = b.lanelet(ns_mid, b.line([(w, -w), (w, w)], *_VIRTUAL), speed_limit_kmh=30.0)
    sb = b.lanelet(ns_mid, b.line([(-w, w), (-w, -w)], *_VIRTUAL), speed_limit_kmh=30.0)
    nb_left = b.lanelet(
        b.line(_arc_points((-w, -w), w, 0.0, _HALF_PI), *_VIRTUAL),
        b.line(_arc_points((-w, -w), 2 * w, 0.0, _HALF_PI), *_VIRTUAL),
        speed_limit_kmh=30.0,
    )
    stop = b.line([(0.0, -w - 1.0), (w, -w - 1.0)], "stop_line")
    b.right_of_way((eb, wb), (nb, nb_left, sb), stop)
    t = time_axis(22.0)
    ego_path = build_path(
        (1.75, -80.0), _HALF_PI, [(76.5, 0.0), (5.25 * _HALF_PI, 1 / 5.25), (100.0, 0.0)], 0.25
    )
    ego = drive(
        ego_path,
        t,
        s0_m=10.0,
        v0_mps=8.0,
        phases=[(5.9, -2.0), (9.9, 0.0), (11.0, 1.5), (13.65, 0.0), (15.5, 1.5), (18.15, 0.0)],
    )
    car = drive(build_path((-120.0, -1.75), 0.0, [(400.0, 0.0)]), t, s0_m=10.0, v0_mps=13.0)
    bus = drive(build_path((120.0, 1.75), math.pi, [(400.0, 0.0)]), t, s0_m=20.0, v0_mps=11.0)
    bike = drive(build_path((-1.75, 80.0), -_HALF_PI, [(160.0, 0.0)]), t, s0_m=25.0, v0_mps=5.0)
    actors = (
        actor(rng, 1, ObjectClass.CAR, car, [west[1][0], eb, east[1][0]], ego=ego),
        actor(rng, 2, ObjectClass.BUS, bus, [east[0][0], wb, west[0][0]], ego=ego),
        actor(rng, 3, ObjectClass.BICYCLE, bike, [north[0][0], sb, south[0][0]], ego=ego),
    )
    return Scenario(
        name="urban_intersection",
        summary=(
            "4-way junction; the main road (x axis, 50 km/h) has priority over the side road "
            "(y axis, 30 km/h) by a right_of_way element with a stop line. The ego comes "
            "north on the side road at 8 m/s, brakes at -2 m/s2 and stops at the stop line "
            "(t = 9.9 s) while the priority car 1 (eastbound, 13 m/s, crosses x = 0 at "
            "t = 8.5 s) and bus 2 (westbound, 11 m/s, t = 9.1 s) pass, then turns left "
            "(R = 5.25 m at 4 m/s) from t = 11 s. Bicycle 3 rides south across the junction."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, [south[1][0], nb_left, west[0][0]]),
        actors=actors,
        lane_map=b,
        layout=RosLayout("odometry", "/localization/kinematic_state", "tracked", "trajectory"),
        road_lanelets=13,
    )


def pedestrian_crossing(seed: int = 5) -> Scenario:
    """Urban street with a signalised crosswalk; the ego stops for a crossing pedestrian."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    spec = RoadSpec(
        (6.5, 3.5, 0.0, -3.5, -6.5),
        (_SOLID, _EDGE, _DASHED, _EDGE, _SOLID),
        (True, False, True, True),
        50.0,
        "urban",
        lane_subtypes=("walkway", "road", "road", "walkway"),
        one_way=(False, True, True, False),
    )
    ref = build_path((0.0, 0.0), 0.0, [(200.0, 0.0)], 10.0)
    lanes = add_road(b, ref, (0.0, 100.0, 104.0, 200.0), spec)
    xs = (-6.5, -3.5, 0.0, 3.5, 6.5)
    crosswalk = b.lanelet(
        b.line([(100.0, y) for y in xs], *_DASHED),
        b.line([(104.0, y) for y in xs], *_DASHED),
        subtype="crosswalk",
        one_way=False,
        speed_limit_kmh=10.0,
    )
    b.traffic_light(
        (lanes[2][0],),
        b.line([(99.0, -5.0), (99.0, -4.4)], "traffic_light", "red_yellow_green"),
        b.line([(98.0, -3.5), (98.0, 0.0)], "stop_line"),
    )
    t = time_axis(20.0)
    ego = drive(
        ref,
        t,
        s0_m=20.0,
        v0_mps=12.0,
        offset_m=-1.75,
        phases=[(4.2, -3.0), (8.2, 0.0), (10.5, 1.5), (18.5, 0.0)],
    )
    walker = drive(
        build_path((102.0, -5.5), _HALF_PI, [(11.0, 0.0)]),
        t,
        s0_m=0.0,
        phases=[(3.0, 1.0), (4.4, 0.0), (10.85, -1.0)],
    )
    stroller = drive(build_path((140.0, 5.0), math.pi, [(40.0, 0.0)]), t, s0_m=0.0, v0_mps=1.2)
    westbound = build_path((200.0, 1.75), math.pi, [(300.0, 0.0)], 10.0)
    car = drive(westbound, t, s0_m=40.0, v0_mps=11.0)
    bike = drive(westbound, t, s0_m=5.0, v0_mps=5.0)
    actors = (
        actor(
            rng, 1, ObjectClass.PEDESTRIAN, walker, [lanes[3][1], crosswalk, lanes[0][1]], ego=ego
        ),
        actor(rng, 2, ObjectClass.PEDESTRIAN, stroller, lanes[0], ego=ego),
        actor(rng, 3, ObjectClass.CAR, car, lanes[1], ego=ego),
        actor(rng, 4, ObjectClass.BICYCLE, bike, lanes[1], ego=ego),
    )
    return Scenario(
        name="pedestrian_crossing",
        summary=(
            "Urban street (50 km/h) with sidewalks and a crosswalk at x = 100-104 m guarded "
            "by a traffic_light element (stop line x = 98 m). Pedestrian 1 steps off the "
            "south sidewalk at t = 3 s and crosses at 1.4 m/s (in the ego lane t = 5.2-7.9 s). "
            "The ego (12 m/s) brakes at -3 m/s2 from t = 4.2 s and stops with its front at "
            "x = 97 m (t = 8.2 s), waits, and pulls away at t = 10.5 s. An oncoming car "
            "passes the crosswalk at t = 5 s; pedestrian 2 walks along the north sidewalk; a "
            "bicycle comes the other way later."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, lanes[2]),
        actors=actors,
        lane_map=b,
        layout=RosLayout("odometry", "/carla/ego_vehicle/odometry", "object_array", "trajectory"),
        road_lanelets=6,
    )


def parking_lot(seed: int = 6) -> Scenario:
    """Parking aisle with spaces on both sides; a car reverses out in front of the ego."""
    rng = np.random.default_rng(seed)
    b = MapBuilder()
    spec = RoadSpec((3.0, -3.0), (_VIRTUAL, _VIRTUAL), (True,), 10.0, "urban", one_way=(False,))
    aisle = add_road(b, build_path((0.0, 0.0), 0.0, [(60.0, 0.0)], 5.0), (0, 30, 60), spec)[0]
    spaces: dict[tuple[int, int], int] = {}
    for side in (1, -1):
        seps = [
            b.line([(10.0 + 2.5 * k, 3.0 * side), (10.0 + 2.5 * k, 8.0 * side)], *_SOLID)
            for k in range(13)
        ]
        for k in range(12):
            left, right = (seps[k], seps[k + 1]) if side > 0 else (seps[k + 1], seps[k])
            spaces[side, k] = b.lanelet(
                left, right, subtype="parking", one_way=False, speed_limit_kmh=10.0
            )
    t = time_axis(20.0)
    back_path = build_path((26.25, 0.0), 0.0, [(5.0 * _HALF_PI, 1 / 5.0), (0.546, 0.0)], 0.1)
    out = drive(
        back_path,
        t,
        s0_m=back_path.length_m,
        reverse=True,
        phases=[(3.0, 0.8), (4.5, 0.0), (10.0, -0.8), (11.5, 0.0)],
    )
    away = drive(
        build_path((26.25, 0.0), 0.0, [(33.0, 0.0)], 0.5),
        t,
        s0_m=0.0,
        phases=[(12.0, 1.0), (14.5, 0.0)],
    )
    reverser = splice(out, away, int(np.searchsorted(t, 11.75)))
    ego = drive(
        build_path((0.0, 0.0), 0.0, [(60.0, 0.0)], 0.5),
        t,
        s0_m=2.0,
        v0_mps=2.0,
        phases=[(7.5, -1.0), (9.5, 0.0), (13.0, 0.8), (16.125, 0.0)],
    )
    parked_a = drive(build_path((16.25, 3.5), _HALF_PI, [(4.0, 0.0)]), t, s0_m=2.0)
    parked_b = drive(build_path((23.75, -3.5), -_HALF_PI, [(4.0, 0.0)]), t, s0_m=2.0)
    walker = drive(build_path((50.0, 2.2), math.pi, [(30.0, 0.0)]), t, s0_m=0.0, v0_mps=1.2)
    crosser = drive(
        build_path((38.75, -6.0), _HALF_PI, [(12.0, 0.0)]),
        t,
        s0_m=0.0,
        v0_mps=1.3,
        phases=[(8.5, -1.3)],
    )
    actors = (
        actor(rng, 1, ObjectClass.CAR, reverser, [spaces[1, 8], *aisle], ego=ego),
        actor(rng, 2, ObjectClass.CAR, parked_a, [spaces[1, 2]], ego=ego),
        actor(rng, 3, ObjectClass.CAR, parked_b, [spaces[-1, 5]], ego=ego),
        actor(rng, 4, ObjectClass.PEDESTRIAN, walker, aisle, ego=ego),
        actor(
            rng,
            5,
            ObjectClass.PEDESTRIAN,
            crosser,
            [spaces[-1, 11], *aisle, spaces[1, 11]],
            ego=ego,
        ),
    )
    return Scenario(
        name="parking_lot",
        summary=(
            "Parking aisle (x = 0-60 m, 6 m wide, 10 km/h) with 12 parking-space lanelets on "
            "each side. Car 1 reverses out of the space at x = 31.25 m from t = 3 s (at most "
            "1.2 m/s) onto the aisle centre (t = 11.5 s) and drives off at 2.5 m/s from "
            "t = 12 s. The ego (2 m/s) brakes to a stop at x = 19 m (t = 9.5 s) and follows "
            "from t = 13 s. Two parked cars; pedestrian 4 walks along the aisle, pedestrian 5 "
            "crosses it at x = 38.75 m."
        ),
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, aisle),
        actors=actors,
        lane_map=b,
        layout=RosLayout("odometry", "/localization/kinematic_state", "predicted", "path"),
        road_lanelets=2,
    )
