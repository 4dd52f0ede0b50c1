"""``clip_rings.surely_simple``: the compiled check that spares GEOS' ``is_valid``."""

from __future__ import annotations

import math

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.clip_rings import surely_simple

_COORD = st.floats(-5.0, 5.0, allow_nan=False)


def _geos_valid(ring: list[float]) -> bool:
    return bool(shapely.is_valid(shapely.polygons(np.reshape(ring, (-1, 2)))))


@settings(max_examples=400, deadline=None)
@given(st.lists(st.tuples(_COORD, _COORD), min_size=1, max_size=9))
def test_random_rings_never_simple_where_geos_says_invalid(pts: list[tuple[float, float]]) -> None:
    """Random (mostly self-crossing) rings: ``True`` only where GEOS finds the ring valid."""
    ring = [v for p in pts for v in p]
    if surely_simple(ring):
        assert _geos_valid(ring)


@settings(max_examples=200, deadline=None)
@given(
    st.integers(3, 40),
    st.lists(st.floats(0.3, 6.0), min_size=40, max_size=40),
    st.lists(st.integers(0, 3), min_size=40, max_size=40),
)
def test_star_rings_simple_and_grid_contacts(n: int, rad: list[float], snap: list[int]) -> None:
    """Star-shaped rings are simple; with vertices snapped to a coarse grid (touching edges,
    repeated and collinear vertices) ``True`` still implies GEOS validity.
    """
    ang = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    r = np.asarray(rad[:n])
    ring = np.stack([r * np.cos(ang), r * np.sin(ang)], axis=1)
    assert surely_simple(ring.ravel().tolist())
    assert _geos_valid(ring.ravel().tolist())
    snapped = np.where(np.asarray(snap[:n])[:, None] == 0, np.round(ring), ring)
    if surely_simple(snapped.ravel().tolist()):
        assert _geos_valid(snapped.ravel().tolist())


def test_degenerate_rings_are_left_to_geos() -> None:
    """Bow tie, vertex contact, fold-back, too few points and NaN all answer ``False``."""
    bow_tie = [0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0]
    touching = [0.0, 0.0, 2.0, 0.0, 1.0, 1.0, 2.0, 2.0, 0.0, 2.0, 1.0, 1.0]
    fold = [0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 1.0, 1.0]
    for ring in (bow_tie, touching, fold, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]):
        assert not surely_simple(ring)
        assert not _geos_valid(ring)
    assert not surely_simple([0.0, 0.0, 1.0, 0.0, math.nan, 1.0])
    assert not surely_simple([0.0, 0.0, 1.0, 0.0, math.inf, 1.0])
    square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0]  # closing vertex repeated
    assert surely_simple(square)
