"""Inspect what ad-map / ad-rss map integration 5.0 sees for cross-check pairs (Town01).

Runs under the oracle interpreter (``.venv-oracle-adrss-map/bin/python``, §8.4 links).
Reads pairs as JSON (a list of ``{"ego": pose, "other": pose}``, as written by
``tools/scene_crosscheck.py --dump``) on stdin and prints, per pair: the occupied regions
of both boxes, the connecting routes (type, lanes, length), the ego's and the object's
predicted routes (lanes), the constellations with their road areas (lane ids, lengths)
and relative positions::

    .venv/bin/python tools/scene_crosscheck.py --pairs 95,100 --dump | \
        .venv-oracle-adrss-map/bin/python tools/adrss_map_inspect.py MAP.xodr
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "rss" / "scene"))

import adrss_map_oracle as oracle

ad = oracle.ad


def _route_lanes(route: Any) -> str:
    segs = []
    for rs in route.road_segments:
        lanes = [
            f"{ls.lane_interval.lane_id!s}[{float(str(ls.lane_interval.start)):.2f}"
            f"-{float(str(ls.lane_interval.end)):.2f}]"
            for ls in rs.drivable_lane_segments
        ]
        segs.append("|".join(lanes))
    return " > ".join(segs)


def _regions(obj: Any) -> str:
    out = []
    for r in obj.map_matched_bounding_box.lane_occupied_regions:
        lon = r.longitudinal_range
        lat = r.lateral_range
        out.append(
            f"{r.lane_id!s} lon[{float(str(lon.minimum)):.3f},{float(str(lon.maximum)):.3f}]"
            f" lat[{float(str(lat.minimum)):.2f},{float(str(lat.maximum)):.2f}]"
        )
    return "; ".join(out)


def _road(area: Any) -> str:
    segs = []
    for seg in area:
        lanes = [
            f"{ls.id!s}({float(str(ls.length.minimum)):.2f}/{float(str(ls.length.maximum)):.2f}"
            f" w{float(str(ls.width.minimum)):.2f})"
            for ls in seg.lane_segments
        ]
        kind = str(seg.type).split("::")[-1][:5]
        extra = ""
        if kind.startswith("Inter"):
            extra = (
                f" b{float(str(seg.minimum_length_before_intersecting_area)):.2f}"
                f" a{float(str(seg.minimum_length_after_intersecting_area)):.2f}"
            )
        segs.append(f"{kind}{extra}:" + ",".join(lanes))
    return " > ".join(segs)


def inspect(pair: dict[str, Any]) -> None:
    """Print ad-map's view of one pair."""
    ego = oracle._object_data(  # noqa: SLF001
        oracle.EGO_ID, ad.rss.world.ObjectType.EgoVehicle, pair["ego"], 4.5, 2.0, 1.0
    )
    other = oracle._object_data(  # noqa: SLF001
        oracle.OTHER_ID, ad.rss.world.ObjectType.OtherVehicle, pair["other"], 4.5, 1.9, 2.0
    )
    print("ego regions:  ", _regions(ego.match_object))
    print("other regions:", _regions(other.match_object))
    routes = ad.map.route.calculateConnectingRoutes(
        ego.match_object, other.match_object, ad.physics.Distance(120.0)
    )
    for cr in routes:
        kind = str(cr.type).split("::")[-1]
        feas = float(str(ad.map.route.getHeadingFeasibility(cr)))
        inter = ad.map.route.isConnectedRoutePartOfAnIntersection(cr)
        print(f"connecting {kind} feas={feas:.2f} intersection={inter}")
        print("   a:", _route_lanes(cr.route_a))
        print("   b:", _route_lanes(cr.route_b))
    mode = ad.map.route.RouteCreationMode.SameDrivingDirection
    dup = ad.map.route.FilterDuplicatesMode.SubRoutesPreferLongerOnes
    for name, obj in (("ego", ego), ("other", other)):
        preds = ad.map.route.predictRoutesOnDistance(
            obj.match_object, ad.physics.Distance(60.0), mode, dup
        )
        for r in preds:
            print(f"{name} predicted:", _route_lanes(r))
    creation = ad.rss.map.RssWorldModelCreation(1, oracle._dynamics(1.0))  # noqa: SLF001
    oracle.append_structured(creation, ego, other)
    model = creation.getWorldModel()
    for c in model.constellations:
        print("constellation", str(c.constellation_type).split("::")[-1])
        print("   ego road:", _road(c.ego_vehicle_road))
        if len(c.intersecting_road):
            print("   obj road:", _road(c.intersecting_road))
        for name, o in (("ego", c.ego_vehicle), ("obj", c.object)):
            regs = [
                f"{r.segment_id!s} lon[{float(str(r.lon_range.minimum)):.3f},"
                f"{float(str(r.lon_range.maximum)):.3f}] lat[{float(str(r.lat_range.minimum)):.2f},"
                f"{float(str(r.lat_range.maximum)):.2f}]"
                for r in o.occupied_regions
            ]
            v = o.velocity
            speed = (
                f" v_lon[{float(str(v.speed_lon_min)):.2f},{float(str(v.speed_lon_max)):.2f}]"
                f" v_lat[{float(str(v.speed_lat_min)):.2f},{float(str(v.speed_lat_max)):.2f}]"
            )
            print(f"   {name}:", "; ".join(regs), speed)


def main() -> None:
    """Inspect every pair read from stdin."""
    content = Path(sys.argv[1]).read_text()
    pairs = json.load(sys.stdin)
    real = os.dup(1)
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    try:
        oracle.init_map(content)
    finally:
        os.dup2(real, 1)
    for k, pair in pairs:
        print(f"===== pair {k}")
        inspect(pair)
        sys.stdout.flush()


if __name__ == "__main__":
    main()
