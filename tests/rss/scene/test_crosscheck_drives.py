"""Drive-level differential test against ad-rss map integration 5.0 on CARLA Town01.

A fixed subset of the seeded random drives of ``town01_drives`` (the ego on a lane route
among 1-6 vehicles, 10 Hz), each cut after the frames that matter, against the
reference's per-frame verdicts with its memory across frames (``adrss_drive_oracle.py``,
one ``RssCheck`` per drive) and ours (``rss.evaluate_frames`` over each drive, memory
across frames), in both modes. The subset holds every frame the reference called
dangerous and we safe on the 20-drive runs of docs/rss_scene.md (drive-level
cross-check), plus frames of both documented ad-rss defects; the whole 20-drive runs are
``tools/drive_crosscheck.py``. Needs ``RSS_MAP_ORACLE_PYTHON`` as
``test_crosscheck_adrss_map.py`` (skipped otherwise). The oracle's answers are cached in
``out/`` (asked again when the drives change): asking costs about 1.5 minutes uncached on
the shared 2-core VM (two oracle processes), the comparison about 2 s.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import PreparedGraph, SceneMemo, prepare
from tests.rss.scene.drive_crosscheck import (
    compare_drives,
    oracle_drives,
    our_drive,
)
from tests.rss.scene.town01_drives import drives as make_drives
from workbench.engines.rss.adapter import lane_graph_from_map

#: ``(seed, min_gap_m, drive, frames)``: drive ``drive`` of ``drives(prep, seed, n,
#: min_gap_m)``, its first ``frames`` frames. Seed 1 (gap 6 m): 4 and 7 hold the "beside on
#: a curve" frames (4:1, 7:12-16; 7:11-16 had no constellation before the beside rule), 6
#: the ego on overlapping junction lanes (6:22), 1 the opposite "beside" case (1:4-6), 16
#: ad-rss' swapped route headings (16:0-20), 17 its turn directions (17:3-6). Seed 2 (gap
#: 0): drive 12 "beside on a curve" from frame 0, 0 and 4 the default mode's documented
#: misses (0:48, 4:8), 7 and 18 the ego on overlapping junction lanes (further route roots:
#: 7:33-36, 18:25-26; 18:27 the junction lanes ad-map links by their end points), 14 the
#: routes of two roots merged (14:18-20).
SUBSET = (
    (1, 6.0, 4, 6),
    (1, 6.0, 7, 18),
    (1, 6.0, 6, 24),
    (1, 6.0, 1, 8),
    (1, 6.0, 16, 8),
    (1, 6.0, 17, 8),
    (2, 0.0, 12, 8),
    (2, 0.0, 0, 50),
    (2, 0.0, 4, 10),
    (2, 0.0, 7, 37),
    (2, 0.0, 18, 28),
    (2, 0.0, 14, 21),
)
#: The default mode's documented miss (docs/rss_scene.md, "Not done"), as ``(seed, drive,
#: frame)``: a frame ad-rss calls dangerous only by ad-map's turn direction, which the
#: compatibility mode reproduces. The swapped route headings (seed-2 0:48) and "beside on
#: a curve" are no longer misses: the default mode joins ad-rss' reading to its own.
DEFAULT_KNOWN = {
    (2, 4, 8): "ad-map's turn direction (IntersectionObjectHasPriority 9.96 m, ours 16.13 m)",
}
CACHE = Path(__file__).resolve().parents[3] / "out" / "adrss_drive_oracle_subset.json"
SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
COMPAT_SETTINGS = SceneSettings(
    restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
)


def subset_drives(prep: PreparedGraph) -> list[dict[str, Any]]:
    """The drives of :data:`SUBSET`, cut after their frames."""
    out = []
    for seed, gap, index, frames in SUBSET:
        drive = make_drives(prep, seed, index + 1, gap)[index]
        out.append({"frames": drive["frames"][:frames]})
    return out


Answers = tuple[PreparedGraph, list[dict[str, Any]], list[list[dict[str, Any]]]]


@pytest.fixture(scope="module")
def town01_drives(external_dir: Path) -> Answers:
    """The prepared Town01 graph, the seeded drives and the oracle's frames (cached)."""
    oracle_python = os.environ.get("RSS_MAP_ORACLE_PYTHON")
    if not oracle_python:
        pytest.skip(
            "RSS_MAP_ORACLE_PYTHON (ad-rss-map-integration 5.0 interpreter) not set; "
            "`make test` runs this module with its side venv (make oracle-adrss-map)"
        )
    town = external_dir / "maps" / "Town01.xodr"
    prep = prepare(lane_graph_from_map(read_opendrive(town)))
    drives = subset_drives(prep)
    return prep, drives, oracle_drives(drives, oracle_python, town, CACHE)


def test_drives_compat_mode_agrees(town01_drives: Answers) -> None:
    """``[scene] reproduce_adrss_5_0_defects``: every compared frame agrees.

    As on the whole 20-drive runs of both seeds (996 / 996 and 995 / 995,
    docs/rss_scene.md); on this subset 224 frames (2 where the reference's check fails
    are not compared).
    """
    prep, drives, theirs = town01_drives
    memo = SceneMemo()
    mine = [our_drive(prep, d, COMPAT_SETTINGS, memo) for d in drives]
    stats = compare_drives(mine, theirs)
    sys.stderr.write(f"drive cross-check, compat mode: {stats.summary()}\n")
    assert stats.frames + len(stats.failed) == sum(frames for *_, frames in SUBSET)
    assert stats.missed == []
    assert stats.extra == []
    assert stats.agree == stats.frames


def test_drives_default_mode_misses_no_danger(town01_drives: Answers) -> None:
    """Default mode: a frame the reference calls dangerous is dangerous for us too, but for
    the one documented case of :data:`DEFAULT_KNOWN`.

    Measured on the subset: 208 of 224 compared frames agree, 1 dangerous only for the
    reference (:data:`DEFAULT_KNOWN`; before issue 27's worst case of both readings 16,
    the other 15 "beside on a curve" and the swapped headings), 15 only for us (ad-rss'
    swapped route headings and turn directions).
    """
    prep, drives, theirs = town01_drives
    memo = SceneMemo()
    mine = [our_drive(prep, d, SETTINGS, memo) for d in drives]
    stats = compare_drives(mine, theirs)
    sys.stderr.write(f"drive cross-check, default mode: {stats.summary()}\n")
    unexplained = [
        (SUBSET[d][0], SUBSET[d][2], k)
        for d, k in stats.missed
        if (SUBSET[d][0], SUBSET[d][2], k) not in DEFAULT_KNOWN
    ]
    assert unexplained == []
    assert stats.agree >= 208  # measured
