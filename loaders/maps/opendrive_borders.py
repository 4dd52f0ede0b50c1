"""Lane borders of one OpenDRIVE lane section, sampled where ad-map samples them.

Every lane's two borders are evaluated at the section start, at the road's stations
inside the section (:meth:`ReferenceLine.stations`) and at the section end (a hair before
it when another section follows, so the section's own polynomials apply). Each lane then
halves its intervals on its own (:func:`bisect_stations`, either border at least
``MAX_SAMPLING_ERROR_M`` from its chord's middle) and finally drops, per border, vertices
closer than 1 mm (in x and y) to the vertex kept before them and vertices where the border
turns back (loops of inner borders in tight curves), the last vertex always kept::

      t ▲   left lanes  (id > 0): right border at t_k,   left border at t_k + w_k
        │
    ────┼──────────▶ s  shifted reference line (laneOffset)
        │
            right lanes (id < 0): left border at -t_k,  right border at -t_k - w_k

with ``t_k`` the summed widths of the lanes between the lane and the reference line.
Borders are ordered along ``s``, ``left`` / ``right`` as seen along ``s``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.maps.opendrive_refline import bisect_stations

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from collections.abc import Collection

    from numpy.typing import NDArray

    from loaders.maps.opendrive_refline import ReferenceLine

    _F = NDArray[np.float64]

__all__ = ["SectionLane", "normalise_border", "section_lanes"]

#: ad-map's point equality (each coordinate closer than this, m).
_SAME_POINT_M = 1e-3
#: A section that does not end the road is evaluated this far before its end (m).
_END_BACKOFF_M = 1e-12


@dataclass(frozen=True, slots=True)
class SectionLane:
    """One lane of a lane section, borders along ``s``.

    Attributes:
        lane_id: OpenDRIVE lane id (``> 0`` left of the reference line).
        element: The ``<lane>`` element.
        left_m: Left border seen along ``s``, ``(K, 2)`` metres.
        right_m: Right border seen along ``s``, ``(M, 2)`` metres.
        centre_m: Middle of both borders at the lane's stations (before the vertex
            clean-up), ``(C, 2)`` metres.
    """

    lane_id: int
    element: ET.Element
    left_m: _F
    right_m: _F
    centre_m: _F


def normalise_border(points_m: _F) -> _F:
    """Drop vertices within 1 mm of the previous kept one, and vertices turning back.

    Args:
        points_m: Border vertices, ``(K, 2)`` metres.

    Returns:
        The kept vertices, ``(K', 2)``; the first and the last vertex are always kept.
    """
    if len(points_m) <= 2:  # noqa: PLR2004 - nothing to drop between two end points
        return points_m
    steps = np.diff(points_m, axis=0)
    same = np.all(np.abs(steps) < _SAME_POINT_M, axis=1)
    back = np.sum(steps[1:] * steps[:-1], axis=1) < 0.0
    if not same[:-1].any() and not back[:-1].any():
        return points_m
    kept = [points_m[0]]
    heading: _F | None = None
    for i in range(1, len(points_m) - 1):
        step = points_m[i] - kept[-1]
        if np.all(np.abs(step) < _SAME_POINT_M):
            continue
        if heading is not None and float(step @ heading) < 0.0:
            continue
        heading = step
        kept.append(points_m[i])
    kept.append(points_m[-1])
    return np.array(kept)


def _side(section: ET.Element, side: str) -> list[ET.Element]:
    lanes = section.findall(f"{side}/lane")
    return sorted(lanes, key=lambda e: abs(int(e.get("id", "0"))))


def _width_records(lanes: list[ET.Element]) -> tuple[_F, _F]:
    """``width`` records of lanes, padded to a common count.

    Returns:
        Starts ``(L, R)`` (``inf`` beyond a lane's records) and ``a b c d`` ``(L, R, 4)``;
        a lane without records has width 0.
    """
    recs = [lane.findall("width") for lane in lanes]
    size = max(1, *(len(r) for r in recs))
    starts = np.full((len(lanes), size), np.inf)
    coeffs = np.zeros((len(lanes), size, 4))
    for i, rows in enumerate(recs):
        if not rows:
            starts[i, 0] = 0.0
        for j, r in enumerate(sorted(rows, key=lambda e: float(e.get("sOffset", "0")))):
            starts[i, j] = float(r.get("sOffset", "0"))
            coeffs[i, j] = [float(r.get(k, "0")) for k in "abcd"]
    return starts, coeffs


def section_lanes(  # noqa: PLR0917 - one section's pieces
    ref: ReferenceLine,
    stations_m: _F,
    section: ET.Element,
    s0_m: float,
    s1_m: float,
    types: Collection[str],
) -> list[SectionLane]:
    """Borders of the lanes of one section whose ``type`` is in ``types``.

    The widths of all lanes add up; the other lanes are not sampled (each lane's vertices
    depend only on its own borders).

    Args:
        ref: The road's reference line.
        stations_m: The road's stations, ``(S,)`` ascending metres.
        section: The ``<laneSection>`` element.
        s0_m: Section start along the road (m).
        s1_m: Section end: the next section's start or the road length (m).
        types: Lane types to sample (``driving``, ``sidewalk``, ...).

    Returns:
        The lanes, left ones (id ascending by magnitude) first.
    """
    if abs(s1_m - ref.length_m) > _SAME_POINT_M:
        s1_m -= _END_BACKOFF_M
    inside = stations_m[(stations_m > s0_m) & (stations_m < s1_m)]
    base = np.concatenate([[s0_m], inside, [s1_m]])
    lanes = [(e, 1.0) for e in _side(section, "left")] + [
        (e, -1.0) for e in _side(section, "right")
    ]
    if not lanes:
        return []
    width_starts, width_coeffs = _width_records([e for e, _ in lanes])
    signs = np.array([sign for _, sign in lanes])
    kept = [k for k, (e, _) in enumerate(lanes) if e.get("type", "") in types]
    if not kept:
        return []

    def points(s: _F) -> _F:
        centre, normal, _ = ref.frame(s)
        ds = (s - s0_m)[:, None, None]
        rec = np.maximum(np.sum(width_starts[None] <= ds, axis=2) - 1, 0)  # (N, L)
        c = np.take_along_axis(width_coeffs[None], rec[..., None, None], axis=2)[:, :, 0]
        d = ds[..., 0] - np.take_along_axis(width_starts[None], rec[..., None], axis=2)[..., 0]
        w = c[..., 0] + d * (c[..., 1] + d * (c[..., 2] + d * c[..., 3]))  # (N, L)
        outer = np.empty_like(w)
        for sign in (1.0, -1.0):
            cols = signs == sign
            outer[:, cols] = sign * np.cumsum(w[:, cols], axis=1)
        inner = outer - signs * w
        # (N, L, 2 borders: left then right, 3)
        left_t = np.where(signs > 0, outer, inner)
        right_t = np.where(signs > 0, inner, outer)
        t = np.stack([left_t[:, kept], right_t[:, kept]], axis=2)
        xy = centre[:, None, None, :2] + t[..., None] * normal[:, None, None, :]
        z = np.broadcast_to(centre[:, None, None, 2:], (*t.shape, 1))
        out: _F = np.concatenate([xy, z], axis=3)
        return out

    extra, owner, extra_points, at_base = bisect_stations(base, points, strict=False)
    result = []
    for k, lane in enumerate(kept):
        elem = lanes[lane][0]
        mine = owner == k
        order = np.argsort(np.concatenate([base, extra[mine]]), kind="stable")
        at = np.concatenate([at_base[:, k], extra_points[mine]])[order]
        left, right = at[:, 0, :2], at[:, 1, :2]
        result.append(
            SectionLane(
                lane_id=int(elem.get("id", "0")),
                element=elem,
                left_m=normalise_border(left),
                right_m=normalise_border(right),
                centre_m=(left + right) / 2,
            )
        )
    return result
