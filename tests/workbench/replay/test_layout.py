import numpy as np
import pytest

from loaders.maps.model import LineType
from loaders.records import ActorTable, EgoState, Frame, ObjectClass
from tests.workbench.fakes import straight_road, synthetic_frame
from workbench.replay.layout import (
    PLAN_Z_M,
    layout_chunk,
    layout_map,
    pad_polylines,
    yaw_to_quaternion,
)


def test_quaternion_of_yaw_rotates_x_axis_to_heading():
    q = yaw_to_quaternion(np.array([0.0, np.pi / 2, np.pi]))
    np.testing.assert_allclose(q[0], [0, 0, 0, 1], atol=1e-7)
    np.testing.assert_allclose(q[1], [0, 0, np.sqrt(0.5), np.sqrt(0.5)], atol=1e-7)
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-6)
    # rotate +x by q[1] (90 deg): x' = 1 - 2(y^2 + z^2), y' = 2(xy + zw)
    x, y, z, w = q[1]
    assert 1 - 2 * (y * y + z * z) == pytest.approx(0.0, abs=1e-6)
    assert 2 * (x * y + z * w) == pytest.approx(1.0, abs=1e-6)


def test_pad_polylines_repeats_last_vertex_and_drops_empty():
    lines = [
        np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]),
        np.zeros((0, 2)),
        np.array([[5.0, 5.0]]),
    ]
    out = pad_polylines(lines, z_m=0.5)
    assert out.shape == (2, 3, 3)
    np.testing.assert_array_equal(out[1], [[5, 5, 0.5]] * 3)
    np.testing.assert_array_equal(out[0, :, 2], 0.5)
    assert pad_polylines([]).shape == (0, 0, 3)


def test_chunk_columns_have_matching_lengths_and_partitions():
    frames = [synthetic_frame(i, n_actors=i % 4) for i in range(8)]
    lay = layout_chunk(frames)
    assert len(lay) == 8
    np.testing.assert_array_equal(lay.frame, np.arange(8))
    assert lay.ego.centre_m.shape == (8, 3)
    assert lay.ego.centre_m[0, 2] == pytest.approx(0.75)  # z + height / 2
    counts = lay.actors.counts
    np.testing.assert_array_equal(counts, [0, 1, 2, 3, 0, 1, 2, 3])
    m = int(counts.sum())
    for arr in (lay.actors.centre_m, lay.actors.half_size_m, lay.actors.velocity_mps):
        assert arr.shape == (m, 3)
    assert lay.actors.quaternion_xyzw.shape == (m, 4)
    assert lay.actors.labels.tolist()[:3] == ["car0", "car0", "car1"]
    assert np.isnan(lay.actors.min_distance_m[0])
    assert lay.actors.min_distance_m[1] == pytest.approx(10.0)
    assert lay.plan.strips_m.shape == (8, 16, 3)
    np.testing.assert_allclose(lay.plan.strips_m[..., 2], PLAN_Z_M, rtol=1e-6)


def test_invalid_actors_are_left_out_and_missing_plans_clear():
    actors = ActorTable.from_columns(
        ids=["a", "b"],
        object_class=[ObjectClass.PEDESTRIAN, ObjectClass.CAR],
        x_m=[3.0, np.nan],
        y_m=[4.0, 0.0],
        yaw_rad=[0.0, 0.0],
        vx_mps=[1.0, 0.0],
        vy_mps=[0.0, 0.0],
        length_m=[0.5, 4.0],
        width_m=[0.5, 2.0],
    )
    ego = EgoState(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    frames = [Frame(index=0, t_ns=0, ego=ego, actors=actors), synthetic_frame(1, 0)]
    lay = layout_chunk(frames)
    np.testing.assert_array_equal(lay.actors.counts, [1, 0])
    assert lay.actors.class_ids.tolist() == [ObjectClass.PEDESTRIAN]
    assert lay.actors.min_distance_m[0] == pytest.approx(5.0)
    np.testing.assert_array_equal(lay.plan.counts, [0, 1])
    assert lay.plan.strips_m.shape[0] == 1


def test_map_groups_borders_by_line_type_without_duplicates():
    lane_map = straight_road(lanes=3)
    lay = layout_map(lane_map)
    assert set(lay.borders) == {LineType.SOLID.value, LineType.DASHED.value}
    # 3 lanes have 4 distinct borders: 2 solid outer, 2 dashed shared
    assert len(lay.borders["solid"]) == 2
    assert len(lay.borders["dashed"]) == 2
    assert lay.centres["road"].shape == (3, 9, 3)
    assert lay.boundaries.shape[0] == 0
    assert not lay.is_empty
