import numpy as np
import pytest

from loaders.maps.geometry import (
    arc_length_m,
    centre_line_m,
    project_to_local_enu_m,
    resample_polyline_m,
)


def test_arc_length_of_an_l_shape():
    np.testing.assert_allclose(arc_length_m([[0, 0], [3, 4], [3, 10]]), [0, 5, 11])
    assert arc_length_m(np.zeros((0, 2))).shape == (0,)


def test_resample_keeps_ends_and_spaces_evenly():
    out = resample_polyline_m([[0, 0], [10, 0], [10, 10]], 5)
    np.testing.assert_allclose(out, [[0, 0], [5, 0], [10, 0], [10, 5], [10, 10]])


def test_resample_degenerate_polyline_repeats_the_point():
    np.testing.assert_allclose(resample_polyline_m([[1, 2]], 3), [[1, 2]] * 3)


def test_resample_rejects_too_few_output_points():
    with pytest.raises(ValueError, match="cannot resample"):
        resample_polyline_m([[0, 0], [1, 0]], 1)


def test_centre_line_averages_borders_with_different_vertex_counts():
    left = [[0, 2], [5, 2], [10, 2]]
    right = [[0, 0], [10, 0]]
    np.testing.assert_allclose(centre_line_m(left, right), [[0, 1], [5, 1], [10, 1]])


def test_projection_origin_and_scale():
    east, north = project_to_local_enu_m([49.0, 49.001, 49.0], [8.4, 8.4, 8.401], 49.0, 8.4)
    np.testing.assert_allclose(east[:2], [0, 0], atol=1e-6)
    np.testing.assert_allclose(north[[0, 2]], [0, 0], atol=1e-3)
    # One millidegree of latitude is about 111.2 m; of longitude at 49 deg about 73.2 m.
    assert north[1] == pytest.approx(111.21, abs=0.05)
    assert east[2] == pytest.approx(73.17, abs=0.05)
