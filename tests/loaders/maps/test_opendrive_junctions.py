"""ad-map's point order of junction lanes: its neighbour linking turns lanes round."""

from __future__ import annotations

import numpy as np

from loaders.maps.opendrive_junctions import JunctionLane, admap_reversed_along_s, contact


def _lane(road: str, lid: int, left: list[list[float]], right: list[list[float]]) -> JunctionLane:
    """A junction lane with border ends along ``s`` (first and last vertex each)."""
    return JunctionLane((road, 0, lid), np.array(left), np.array(right))


def test_contact_places() -> None:
    a = _lane("1", -1, [[0, 0], [10, 0]], [[0, -4], [10, -4]])
    assert contact(a, a) == "same"
    assert contact(a, _lane("2", -1, [[0, 4], [10, 4]], [[0, 0], [10, 0]])) == "lr"
    assert contact(a, _lane("2", 1, [[10, 0], [0, 0]], [[10, 4], [0, 4]])) == "ll"
    assert contact(a, _lane("2", -1, [[0, -4], [10, -4]], [[0, -8], [10, -8]])) == "rl"
    assert contact(a, _lane("2", 1, [[10, -8], [0, -8]], [[10, -4], [0, -4]])) == "rr"
    assert contact(a, _lane("2", -1, [[20, 0], [30, 0]], [[20, -4], [30, -4]])) == ""


def test_later_lane_sharing_a_reversed_border_is_turned_with_its_neighbours() -> None:
    first = _lane("1", -1, [[0, 0], [10, 0]], [[0, -4], [10, -4]])
    # road 2 runs the other way: its lane 1 shares first's left border reversed (its
    # left border), its lane 2 lies beyond (its left neighbour along s)
    inner = _lane("2", 1, [[10, 0], [0, 0]], [[10, 4], [0, 4]])
    outer = _lane("2", 2, [[10, 4], [0, 4]], [[10, 8], [0, 8]])
    # a road of another junction with the same geometry is not touched by this one
    other = _lane("3", 1, [[10, 0], [0, 0]], [[10, 4], [0, 4]])
    turned = admap_reversed_along_s([[first, inner, outer], [other]])
    assert turned == {("2", 0, 1), ("2", 0, 2)}
    np.testing.assert_array_equal(inner.right_m, first.left_m)  # now shared in one order
    assert (first.left, inner.right) == (("2", 0, 1), ("1", 0, -1))


def test_lanes_sharing_a_border_in_one_order_stay() -> None:
    first = _lane("1", -1, [[0, 0], [10, 0]], [[0, -4], [10, -4]])
    beside = _lane("2", -1, [[0, 4], [10, 4]], [[0, 0], [10, 0]])
    assert admap_reversed_along_s([[first, beside]]) == set()
    assert (first.left, beside.right) == (("2", 0, -1), ("1", 0, -1))
