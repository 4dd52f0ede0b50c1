"""The lane borders of a map with their nearest-point index (built once by ``prepare``).

Line ``l`` is the left border of lane ``l``, line ``L + l`` its right border, each with
every given vertex (ad-map measures and cuts on its own vertices). A nearest-point query
tries only the segments that can be nearest (``rss.scene.segment_cells``) and applies
ad-map's tie rule in ad-map's point order (``rss.scene.admap_nearest``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.scene.admap_nearest import nearest_in_windows, segment_window, segments
from rss.scene.segment_cells import SegmentCells, narrowed, segment_cells

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.scene.polylines import Polylines

__all__ = ["BorderIndex", "border_index"]


@dataclass(frozen=True)
class BorderIndex:
    """The borders as flat arrays with what their nearest-point queries need.

    Attributes:
        lines: The ``2 L`` borders (left borders first, then right borders).
        segments: ``admap_nearest.segments`` of ``lines`` (per vertex).
        cells: Candidate segments per grid cell (``segment_cells``).
        backwards: ``(2 L,)`` per line: ad-map's point order runs against ours.
    """

    lines: Polylines
    segments: FloatArray
    cells: SegmentCells
    backwards: BoolArray

    def nearest(
        self,
        which: IntArray,
        points: FloatArray,
        near_m: FloatArray | None = None,
        reach_m: float = 0.0,
    ) -> tuple[FloatArray, FloatArray]:
        """Nearest points of ``points`` ``(Q, 2)`` on the lines ``which``: arc lengths, points.

        ad-map's tie rule in ad-map's point order (``admap_nearest.nearest_in_windows``);
        only the segments within ``reach_m`` of arc length ``near_m`` when given, and of
        those only the ones that can be nearest (``cells``; same result).
        """
        first, last = segment_window(self.lines, which, near_m, reach_m)
        first, last = narrowed(self.cells, which, points, first, last)
        return nearest_in_windows(self.segments, points, self.backwards[which], first, last)


def border_index(lines: Polylines, backwards: BoolArray) -> BorderIndex:
    """Index the border ``lines`` (``backwards``: ad-map's order runs against ours)."""
    return BorderIndex(lines, segments(lines), segment_cells(lines), backwards)
