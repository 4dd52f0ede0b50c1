"""``robust_difference``: the plain overlay where it works, snap-rounding where GEOS fails."""

from __future__ import annotations

import numpy as np
import shapely

from reachsets.patches import robust_difference


def _pairs() -> tuple[np.ndarray, np.ndarray]:
    a = np.array([shapely.box(0, 0, 2, 2), shapely.box(5, 5, 6, 6)], dtype=object)
    b = np.array([shapely.box(1, 1, 3, 3), shapely.box(0, 0, 1, 1)], dtype=object)
    return a, b


def test_equals_the_plain_difference():
    a, b = _pairs()
    got = robust_difference(a, b)
    assert all(shapely.equals(g, e) for g, e in zip(got, shapely.difference(a, b), strict=True))
    assert shapely.area(got[0]) == 3.0


def test_pairs_that_fail_are_snap_rounded(monkeypatch):
    a, b = _pairs()
    real = shapely.difference
    calls: list[object] = []

    def flaky(x, y, **kwargs):
        calls.append(kwargs.get("grid_size"))
        if kwargs.get("grid_size") is None and (isinstance(x, np.ndarray) or x is a[0]):
            raise shapely.errors.GEOSException("Unable to determine overlay result geometry")
        return real(x, y, **kwargs)

    monkeypatch.setattr(shapely, "difference", flaky)
    got = robust_difference(a, b)
    assert calls == [None, None, 1e-6, None]  # array, pair 0, pair 0 snapped, pair 1
    assert shapely.area(got[0]) == 3.0
    assert shapely.equals(got[1], a[1])
