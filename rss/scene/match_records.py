"""The records of map matching: boxes in (:class:`BoxArrays`), regions out (:class:`Matches`).

Box ``b`` of a frame's :class:`BoxArrays` (box 0 the ego, box ``i + 1`` object ``i``)
occupies, in every lane it overlaps, a parametric region ``[lon_min, lon_max]`` along the
lane's point order by ``[lat_min, lat_max]`` across it (0 = left border); its anchor is the
lane it is on. ``rss.scene.matching`` computes them as ad-map does.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely

from rss.scene.admap_nearest import columns

if TYPE_CHECKING:
    from rss.arrays import FloatArray, IntArray

__all__ = ["BoxArrays", "MatchRow", "Matches", "box_polygons"]


@dataclass(frozen=True)
class BoxArrays:
    """Oriented boxes, all ``(N,)`` (map frame, ENU).

    Attributes:
        x_m: Centre x.
        y_m: Centre y.
        yaw_rad: Heading, counter-clockwise from +x.
        length_m: Length along the heading.
        width_m: Width.
    """

    x_m: FloatArray
    y_m: FloatArray
    yaw_rad: FloatArray
    length_m: FloatArray
    width_m: FloatArray


class MatchRow(NamedTuple):
    """One (box, lane) pair of :class:`Matches` as Python scalars (see its attributes)."""

    lane: int
    lon_min: float
    lon_max: float
    lat_min: float
    lat_max: float
    heading_rad: float


@dataclass(frozen=True)
class Matches:
    """Occupied regions of ``N`` boxes as ``P`` (box, lane) pairs.

    Attributes:
        box: ``(P,)`` box index.
        lane: ``(P,)`` lane index.
        lon_min: ``(P,)`` parametric start along the lane's point order, in [0, 1].
        lon_max: ``(P,)`` parametric end.
        lat_min: ``(P,)`` parametric left edge (0 = left border).
        lat_max: ``(P,)`` parametric right edge.
        anchor: ``(N,)`` the lane the box is on: among the touched lanes, the one nearest
            to its centre and best aligned with its heading; -1 when it touches no lane.
        anchor_s: ``(N,)`` parametric position of the centre on the anchor lane.
        anchor_heading_rad: ``(N,)`` heading of the anchor lane's point order there.
        heading_rad: ``(P,)`` heading of each pair's lane point order at the box centre.
        starts: ``N + 1`` offsets: the pairs of box ``b`` are ``starts[b]:starts[b + 1]``.
    """

    box: IntArray
    lane: IntArray
    lon_min: FloatArray
    lon_max: FloatArray
    lat_min: FloatArray
    lat_max: FloatArray
    anchor: IntArray
    anchor_s: FloatArray
    anchor_heading_rad: FloatArray
    heading_rad: FloatArray
    starts: list[int]

    def rows(self, box: int) -> range:
        """Pair indices of ``box`` (pairs are sorted by box)."""
        return range(self.starts[box], self.starts[box + 1])

    @functools.cached_property
    def _by_box(self) -> list[list[MatchRow]]:
        rows = list(
            map(
                MatchRow,
                self.lane.tolist(),
                self.lon_min.tolist(),
                self.lon_max.tolist(),
                self.lat_min.tolist(),
                self.lat_max.tolist(),
                self.heading_rad.tolist(),
            )
        )
        return [rows[a:b] for a, b in zip(self.starts[:-1], self.starts[1:], strict=True)]

    @functools.cached_property
    def anchors(self) -> list[int]:
        """``anchor`` as a Python list."""
        out: list[int] = self.anchor.tolist()
        return out

    def regions(self, box: int) -> list[MatchRow]:
        """The pairs of ``box`` as Python scalars, in pair order (do not modify)."""
        return self._by_box[box]

    def lanes_of(self, box: int) -> IntArray:
        """Lanes touched by ``box``."""
        r = self.rows(box)
        out: IntArray = self.lane[r.start : r.stop]
        return out


def box_polygons(boxes: BoxArrays) -> np.ndarray:
    """``(N,)`` polygons of the boxes."""
    c, s = np.cos(boxes.yaw_rad), np.sin(boxes.yaw_rad)
    hl, hw = boxes.length_m / 2.0, boxes.width_m / 2.0
    corners_l = np.array([1.0, 1.0, -1.0, -1.0])[None, :] * hl[:, None]
    corners_w = np.array([1.0, -1.0, -1.0, 1.0])[None, :] * hw[:, None]
    xs = boxes.x_m[:, None] + corners_l * c[:, None] - corners_w * s[:, None]
    ys = boxes.y_m[:, None] + corners_l * s[:, None] + corners_w * c[:, None]
    out: np.ndarray = shapely.polygons(columns(xs, ys))
    return out
