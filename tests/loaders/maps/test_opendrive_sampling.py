# ruff: noqa: E501
"""Where the OpenDRIVE reader puts border vertices (ad-map's sampling rule) on synthetic roads.

Vertices are checked against the analytic curves (arc, clothoid, width polynomials) and the
spacing rule against a slow scalar restatement of it.
"""

import itertools
import math
from collections.abc import Callable

import numpy as np
import pytest

from loaders.maps.opendrive import read_opendrive
from loaders.maps.opendrive_borders import normalise_border
from loaders.maps.opendrive_refline import MAX_SAMPLING_ERROR_M, ReferenceLine
from loaders.maps.xmlsource import read_xml_root

E = MAX_SAMPLING_ERROR_M
Curve = Callable[[float], np.ndarray]


def _xodr(geometry: str, length: float, width: str, offset: str = "") -> bytes:
    return f"""<?xml version='1.0'?><OpenDRIVE><header/>
  <road id="1" length="{length}" junction="-1"><link/>
    <planView>{geometry}</planView>
    <lanes>{offset}
      <laneSection s="0">
        <center><lane id="0" type="none"/></center>
        <right><lane id="-1" type="driving">{width}</lane></right>
      </laneSection>
    </lanes>
  </road></OpenDRIVE>""".encode()


def _bisect(a: float, b: float, curve: Curve, *, strict: bool) -> list[float]:
    """Scalar restatement of the halving rule: stations inserted into ``[a, b]``."""
    if b - a < E:
        return []
    m = 0.5 * (a + b)
    err = float(np.max(np.hypot(*(curve(m) - 0.5 * (curve(a) + curve(b))).T)))
    if (err > E) if strict else (err >= E):
        return [*_bisect(a, m, curve, strict=strict), m, *_bisect(m, b, curve, strict=strict)]
    return []


def _expected(stations: list[float], curve: Curve, *, strict: bool) -> list[float]:
    out = [stations[0]]
    for a, b in itertools.pairwise(stations):
        out += [*_bisect(a, b, curve, strict=strict), b]
    return out


R, L_ARC = 20.0, 30.0
ARC = f'<geometry s="0" x="0" y="0" hdg="0" length="{L_ARC}"><arc curvature="{1 / R}"/></geometry>'
#: A lane opening from 0 to 3.5 m over the first 10 m (cubic), then 3.5 m wide.
WIDTH = (
    '<width sOffset="0" a="0" b="0" c="0.105" d="-0.007"/>'
    '<width sOffset="10" a="3.5" b="0" c="0" d="0"/>'
)


def _width(s: float | np.ndarray) -> np.ndarray:
    s = np.asarray(s, dtype=float)
    return np.where(s < 10, 0.105 * s**2 - 0.007 * s**3, 3.5)


def _arc_point(s: float, t: float) -> np.ndarray:
    """Point at station ``s``, lateral ``t`` (left positive) of the left-turning arc."""
    phi = s / R
    rho = R - t
    return np.array([rho * math.sin(phi), R - rho * math.cos(phi)])


def _arc_seeds() -> list[float]:
    step = 2 * R * math.acos(1 - E / R)  # chord whose sagitta is E
    pieces = int(L_ARC / step)  # rounded down: the pieces are a little longer
    return list(np.linspace(0, L_ARC, pieces + 1))


def test_arc_stations_follow_the_chord_rule():
    road = read_xml_root(_xodr(ARC, L_ARC, WIDTH), "arc")[0].find("road")
    assert road is not None
    stations = ReferenceLine(road).stations()
    seeds = _arc_seeds()
    expected = _expected(seeds, lambda s: _arc_point(s, 0.0)[None], strict=True)
    assert len(expected) == 2 * len(seeds) - 1  # pieces of 3 m: sagitta 5.6 cm, halved once
    np.testing.assert_allclose(stations, expected, atol=1e-12)


def test_arc_border_vertices_on_the_curve_and_refined_per_lane():
    lane = read_opendrive(_xodr(ARC, L_ARC, WIDTH)).lanes["1_0_-1"]
    # the lane's left border is the reference arc, its right border lies w(s) outside
    phi_l = np.arctan2(lane.left_m[:, 0], R - lane.left_m[:, 1])
    np.testing.assert_allclose(np.hypot(lane.left_m[:, 0], R - lane.left_m[:, 1]), R, atol=1e-9)
    phi_r = np.arctan2(lane.right_m[:, 0], R - lane.right_m[:, 1])
    rho_r = np.hypot(lane.right_m[:, 0], R - lane.right_m[:, 1])
    np.testing.assert_allclose(rho_r, R + _width(phi_r * R), atol=1e-9)
    # both borders share the lane's stations; the opening needs more than the arc
    np.testing.assert_allclose(phi_l, phi_r, atol=1e-12)
    base = _expected(_arc_seeds(), lambda s: _arc_point(s, 0.0)[None], strict=True)

    def borders(s: float) -> np.ndarray:
        return np.stack([_arc_point(s, 0.0), _arc_point(s, -float(_width(s)))])

    expected = _expected(base, borders, strict=False)
    assert len(expected) > len(base)
    np.testing.assert_allclose(phi_l * R, expected, atol=1e-9)
    # every chord ends within the tolerance of the curve at its middle
    for s0, s1 in itertools.pairwise(expected):
        chord_mid = 0.5 * (borders(s0) + borders(s1))
        assert np.max(np.hypot(*(borders(0.5 * (s0 + s1)) - chord_mid).T)) < E


def test_line_with_a_width_polynomial_and_lane_offset():
    line = '<geometry s="0" x="5" y="-2" hdg="0" length="60"><line/></geometry>'
    width = '<width sOffset="0" a="3" b="0" c="0.004" d="-0.00005"/>'
    offset = '<laneOffset s="0" a="0.5" b="0" c="0" d="0"/>'
    lane = read_opendrive(_xodr(line, 60.0, width, offset)).lanes["1_0_-1"]
    s = lane.right_m[:, 0] - 5.0
    # the straight left border shares the stations the curved right one needs
    np.testing.assert_allclose(
        lane.left_m, np.stack([5.0 + s, np.full_like(s, -1.5)], 1), atol=1e-12
    )
    w = 3 + 0.004 * s**2 - 0.00005 * s**3
    np.testing.assert_allclose(lane.right_m[:, 1], -1.5 - w, atol=1e-12)

    def borders(x: float) -> np.ndarray:
        return np.array([[5.0 + x, -1.5], [5.0 + x, -1.5 - (3 + 0.004 * x**2 - 0.00005 * x**3)]])

    np.testing.assert_allclose(s, _expected([0.0, 60.0], borders, strict=False), atol=1e-9)


def test_spiral_vertices_on_the_clothoid():
    k1, length = 0.08, 40.0
    geo = f'<geometry s="0" x="1" y="2" hdg="0.3" length="{length}"><spiral curvStart="0" curvEnd="{k1}"/></geometry>'
    lane = read_opendrive(
        _xodr(geo, length, '<width sOffset="0" a="3.5" b="0" c="0" d="0"/>')
    ).lanes["1_0_-1"]
    fine = np.linspace(0.0, length, 400_001)
    heading = 0.3 + k1 * fine**2 / (2 * length)
    step = np.diff(fine)
    x = 1 + np.concatenate(
        [[0], np.cumsum((np.cos(heading[1:]) + np.cos(heading[:-1])) / 2 * step)]
    )
    y = 2 + np.concatenate(
        [[0], np.cumsum((np.sin(heading[1:]) + np.sin(heading[:-1])) / 2 * step)]
    )
    # the left border is the reference line: every vertex lies on the clothoid
    gaps = [np.min(np.hypot(x - px, y - py)) for px, py in lane.left_m]
    assert max(gaps) < 1e-6
    assert len(lane.left_m) > 2  # the curve needs stations in between (centre-line halving)


def test_section_ends_use_their_own_polynomials():
    """A lane section that does not end the road is sampled a hair before the next one."""
    line = '<geometry s="0" x="0" y="0" hdg="0" length="20"><line/></geometry>'
    doc = _xodr(line, 20.0, '<width sOffset="0" a="3" b="0" c="0" d="0"/>').decode()
    second = '<laneSection s="10"><center><lane id="0" type="none"/></center><right><lane id="-1" type="driving"><width sOffset="0" a="5" b="0" c="0" d="0"/></lane></right></laneSection>'
    doc = doc.replace("</lanes>", second + "</lanes>")
    m = read_opendrive(doc.encode())
    np.testing.assert_allclose(m.lanes["1_0_-1"].right_m, [[0, -3], [10, -3]], atol=1e-9)
    np.testing.assert_allclose(m.lanes["1_1_-1"].right_m, [[10, -5], [20, -5]], atol=1e-9)


@pytest.mark.parametrize(
    ("points", "kept"),
    [
        ([[0, 0], [1, 0], [1.0005, 0.0002], [2, 0]], [0, 1, 3]),  # within 1 mm of the last kept
        ([[0, 0], [1, 0], [0.5, 0.1], [2, 0]], [0, 1, 3]),  # turns back
        ([[0, 0], [1, 0], [1, 0]], [0, 1, 2]),  # the last vertex always stays
    ],
)
def test_normalise_border(points, kept):
    pts = np.array(points, dtype=float)
    np.testing.assert_array_equal(normalise_border(pts), pts[kept])
