"""``verdict.touching``: GEOS' ``intersects`` per cell, skipped where the boxes are apart."""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.verdict import touching

_GRID = st.integers(-6, 6).map(float)  # a coarse grid: boxes and edges that just touch


@st.composite
def _cells(draw: Any) -> tuple[Any, Any, Any]:
    frames, rows, steps = draw(st.integers(1, 3)), draw(st.integers(1, 4)), draw(st.integers(1, 3))
    frame = np.array(draw(st.lists(st.integers(0, frames - 1), min_size=rows, max_size=rows)))
    corners = np.empty((frames, steps, 4, 2))
    for f in range(frames):
        for k in range(steps):
            x0, y0 = draw(_GRID), draw(_GRID)
            w, h = draw(st.integers(1, 3)), draw(st.integers(1, 3))
            corners[f, k] = [[x0 + w, y0 + h], [x0, y0 + h], [x0, y0], [x0 + w, y0]]
    sets = np.empty((rows, steps), dtype=object)
    for i in range(rows):
        for k in range(steps):
            kind = draw(st.sampled_from(["triangle", "multi", "empty", "none"]))
            pts = [(draw(_GRID), draw(_GRID)) for _ in range(3)]
            triangle = shapely.Polygon(pts)
            far = shapely.Polygon([(x + 20.0, y) for x, y in pts])
            sets[i, k] = {
                "triangle": triangle,
                "multi": shapely.MultiPolygon([triangle, far]),
                "empty": shapely.Polygon(),
                "none": None,
            }[kind]
    return sets, corners, frame


@settings(max_examples=200, deadline=None)
@given(_cells())
def test_touching_is_geos_intersects(cells: tuple[Any, Any, Any]) -> None:
    sets, corners, frame = cells
    ego = np.asarray(shapely.polygons(corners))[frame]
    want = np.asarray(shapely.intersects(sets, ego), dtype=bool)
    got = touching(sets, corners, frame)
    assert got.dtype == bool
    assert got.shape == sets.shape
    assert np.array_equal(got, want)
