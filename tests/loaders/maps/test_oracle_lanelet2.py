"""Differential test: ``read_lanelet2`` against the lanelet2 library (``pip lanelet2``).

Maps: every ``sample_logs/*.osm`` (generated, with ``local_x``/``local_y`` tags) and the
external ``maps/mapping_example.osm`` (lat/lon only). lanelet2 loads each with a
``UtmProjector`` whose origin is the file's first node.

Comparison rules:

- *Ids*: the same lanelet ids.
- *Topology* is compared on the vehicle subset: lanelets a German vehicle may pass
  (``traffic_rules.canPass``). Crosswalks, walkways, bicycle lanes and parking lanelets
  are not in a vehicle routing graph, so successors and predecessors are compared after
  intersecting ours with that subset. Our ``successors`` are the lanes attached at the
  reference end in any allowed traversal. In lanelet2 terms that is
  ``following(ll)``, plus ``previous(ll.invert())`` when the lanelet is not one-way for
  vehicles. Predecessors mirror this. Our ``BIDIRECTIONAL`` must equal
  ``not isOneWay``.
- *Neighbours*: wherever the routing graph reports a left/right lanelet (``left`` or
  ``adjacentLeft``), ours is the same id with the same "opposite" flag (lanelet2: the
  neighbour is inverted). Conversely, a same-direction neighbour of ours inside the
  vehicle subset must be reported by lanelet2. lanelet2 reports no neighbours for
  pedestrian lanelets and no oncoming-lane neighbours, so those are not compared.
- *Geometry*: the same vertex count per border, in the same order.
  - With ``local_x``/``local_y`` tags, ours equal the tags that lanelet2 keeps on its
    points, exactly.
  - Every border's length agrees with lanelet2's UTM length within 0.5 %. The sample
    files' lat/lon come from a spherical approximation, so they are up to 0.2 % off
    their own local tags.
  - For lat/lon-only maps the projection difference is removed by a best-fit
    similarity transform. Residual < 1 cm, scale within 0.1 % of 1 (UTM scales by
    about 0.9996).
- *Regulatory elements*: the same number of ``traffic_light`` and ``right_of_way``
  elements, the same controlled, priority and yield lanelets. Speed limits are compared
  where a lanelet is tagged (a ``speed_limit`` tag or a speed-limit element). There,
  ours equals ``traffic_rules.speedLimit``, which lanelet2's Python binding gives in
  km/h. Untagged lanelets get a location default in lanelet2 and NaN in ours.
"""

from __future__ import annotations

import functools
import importlib
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from loaders.maps.lanelet2 import read_lanelet2
from loaders.maps.model import LaneDirection, LaneMap
from tests.conftest import running_in_ci

pytestmark = pytest.mark.oracle

_REASON = "lanelet2 (pip lanelet2, in the `test` extra) not installed"
if running_in_ci():
    lanelet2: Any = importlib.import_module("lanelet2")  # CI=true: a missing oracle fails
else:
    lanelet2 = pytest.importorskip("lanelet2", reason=_REASON)

SAMPLE_DIR = Path(__file__).resolve().parents[3] / "sample_logs"
SAMPLE_MAPS = sorted(p.name for p in SAMPLE_DIR.glob("*.osm"))
EXTERNAL_MAP = "maps/mapping_example.osm"
MAPS = [
    *(pytest.param(f"sample:{name}", id=name) for name in SAMPLE_MAPS),
    pytest.param(f"external:{EXTERNAL_MAP}", id="mapping_example", marks=pytest.mark.external),
]
LENGTH_RTOL = 0.005
KMH = 1.0 / 3.6


@dataclass(frozen=True)
class Pair:
    """One map read by both readers."""

    ours: LaneMap
    theirs: Any
    rules: Any
    graph: Any
    local_tags: bool

    @functools.cached_property
    def by_id(self) -> dict[str, Any]:
        return {str(ll.id): ll for ll in self.theirs.laneletLayer}

    @functools.cached_property
    def vehicle(self) -> set[str]:
        return {i for i, ll in self.by_id.items() if self.rules.canPass(ll)}


@functools.cache
def _load(path: Path) -> Pair:
    text = path.read_text(encoding="utf-8")
    first = re.search(r"""lat=["']([-0-9.]+)["']\s+lon=["']([-0-9.]+)["']""", text)
    assert first is not None, "no node with lat/lon"
    origin = lanelet2.io.Origin(float(first.group(1)), float(first.group(2)))
    theirs, errors = lanelet2.io.loadRobust(str(path), lanelet2.projection.UtmProjector(origin))
    assert list(errors) == []
    tr = lanelet2.traffic_rules
    rules = tr.create(tr.Locations.Germany, tr.Participants.Vehicle)
    graph = lanelet2.routing.RoutingGraph(theirs, rules)
    return Pair(read_lanelet2(path), theirs, rules, graph, "local_x" in text)


@pytest.fixture(params=MAPS)
def pair(request: pytest.FixtureRequest) -> Pair:
    where, name = str(request.param).split(":", 1)
    if where == "sample":
        return _load(SAMPLE_DIR / name)
    path = Path(request.getfixturevalue("external_dir")) / name
    if not path.is_file():
        if running_in_ci():
            pytest.fail(f"{path} missing (CI=true: external data is required)")
        pytest.skip(f"{path} missing")
    return _load(path)


def _ids(lanelets: Any) -> set[str]:
    return {str(ll.id) for ll in lanelets}


def _points(linestring: Any) -> np.ndarray:
    return np.array([(p.x, p.y) for p in linestring], dtype=np.float64).reshape(-1, 2)


def _length(points: np.ndarray) -> float:
    steps = np.diff(points, axis=0)
    return float(np.hypot(steps[:, 0], steps[:, 1]).sum())


def test_sample_maps_present() -> None:
    assert len(SAMPLE_MAPS) >= 6


def test_lanelet_ids(pair: Pair) -> None:
    assert set(pair.ours.lanes) == set(pair.by_id)


def test_vehicle_topology(pair: Pair) -> None:
    vehicle, graph = pair.vehicle, pair.graph
    assert vehicle
    for lid in sorted(vehicle):
        ll, lane = pair.by_id[lid], pair.ours.lanes[lid]
        two_way = not pair.rules.isOneWay(ll)
        assert (lane.direction is LaneDirection.BIDIRECTIONAL) == two_way, lid
        succ, pred = _ids(graph.following(ll)), _ids(graph.previous(ll))
        if two_way:
            succ |= _ids(graph.previous(ll.invert()))
            pred |= _ids(graph.following(ll.invert()))
        assert set(lane.successors) & vehicle == succ, f"successors of {lid}"
        assert set(lane.predecessors) & vehicle == pred, f"predecessors of {lid}"


def test_neighbours(pair: Pair) -> None:
    graph, reported = pair.graph, 0
    for lid in sorted(pair.vehicle):
        ll, lane = pair.by_id[lid], pair.ours.lanes[lid]
        for side, change, adjacent in (
            ("left", graph.left, graph.adjacentLeft),
            ("right", graph.right, graph.adjacentRight),
        ):
            theirs = change(ll) or adjacent(ll)
            ours = getattr(lane, f"{side}_neighbour")
            opposite = getattr(lane, f"{side}_neighbour_opposite")
            if theirs is not None:
                reported += 1
                assert (ours, opposite) == (str(theirs.id), theirs.inverted()), (lid, side)
            elif ours in pair.vehicle:
                assert opposite, f"{side} neighbour {ours} of {lid} not reported by lanelet2"
    if pair.ours.source.endswith("mapping_example.osm"):
        assert reported == 222  # 111 left + 111 right


def test_border_geometry(pair: Pair) -> None:
    ours_pts, theirs_pts = [], []
    for lid, ll in pair.by_id.items():
        lane = pair.ours.lanes[lid]
        for side, mine in (("left", lane.left_m), ("right", lane.right_m)):
            bound = ll.leftBound if side == "left" else ll.rightBound
            utm = _points(bound)
            assert mine.shape == utm.shape, (lid, side)
            assert _length(mine) == pytest.approx(_length(utm), rel=LENGTH_RTOL), (lid, side)
            if pair.local_tags:
                tagged = [
                    (float(p.attributes["local_x"]), float(p.attributes["local_y"])) for p in bound
                ]
                np.testing.assert_array_equal(mine, np.array(tagged), err_msg=f"{lid} {side}")
            ours_pts.append(mine)
            theirs_pts.append(utm)
    if pair.local_tags:
        return
    a, b = np.concatenate(ours_pts), np.concatenate(theirs_pts)
    a, b = a - a.mean(axis=0), b - b.mean(axis=0)
    u, s, vt = np.linalg.svd(a.T @ b)
    rot = (u @ vt).T
    assert np.linalg.det(rot) > 0.0
    scale = float(s.sum() / (a * a).sum())
    residual = np.hypot(*(scale * a @ rot.T - b).T)
    assert scale == pytest.approx(1.0, rel=1e-3)
    assert float(residual.max()) < 0.01


def test_regulatory_elements(pair: Pair) -> None:
    regs = list(pair.theirs.regulatoryElementLayer)
    lights = {str(r.id): r for r in regs if r.attributes["subtype"] == "traffic_light"}
    rows = {str(r.id): r for r in regs if r.attributes["subtype"] == "right_of_way"}
    assert {t.id for t in pair.ours.traffic_lights} == set(lights)
    assert {r.id for r in pair.ours.right_of_way} == set(rows)
    for light in pair.ours.traffic_lights:
        controlled = {i for i, ll in pair.by_id.items() if light.id in _ids(ll.trafficLights())}
        assert set(light.controlled_lanes) == controlled, light.id
    for row in pair.ours.right_of_way:
        theirs = rows[row.id]
        assert set(row.priority_lanes) == _ids(theirs.rightOfWayLanelets()), row.id
        assert set(row.yield_lanes) == _ids(theirs.yieldLanelets()), row.id


def test_speed_limits_where_tagged(pair: Pair) -> None:
    for lid, ll in pair.by_id.items():
        ours = pair.ours.lanes[lid].speed_limit_mps
        if "speed_limit" in ll.attributes or len(ll.speedLimits()) > 0:
            theirs_kmh = pair.rules.speedLimit(ll).speedLimit
            assert ours == pytest.approx(theirs_kmh * KMH, rel=1e-9), lid
        else:
            assert math.isnan(ours), lid
