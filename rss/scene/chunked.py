"""Map matching of several frames in one call, split back per frame.

``match_boxes`` treats every box on its own (tree query, clipping and projection per
(box, lane) pair), so the boxes of ``F`` frames can be matched at once and each frame's
pairs cut out afterwards::

    frame 0 boxes | frame 1 boxes | ...   ──match_boxes──▶  pairs sorted by box
    box offsets  b0=0      b1            ──split_matches──▶ one Matches per frame

The per-frame ``Matches`` hold the same values as ``match_boxes`` on that frame's boxes
alone (box indices renumbered from 0).
"""

from __future__ import annotations

import dataclasses
import itertools
from typing import TYPE_CHECKING

import numpy as np

from rss.scene.match_records import BoxArrays, Matches
from rss.scene.matching import match_boxes

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.scene.prepared import PreparedGraph

__all__ = ["match_frames", "split_matches"]


def split_matches(matches: Matches, box_starts: Sequence[int]) -> list[Matches]:
    """Cut the matching of concatenated boxes into one ``Matches`` per frame.

    Args:
        matches: Matching of ``N`` boxes of ``F`` frames, frame after frame.
        box_starts: ``F + 1`` offsets: the boxes of frame ``f`` are
            ``box_starts[f]:box_starts[f + 1]``.

    Returns:
        ``F`` matchings with box indices counted from each frame's first box.
    """
    out: list[Matches] = []
    for b0, b1 in itertools.pairwise(box_starts):
        p0, p1 = matches.starts[b0], matches.starts[b1]
        out.append(
            Matches(
                box=matches.box[p0:p1] - b0,
                lane=matches.lane[p0:p1],
                lon_min=matches.lon_min[p0:p1],
                lon_max=matches.lon_max[p0:p1],
                lat_min=matches.lat_min[p0:p1],
                lat_max=matches.lat_max[p0:p1],
                anchor=matches.anchor[b0:b1],
                anchor_s=matches.anchor_s[b0:b1],
                anchor_heading_rad=matches.anchor_heading_rad[b0:b1],
                heading_rad=matches.heading_rad[p0:p1],
                starts=[p - p0 for p in matches.starts[b0 : b1 + 1]],
            )
        )
    return out


def match_frames(prep: PreparedGraph, boxes: Sequence[BoxArrays]) -> list[Matches]:
    """Match the boxes of ``F`` frames in one ``match_boxes`` call.

    Args:
        prep: The prepared lane graph.
        boxes: Per frame, its boxes (``(N_f,)`` arrays each).

    Returns:
        Per frame, the matching of its boxes (as ``match_boxes`` on them alone).
    """
    if not boxes:
        return []
    names = [f.name for f in dataclasses.fields(BoxArrays)]
    joined = BoxArrays(*(np.concatenate([getattr(b, name) for b in boxes]) for name in names))
    box_starts = np.concatenate([[0], np.cumsum([len(b.x_m) for b in boxes])]).tolist()
    return split_matches(match_boxes(prep, joined), box_starts)
