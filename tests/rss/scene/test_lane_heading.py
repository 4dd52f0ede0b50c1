"""``rss.scene.roadarea.lane_heading``: ad-map's lane heading on a curve.

ad-map takes the direction between the lane's middle points 5 cm before and after the
position, a middle point being the mean of the two border points at that fraction of
each border's own length (``getLaneECEFDirection``). On a lane that runs straight and
then turns, the borders' fractions part from the centre line's: the heading there is
not the centre line's::

    left border (inner)   ──────────╮
    centre                ───────────╮   straight 10 m, then a quarter circle
    right border (outer)  ────────────╮
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rss.scene import LaneGraph, SceneMemo, prepare
from rss.scene.roadarea import lane_heading

HALF_WIDTH = 2.0
RADIUS = 10.0


def _line(offset: float) -> np.ndarray:
    """The lane's centre shifted ``offset`` to the left: 10 m along +x, then a left turn."""
    straight = np.stack([np.linspace(0.0, 10.0, 11), np.full(11, offset)], axis=1)
    a = np.linspace(0.0, math.pi / 2, 91)[1:]
    r = RADIUS - offset
    arc = np.stack([10.0 + r * np.sin(a), RADIUS - r * np.cos(a)], axis=1)
    return np.concatenate([straight, arc])


def _graph() -> LaneGraph:
    one = np.zeros(1, dtype=np.int64)
    return LaneGraph(
        ids=("0",),
        left_m=(_line(HALF_WIDTH),),
        right_m=(_line(-HALF_WIDTH),),
        centre_m=(_line(0.0),),
        direction=np.ones(1, dtype=np.int64),
        speed_limit_mps=np.full(1, 14.0),
        successors=((),),
        predecessors=((),),
        left_neighbour=one - 1,
        right_neighbour=one - 1,
        left_opposite=np.zeros(1, dtype=bool),
        right_opposite=np.zeros(1, dtype=bool),
        is_intersection=np.zeros(1, dtype=bool),
        priority=one,
        traffic_light=one - 1,
    )


def _at(line: np.ndarray, t: float) -> np.ndarray:
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line, axis=0).T))])
    return np.array(
        [np.interp(t * arc[-1], arc, line[:, 0]), np.interp(t * arc[-1], arc, line[:, 1])]
    )


def _admap_heading(t: float) -> float:
    """ad-map's rule restated with numpy (slow, obvious)."""
    left, right = _line(HALF_WIDTH), _line(-HALF_WIDTH)
    length = 0.5 * (
        np.hypot(*np.diff(left, axis=0).T).sum() + np.hypot(*np.diff(right, axis=0).T).sum()
    )
    d = 0.1 / length
    t0 = min(max(t - d / 2, 0.0), 1.0 - d)
    p0 = 0.5 * (_at(left, t0) + _at(right, t0))
    p1 = 0.5 * (_at(left, t0 + d) + _at(right, t0 + d))
    return math.atan2(p1[1] - p0[1], p1[0] - p0[0])


@pytest.mark.parametrize("t", [0.0, 0.2, 0.45, 0.5, 0.7, 0.9, 1.0])
def test_heading_is_ad_maps(t):
    prep = prepare(_graph())
    assert lane_heading(prep, SceneMemo(), 0, t) == pytest.approx(_admap_heading(t), abs=1e-9)


def test_on_the_curve_it_is_not_the_centre_lines():
    prep = prepare(_graph())
    centre = _line(0.0)
    c0, c1 = _at(centre, 0.4 - 0.002), _at(centre, 0.4 + 0.002)
    along_centre = math.atan2(c1[1] - c0[1], c1[0] - c0[0])
    # 0.4: the inner border is already on the arc, the centre line not yet
    assert abs(lane_heading(prep, SceneMemo(), 0, 0.4) - along_centre) > 0.04
