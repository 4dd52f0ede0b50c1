"""Points along flat-array polylines (``rss.scene.polylines``) against shapely, the reference."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from rss.scene.polylines import heading_at, interpolate, polylines

#: Agreement with GEOS: the same formulas, so differences are a few ulps of the coordinates.
TOL_M = 1e-9


def _lines(rng: np.random.Generator) -> np.ndarray:
    """Straight, curved (dense), zig-zag and two-point lines, like lane centre lines."""
    out = [shapely.LineString([(0.0, 0.0), (30.0, 0.0)])]
    t = np.linspace(0.0, np.pi / 2, 60)
    out.append(shapely.LineString(np.c_[20.0 * np.cos(t) + 5.0, 20.0 * np.sin(t) - 3.0]))
    for _ in range(6):
        steps = rng.normal(0.0, 4.0, (int(rng.integers(1, 12)), 2)) + np.array([5.0, 0.0])
        start = rng.uniform(-50.0, 50.0, 2)
        out.append(shapely.LineString(np.vstack([start, start + np.cumsum(steps, axis=0)])))
    return np.array(out, dtype=object)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_interpolate_and_heading_match_shapely(seed: int) -> None:
    rng = np.random.default_rng(seed)
    lines = _lines(rng)
    flat = polylines(lines)
    which = rng.integers(0, len(lines), 3000)
    length = flat.length_m[which]
    s = rng.uniform(-0.2, 1.2, 3000) * length
    vertices = rng.integers(0, len(flat.xy_m), 200)
    which[:200] = np.searchsorted(flat.start, vertices, side="right") - 1
    s[:200] = flat.s_at_m[vertices]
    clamped = np.clip(s, 0.0, flat.length_m[which])
    ref = shapely.get_coordinates(shapely.line_interpolate_point(lines[which], clamped))
    np.testing.assert_allclose(interpolate(flat, which, s), ref, rtol=0.0, atol=TOL_M)
    a = shapely.line_interpolate_point(lines[which], np.clip(s - 0.5, 0.0, flat.length_m[which]))
    b = shapely.line_interpolate_point(lines[which], np.clip(s + 0.5, 0.0, flat.length_m[which]))
    d = shapely.get_coordinates(b) - shapely.get_coordinates(a)
    np.testing.assert_allclose(
        heading_at(flat, which, s, 0.5), np.arctan2(d[:, 1], d[:, 0]), rtol=0.0, atol=1e-9
    )


def test_empty_queries() -> None:
    flat = polylines(_lines(np.random.default_rng(0)))
    assert interpolate(flat, np.zeros(0, dtype=np.int64), np.zeros(0)).shape == (0, 2)


def test_lengths_match_shapely() -> None:
    lines = _lines(np.random.default_rng(3))
    np.testing.assert_array_equal(polylines(lines).length_m, shapely.length(lines))
