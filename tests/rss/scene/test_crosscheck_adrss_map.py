"""Differential test against ad-rss map integration 5.0 on CARLA Town01 (500 seeded pairs).

Needs ``RSS_MAP_ORACLE_PYTHON``: an interpreter with ``ad-rss-map-integration`` 5.0 and
the packaging work-around of the reference notes §8.4 (see ``adrss_map_oracle.py``);
skipped otherwise. Compares, pair by pair, the set of constellation types, the lon/lat
distances of pairs that both sides model with one same/opposite-direction constellation,
and the verdict (any dangerous constellation), in two modes on the same oracle answers:
the default one (ad-rss' two documented defects not reproduced, their pairs counted apart)
and ``[scene] reproduce_adrss_5_0_defects`` (raw agreement). docs/rss_scene.md lists the
measured rates; the thresholds here guard against regressions.
"""

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import shapely

from loaders.maps.model import LaneKind, LaneMap
from loaders.maps.opendrive import read_opendrive
from rss.params import (
    DEFAULT_EGO_DYNAMICS,
    DEFAULT_VEHICLE_DYNAMICS,
    RestrictSpeedLimitMode,
    SceneSettings,
)
from rss.scene import (
    PreparedGraph,
    SceneEgo,
    SceneMemo,
    SceneObjects,
    create_scene,
    match_boxes,
    prepare,
)
from rss.scene.create import scene_boxes
from rss.scene.junction_arms import Arm, intersection_arms
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from tests.rss.scene.oracle_processes import ask_in_parallel
from workbench.engines.rss.adapter import lane_graph_from_map

ORACLE = Path(__file__).with_name("adrss_map_oracle.py")
N_PAIRS = 500
SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
#: The same settings with ad-rss 5.0's defects reproduced (``[scene]
#: reproduce_adrss_5_0_defects``).
COMPAT_SETTINGS = SceneSettings(
    restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
)


def _pose(prep: PreparedGraph, rng: np.random.Generator, lane: int) -> dict[str, float]:
    """A point uniform along a lane's centre line, heading along the line there."""
    c = prep.graph.centre_m[lane]
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(c, axis=0).T))])
    s = rng.uniform(0.0, arc[-1])
    k = int(np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(c) - 2))
    d = c[k + 1] - c[k]
    p = c[k] + (s - arc[k]) / max(arc[k + 1] - arc[k], 1e-12) * d
    return {"x": float(p[0]), "y": float(p[1]), "yaw": float(np.arctan2(d[1], d[0]))}


def placements(prep: PreparedGraph, seed: int, n: int) -> list[dict[str, Any]]:
    """``n`` ego/other pairs on lanes, 6-50 m apart, headings along their lanes.

    The ego is on a road (not junction) lane, the other on a lane whose centre line passes
    within 50 m; both uniform along their lanes' centre lines.
    """
    rng = np.random.default_rng(seed)
    g = prep.graph
    roads = np.flatnonzero(~g.is_intersection)
    pairs: list[dict[str, Any]] = []
    while len(pairs) < n:
        ego = _pose(prep, rng, int(rng.choice(roads)))
        gaps = shapely.distance(prep.centre_lines, shapely.Point(ego["x"], ego["y"]))
        near = np.flatnonzero(gaps < 50.0)
        other = _pose(prep, rng, int(rng.choice(near)))
        gap = np.hypot(other["x"] - ego["x"], other["y"] - ego["y"])
        if 6.0 <= gap <= 50.0:
            ego["v"], other["v"] = float(rng.uniform(0, 12)), float(rng.uniform(0, 12))
            pairs.append({"ego": ego, "other": other})
    return pairs


def pair_inputs(pair: dict[str, Any]) -> tuple[SceneEgo, SceneObjects]:
    """Scene inputs of one placement (the oracle script builds the same vehicles)."""
    e, o = pair["ego"], pair["other"]
    ego = SceneEgo(1000, e["x"], e["y"], e["yaw"], e["v"], 4.5, 2.0, DEFAULT_EGO_DYNAMICS)
    objects = SceneObjects(
        ids=np.array([1]),
        object_type=np.array([2]),
        x_m=np.array([o["x"]]),
        y_m=np.array([o["y"]]),
        yaw_rad=np.array([o["yaw"]]),
        vx_mps=np.array([o["v"] * np.cos(o["yaw"])]),
        vy_mps=np.array([o["v"] * np.sin(o["yaw"])]),
        length_m=np.array([4.5]),
        width_m=np.array([1.9]),
        dynamics=(DEFAULT_VEHICLE_DYNAMICS,),
    )
    return ego, objects


def ours(
    prep: PreparedGraph, pair: dict[str, Any], settings: SceneSettings = SETTINGS
) -> dict[str, Any]:
    """Our situations of one pair in the oracle's answer format (types, distances, speeds)."""
    ego, objects = pair_inputs(pair)
    scene = create_scene(prep, ego, objects, settings)
    out: dict[str, Any] = {"situations": [], "dangerous": []}
    if scene.constellations:
        result, _ = check_frame(stack_constellations(scene.constellations), DEFAULT_EGO_DYNAMICS)
        for i, c in enumerate(scene.constellations):
            out["situations"].append(
                {
                    "type": c.constellation_type.name,
                    "lon_d": float(result.relative.lon_distance_m[i]),
                    "lat_d": float(result.relative.lat_distance_m[i]),
                    "ego_v_lon": c.ego.speed.lon_max_mps,
                    "ego_v_lat": c.ego.speed.lat_max_mps,
                    "other_v_lon": c.other.speed.lon_max_mps,
                    "other_v_lat": c.other.speed.lat_max_mps,
                }
            )
        out["dangerous"] = [bool(x) for x in result.dangerous]
    return out


#: ad-rss 5.0 resolves the speeds of a Following pair with the object behind along the
#: other vehicle's heading (docs/rss_scene.md, deviations): its ego then has a lateral speed
#: although it drives along its (straight) lane.
_SWAPPED_HEADING_MPS = 0.3


def _swapped_headings(answer: dict[str, Any]) -> bool:
    return any(
        abs(s.get("ego_v_lat", 0.0)) > _SWAPPED_HEADING_MPS
        for s in answer["situations"]
        if s["type"] == "SameDirection"
    )


#: ad-map's names of the turn directions (``Intersection.turnDirection``).
_TURN_NAMES = {
    Arm.UTURN: "UTurn",
    Arm.LEFT: "Left",
    Arm.STRAIGHT: "Straight",
    Arm.RIGHT: "Right",
    Arm.UNKNOWN: "Unknown",
}


def admap_lane_id(prep: PreparedGraph, lane: int) -> str:
    """ad-map's id of one of our OpenDRIVE lanes (``road_section_lane``), as a string."""
    road, section, idx = prep.graph.ids[lane].split("_")
    return str(int(road) * 10000 + (int(section) + 1) * 100 + int(idx) + 50)


def turn_defect(prep: PreparedGraph, pair: dict[str, Any], answer: dict[str, Any]) -> bool:
    """Whether ad-map's Town01 turn-direction defect is in play for a pair.

    ad-map 5.0 takes some left turns for U-turns (docs/rss_scene.md, deviations). A pair
    is affected when the oracle reports, on one of the ego's predicted routes, a turn that
    differs from the geometric one (:func:`rss.scene.junction_arms.intersection_arms`) at a
    junction the other vehicle touches or is next to.
    """
    lane_of = {admap_lane_id(prep, lane): lane for lane in range(len(prep.graph))}
    jid = prep.junction_list
    ego, objects = pair_inputs(pair)
    touched = set(match_boxes(prep, scene_boxes(ego, objects)).lanes_of(1).tolist())
    for incoming, outgoing, turn in answer.get("turns", []):
        lane_in, lane_out = lane_of[incoming[0]], lane_of[outgoing[0]]
        ends = (*prep.graph.successors[lane_in], *prep.graph.predecessors[lane_in])
        for j in {jid[b] for b in ends if jid[b] >= 0}:
            arms = intersection_arms(prep, SceneMemo(), j, lane_in)
            arm = arms.get(lane_out)
            if arm is None or _TURN_NAMES[arm] == turn:
                continue
            around = {lane for lane, k in enumerate(jid) if k == j} | set(arms)
            if touched & around:
                return True
    return False


def compare(
    mine: list[dict[str, Any]], theirs: list[dict[str, Any]], turn_defects: list[bool]
) -> dict[str, float]:
    """Agreement rates (types, verdicts) and distance errors.

    ``turn_defects`` flags the pairs :func:`turn_defect` attributes to ad-map's turn
    directions; verdicts are also counted outside both ad-rss defect classes.
    """
    types = verdicts = 0
    plain = plain_verdicts = 0
    clean = clean_verdicts = 0
    lon, lat = [], []
    for a, b, turn in zip(mine, theirs, turn_defects, strict=True):
        ta = {s["type"] for s in a["situations"]}
        tb = {s["type"] for s in b["situations"]} - {"NotRelevant"}
        types += ta == tb
        same_verdict = any(a["dangerous"]) == any(b["dangerous"])
        verdicts += same_verdict
        if not _swapped_headings(b):
            plain += 1
            plain_verdicts += same_verdict
            if not turn:
                clean += 1
                clean_verdicts += same_verdict
        single = len(a["situations"]) == len(b["situations"]) == 1
        if single and ta == tb and ta <= {"SameDirection", "OppositeDirection"}:
            lon.append(abs(a["situations"][0]["lon_d"] - b["situations"][0]["lon_d"]))
            lat.append(abs(a["situations"][0]["lat_d"] - b["situations"][0]["lat_d"]))
    n = len(mine)
    return {
        "types": types / n,
        "verdicts": verdicts / n,
        "verdicts_without_swapped_headings": plain_verdicts / max(plain, 1),
        "swapped_heading_pairs": float(n - plain),
        "verdicts_outside_defects": clean_verdicts / max(clean, 1),
        "turn_defect_pairs": float(plain - clean),
        "compared": float(len(lon)),
        "lon_median_m": float(np.median(lon)),
        "lon_within_0_5": float(np.mean(np.array(lon) < 0.5)),
        "lon_within_0_01": float(np.mean(np.array(lon) < 0.01)),
        "lat_within_0_2": float(np.mean(np.array(lat) < 0.2)),
        "lat_within_0_01": float(np.mean(np.array(lat) < 0.01)),
    }


def _oracle_python() -> str:
    oracle_python = os.environ.get("RSS_MAP_ORACLE_PYTHON")
    if not oracle_python:
        pytest.skip(
            "RSS_MAP_ORACLE_PYTHON (ad-rss-map-integration 5.0 interpreter) not set; "
            "`make test` runs this module with its side venv (make oracle-adrss-map)"
        )
    return oracle_python


def border_gaps(lane_map: LaneMap, theirs: dict[str, Any]) -> dict[str, float]:
    """Per lane of ``lane_map``: the largest distance (m) between our border vertices and
    ad-map's, ``inf`` when the vertex counts differ.

    ad-map orders borders along the road's ``s`` (our left lanes are reversed) and turns
    some junction lanes round (their borders reversed and swapped): our borders are
    compared in ad-map's order as the reader flags it (``Lane.admap_reversed``), so a
    wrong flag shows as a gap of metres.
    """
    gaps = {}
    for lane_id, lane in lane_map.lanes.items():
        road, section, idx = lane_id.split("_")
        ad_id = str(int(road) * 10000 + (int(section) + 1) * 100 + int(idx) + 50)
        left, right = np.array(theirs[ad_id]["left"]), np.array(theirs[ad_id]["right"])
        ours_l, ours_r = lane.left_m, lane.right_m
        if lane.admap_reversed:
            ours_l, ours_r = ours_r[::-1], ours_l[::-1]
        gap = np.inf
        if ours_l.shape == left.shape and ours_r.shape == right.shape:
            gap = float(max(np.abs(ours_l - left).max(), np.abs(ours_r - right).max()))
        gaps[lane_id] = gap
    return gaps


def test_town01_borders_are_ad_maps(external_dir):
    """Every Town01 lane border vertex (212 lanes of all kept kinds) is ad-map's, in its order."""
    town = external_dir / "maps" / "Town01.xodr"
    out = subprocess.run(  # noqa: S603 - interpreter chosen by the tester
        [_oracle_python(), str(ORACLE), str(town), "--borders"],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    ).stdout
    theirs = json.loads(out.strip().splitlines()[-1])
    lane_map = read_opendrive(town)
    gaps = border_gaps(lane_map, theirs)
    drivable = [
        k for k, ln in lane_map.lanes.items() if ln.kind in {LaneKind.ROAD, LaneKind.INTERSECTION}
    ]
    assert len(drivable) == 124
    assert len(gaps) == 212
    assert not [k for k, gap in gaps.items() if gap == np.inf], "vertex counts differ"
    assert max(gaps.values()) < 1e-6


@pytest.fixture(scope="module")
def town01_answers(
    external_dir: Path,
) -> tuple[PreparedGraph, list[dict[str, Any]], list[dict[str, Any]]]:
    """The prepared Town01 graph, the seeded pairs and the oracle's answers (asked once)."""
    oracle_python = _oracle_python()
    town = external_dir / "maps" / "Town01.xodr"
    prep = prepare(lane_graph_from_map(read_opendrive(town)))
    pairs = placements(prep, seed=1, n=N_PAIRS)
    # The reference needs about 0.5 s per pair: one oracle process per core, half each.
    halves = [pairs[: N_PAIRS // 2], pairs[N_PAIRS // 2 :]]
    theirs = []
    for code, out, err in ask_in_parallel(oracle_python, ORACLE, town, halves, 1800):
        assert code == 0, f"oracle failed: {err[-2000:]}"
        theirs += json.loads(out.strip().splitlines()[-1])
    return prep, pairs, theirs


def test_town01_against_ad_rss_map_integration(
    town01_answers: tuple[PreparedGraph, list[dict[str, Any]], list[dict[str, Any]]],
) -> None:
    """Default mode: ad-rss 5.0's two documented defects are not reproduced (counted apart)."""
    prep, pairs, theirs = town01_answers
    defects = [turn_defect(prep, p, answer) for p, answer in zip(pairs, theirs, strict=True)]
    stats = compare([ours(prep, p) for p in pairs], theirs, defects)
    sys.stderr.write(f"ad-rss map integration cross-check: {stats}\n")
    # measured (docs/rss_scene.md; pairs uniform along the centre lines since the reader
    # gives ad-map's border vertices): types 98.8 %, verdicts 93.6 % (94.2 % before the
    # default mode joined ad-rss' swapped headings to its own: 3 pairs of that class more
    # are dangerous for us only by the joined speed intervals; 98.8 % outside the 70
    # pairs with ad-rss' swapped route headings, 99.7 % outside those and the 51 pairs where
    # ad-map's turn-direction defect is in play), lateral within 0.2 m 100 % / within 1 cm
    # 100 % (ad-map's lane widths, lattice points for lateral extremes), longitudinal within
    # 0.5 m 100 % and within 1 cm 99.6 % (239 / 240, pair 21 off; its tie rule, aligned
    # cuts of neighbour lanes, lane-end rule, unsimplified borders, lane changes costing
    # the centre-line distance in the route search), median 0.02 mm; since the default
    # mode joins ad-rss' readings, 184 pairs keep one constellation a side: all within 1 cm
    assert stats["types"] >= 0.985
    assert stats["verdicts"] >= 0.935
    assert stats["verdicts_without_swapped_headings"] >= 0.985
    assert stats["verdicts_outside_defects"] >= 0.995
    assert stats["lat_within_0_2"] >= 0.995
    assert stats["lat_within_0_01"] >= 0.995
    assert stats["lon_within_0_5"] >= 0.995
    assert stats["lon_within_0_01"] >= 0.995
    assert stats["lon_median_m"] <= 0.0005


def test_town01_compat_mode_reproduces_ad_rss(
    town01_answers: tuple[PreparedGraph, list[dict[str, Any]], list[dict[str, Any]]],
) -> None:
    """``[scene] reproduce_adrss_5_0_defects``: raw agreement, nothing counted apart."""
    prep, pairs, theirs = town01_answers
    mine = [ours(prep, p, COMPAT_SETTINGS) for p in pairs]
    stats = compare(mine, theirs, [False] * len(pairs))
    sys.stderr.write(f"ad-rss map integration cross-check, compat mode: {stats}\n")
    # measured (docs/rss_scene.md): types 99.8 % (pair 473: ad-map's duplicate filter of
    # routes to lanes side by side), verdicts 100 %, lateral within 0.2 m and 1 cm 100 %,
    # longitudinal within 0.5 m 100 %, within 1 cm 99.6 % (pair 21)
    assert stats["types"] >= 0.996
    assert stats["verdicts"] >= 0.996
    assert stats["lat_within_0_2"] >= 0.995
    assert stats["lat_within_0_01"] >= 0.995
    assert stats["lon_within_0_5"] >= 0.995
    assert stats["lon_within_0_01"] >= 0.995
    assert stats["lon_median_m"] <= 0.0005
