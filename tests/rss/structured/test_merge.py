"""Worst-case merging of similar constellations (ad-rss ``RssSituationExtraction``)."""

import dataclasses

import numpy as np
import pytest

from rss.model import Constellation, SpeedInterval
from rss.params import DEFAULT_EGO_DYNAMICS, RestrictSpeedLimitMode, SceneSettings
from rss.scene import create_scene, prepare
from rss.structured.engine import check_frame
from rss.structured.extraction import extract
from rss.structured.merge import merge_position_groups, merge_positions, merge_similar
from rss.structured.stacking import stack_constellations
from rss.structured.states import LateralPosition as Lat
from rss.structured.states import LongitudinalPosition as Lon
from tests.rss.scene.synthetic import WIDTH, ego, objects, straight_road

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)


@pytest.mark.parametrize(
    ("a", "b", "expected"),
    [
        ((Lon.InFront, 5.0), (Lon.InFront, 3.0), (Lon.InFront, 3.0)),
        ((Lon.InFront, 5.0), (Lon.AtBack, 3.0), (Lon.Overlap, 0.0)),
        ((Lon.OverlapFront, 0.0), (Lon.InFront, 3.0), (Lon.OverlapFront, 0.0)),
        ((Lon.AtBack, 2.0), (Lon.OverlapBack, 0.0), (Lon.OverlapBack, 0.0)),
        ((Lon.Overlap, 0.0), (Lon.AtBack, 4.0), (Lon.Overlap, 0.0)),
        ((Lat.AtLeft, 1.0), (Lat.AtRight, 2.0), (Lat.Overlap, 0.0)),
        ((Lat.OverlapLeft, 0.0), (Lat.AtLeft, 2.0), (Lat.OverlapLeft, 0.0)),
    ],
)
def test_merge_positions_worst_case(a, b, expected):
    code, dist = merge_positions(int(a[0]), int(b[0]), a[1], b[1])
    assert (code, dist) == (int(expected[0]), expected[1])
    assert merge_positions(int(b[0]), int(a[0]), b[1], a[1]) == (code, dist)


@pytest.mark.parametrize("seed", [1, 7, 2026])
def test_merge_position_groups_equals_the_scalar_fold(seed):
    rng = np.random.default_rng(seed)
    sizes = rng.integers(1, 6, size=300)
    codes = rng.integers(0, 5, size=(int(sizes.sum()), 2))
    far = (codes == 0) | (codes == 4)  # AtLeft / AtRight (InFront / AtBack)
    distances = np.where(far, rng.uniform(0.0, 30.0, codes.shape).round(1), 0.0)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    got_codes, got_distances = merge_position_groups(codes, distances, starts)
    for g, (lo, n) in enumerate(zip(starts.tolist(), sizes.tolist(), strict=True)):
        for k in range(2):
            code, dist = int(codes[lo, k]), float(distances[lo, k])
            for row in range(lo + 1, lo + n):
                code, dist = merge_positions(code, int(codes[row, k]), dist, distances[row, k])
            assert (int(got_codes[g, k]), float(got_distances[g, k])) == (code, dist)


def _pair_on_both_sides() -> tuple[Constellation, Constellation]:
    """One object seen twice: left of the ego and right of it (same id, same type)."""
    prep = prepare(straight_road())
    scene = create_scene(
        prep,
        ego(50.0, 0.0),
        objects((70.0, WIDTH, 0.0, 8.0), (80.0, -WIDTH, 0.0, 12.0)),
        SETTINGS,
    )
    left, right = scene.constellations
    other = dataclasses.replace(
        right.other,
        object_id=left.other.object_id,
        speed=SpeedInterval(11.0, 12.0, -0.5, 0.0),
    )
    return left, dataclasses.replace(right, other=other)


def test_contradicting_sides_merge_to_lateral_overlap_and_speed_union():
    left, right = _pair_on_both_sides()
    batch = stack_constellations([left, right])
    rel = extract(batch)
    assert {int(v) for v in rel.lat_position} == {int(Lat.AtLeft), int(Lat.AtRight)}
    merged, mrel = merge_similar(batch, rel, np.zeros(2, dtype=np.int64))
    assert mrel.lat_position.tolist() == [int(Lat.Overlap)] * 2
    assert mrel.lat_distance_m.tolist() == [0.0, 0.0]
    assert mrel.lon_distance_m.tolist() == [float(rel.lon_distance_m.min())] * 2
    assert merged.other.speed_lon_min_mps.tolist() == [8.0, 8.0]
    assert merged.other.speed_lon_max_mps.tolist() == [12.0, 12.0]
    assert merged.other.speed_lat_min_mps.tolist() == [-0.5, -0.5]


def test_merged_rows_share_one_verdict_and_other_frames_stay_apart():
    left, right = _pair_on_both_sides()
    batch = stack_constellations([left, right])
    rel = extract(batch)
    merged, mrel = merge_similar(batch, rel, np.array([0, 1]))
    assert merged is batch  # different frames: nothing to merge
    assert mrel is rel
    result, _ = check_frame(batch, DEFAULT_EGO_DYNAMICS)
    assert result.dangerous[0] == result.dangerous[1]
    assert result.relative.lat_distance_m.tolist() == [0.0, 0.0]
