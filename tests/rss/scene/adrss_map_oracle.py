"""ad-rss map integration 5.0 as an oracle: pairs (JSON, stdin) -> situations (JSON, stdout).

Runs under a separate interpreter that has ``ad-rss-map-integration`` 5.0 with the
packaging work-around of the reference notes (§8.4: the vendored ``libad_map_access`` and
``libad_rss`` of ``ad_rss_map_integration.libs`` replaced by symlinks to the base wheels'
copies). Usage: ``python adrss_map_oracle.py MAP.xodr < pairs.json > answers.json``, or
``python adrss_map_oracle.py MAP.xodr --borders > borders.json`` for ad-map's lane border
vertices (``{lane id: {"left": [[x, y], ...], "right": ...}}``, ENU metres, full
precision, as ad-map orders them).
Dynamics: the unit-test values (ego response time 1 s, others 2 s), no speed-limit mode,
no ego route (routes predicted), no green lights. The library logs to the C-level stdout,
so file descriptor 1 is redirected while it runs.
"""

import json
import os
import sys
from typing import Any

import ad_rss_map_integration as ad  # type: ignore[import-not-found]

EGO_ID = 1000
OTHER_ID = 1


def _value(x: Any) -> float:
    return float(str(x))


def _dynamics(response_time: float) -> Any:
    d = ad.rss.world.RssDynamics()
    d.response_time = ad.physics.Duration(response_time)
    d.max_speed_on_acceleration = ad.physics.Speed(100.0)
    d.alpha_lat.accel_max = ad.physics.Acceleration(0.2)
    d.alpha_lat.brake_min = ad.physics.Acceleration(-0.8)
    d.alpha_lon.accel_max = ad.physics.Acceleration(3.5)
    d.alpha_lon.brake_max = ad.physics.Acceleration(-8.0)
    d.alpha_lon.brake_min_correct = ad.physics.Acceleration(-3.0)
    d.alpha_lon.brake_min = ad.physics.Acceleration(-4.0)
    d.lateral_fluctuation_margin = ad.physics.Distance(0.1)
    settings = ad.rss.world.UnstructuredSettings()
    settings.pedestrian_turning_radius = ad.physics.Distance(2.0)
    settings.drive_away_max_angle = ad.physics.Angle(2.4)
    settings.vehicle_yaw_rate_change = ad.physics.AngularAcceleration(0.3)
    settings.vehicle_min_radius = ad.physics.Distance(3.5)
    settings.vehicle_trajectory_calculation_step = ad.physics.Duration(0.2)
    d.unstructured_settings = settings
    return d


def _matched(pose: dict[str, float], length: float, width: float) -> Any:
    obj = ad.map.match.Object()
    obj.enu_position.center_point = ad.map.point.createENUPoint(pose["x"], pose["y"], 0.0)
    obj.enu_position.heading = ad.map.point.createENUHeading(pose["yaw"])
    obj.enu_position.dimension.length = ad.physics.Distance(length)
    obj.enu_position.dimension.width = ad.physics.Distance(width)
    obj.enu_position.dimension.height = ad.physics.Distance(1.5)
    obj.enu_position.enu_reference_point = ad.map.access.getENUReferencePoint()
    matching = ad.map.match.AdMapMatching()
    obj.map_matched_bounding_box = matching.getMapMatchedBoundingBox(
        obj.enu_position, ad.physics.Distance(0.1)
    )
    return obj


def _object_data(  # noqa: PLR0917 - one object's fields
    object_id: int,
    object_type: Any,
    pose: dict[str, float],
    length: float,
    width: float,
    response_time: float,
) -> Any:
    data = ad.rss.map.RssObjectData()
    data.id = object_id
    data.type = object_type
    data.match_object = _matched(pose, length, width)
    data.speed_range.minimum = ad.physics.Speed(pose["v"])
    data.speed_range.maximum = ad.physics.Speed(pose["v"])
    data.yaw_rate = ad.physics.AngularVelocity(0.0)
    data.steering_angle = ad.physics.Angle(0.0)
    data.rss_dynamics = _dynamics(response_time)
    return data


def append_structured(creation: Any, ego: Any, other: Any, speed_limit_mode: str = "None") -> bool:
    """Append one pair's structured constellations (routes predicted; ``speed_limit_mode``:
    an ``RssRestrictSpeedLimitMode`` name, default none)."""
    return bool(
        creation.appendConstellations(
            ego,
            ad.map.route.FullRoute(),
            other,
            getattr(ad.rss.map.RssRestrictSpeedLimitMode, speed_limit_mode),
            ad.map.landmark.LandmarkIdSet(),
            ad.rss.map.RssConstellationCreationMode.Structured,
        )
    )


def init_map(content: str) -> None:
    """Load an OpenDRIVE map (text) into ad-map and silence ad-rss' logger."""
    unknown = ad.map.intersection.IntersectionType.Unknown
    light = ad.map.landmark.TrafficLightType.UNKNOWN
    if not ad.map.access.initFromOpenDriveContent(content, 0.2, unknown, light):
        raise SystemExit("ad-map cannot read the map")
    ad.rss.map.setLogLevel("off")


#: How far ahead the ego's predicted routes are searched for intersections (m): the
#: 100 m relevance floor of ad-rss plus the two vehicle lengths.
_TURN_HORIZON_M = 110.0


def _turns(ego: Any) -> list[list[Any]]:
    """``[incoming lane ids, outgoing lane ids, turn]`` of every intersection on the ego's
    predicted routes, as ad-map classifies the turn (``Intersection.turnDirection``)."""
    routes = ad.map.route.predictRoutesOnDistance(
        ego.match_object,
        ad.physics.Distance(_TURN_HORIZON_M),
        ad.map.route.RouteCreationMode.SameDrivingDirection,
        ad.map.route.FilterDuplicatesMode.SubRoutesPreferLongerOnes,
    )
    return [
        [
            sorted(str(x) for x in hit.incomingLanesOnRoute),
            sorted(str(x) for x in hit.outgoingLanesOnRoute),
            str(hit.turnDirection).split(".")[-1].split("::")[-1],
        ]
        for route in routes
        for hit in ad.map.intersection.Intersection.getIntersectionsForRoute(route)
    ]


def _answer(pair: dict[str, dict[str, float]]) -> dict[str, Any]:
    creation = ad.rss.map.RssWorldModelCreation(1, _dynamics(1.0))
    ego = _object_data(EGO_ID, ad.rss.world.ObjectType.EgoVehicle, pair["ego"], 4.5, 2.0, 1.0)
    ok = append_structured(
        creation,
        ego,
        _object_data(OTHER_ID, ad.rss.world.ObjectType.OtherVehicle, pair["other"], 4.5, 1.9, 2.0),
    )
    answer: dict[str, Any] = {
        "ok": bool(ok),
        "situations": [],
        "dangerous": [],
        "turns": _turns(ego),
    }
    snapshot = ad.rss.core.RssSituationSnapshot()
    if not ok or not ad.rss.core.RssSituationExtraction().extractSituation(
        creation.getWorldModel(), snapshot
    ):
        answer["ok"] = False
        return answer
    states = ad.rss.state.RssStateSnapshot()
    ad.rss.core.RssSituationChecking().checkSituation(snapshot, states)
    for c in snapshot.constellations:
        rp = c.relative_position
        speeds = {}
        for who, state in (("ego", c.ego_state), ("other", c.other_state)):
            v = state.structured_object_state.velocity
            speeds[f"{who}_v_lon"] = _value(v.speed_lon_max)
            speeds[f"{who}_v_lat"] = _value(v.speed_lat_max)
        answer["situations"].append(
            {
                "type": str(c.constellation_type).split("::")[-1],
                "lon_d": _value(rp.longitudinal_distance),
                "lat_d": _value(rp.lateral_distance),
                **speeds,
            }
        )
    answer["dangerous"] = [bool(ad.rss.state.isDangerous(s)) for s in states.individual_responses]
    return answer


def borders() -> dict[str, dict[str, list[list[float]]]]:
    """ad-map's left and right border vertices of every lane (ENU x, y in metres)."""

    def points(edge: Any) -> list[list[float]]:
        return [
            [p.x.mENUCoordinate, p.y.mENUCoordinate]
            for p in ad.map.point.getCachedENUPointList(edge)
        ]

    out = {}
    for lane_id in ad.map.lane.getLanes():
        lane = ad.map.lane.getLane(lane_id)
        out[str(lane_id)] = {"left": points(lane.edge_left), "right": points(lane.edge_right)}
    return out


def main() -> None:
    content = open(sys.argv[1]).read()  # noqa: PTH123, SIM115
    want_borders = sys.argv[2:] == ["--borders"]
    pairs = [] if want_borders else json.load(sys.stdin)
    real_stdout = os.dup(1)
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    try:
        init_map(content)
        result: Any = borders() if want_borders else [_answer(p) for p in pairs]
    finally:
        os.dup2(real_stdout, 1)
    sys.stdout.write(json.dumps(result) + "\n")


if __name__ == "__main__":
    main()
