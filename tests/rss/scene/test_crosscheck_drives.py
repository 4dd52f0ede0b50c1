"""Drive-level differential test against ad-rss map integration 5.0 on CARLA Town01.

Twenty seeded random drives of ``town01_drives`` (the ego on a lane route among 1-6
vehicles, 50 frames at 10 Hz each), the reference's per-frame verdicts with its memory
across frames (``adrss_drive_oracle.py``, one ``RssCheck`` per drive) against ours
(``rss.evaluate_frames`` over each drive, memory across frames), in both modes. Needs
``RSS_MAP_ORACLE_PYTHON`` as ``test_crosscheck_adrss_map.py`` (skipped otherwise). The
oracle's answers are cached in ``out/`` beside those of ``tools/drive_crosscheck.py``
(asked again when the drives change): asking costs 14 minutes (measured on the shared
2-core VM under a load of 5, two oracle processes; ≈ 0.1 s per object and frame), the
comparison of both modes ≈ 10 s.
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
    beside_on_curve,
    compare_drives,
    oracle_drives,
    our_drive,
)
from tests.rss.scene.town01_drives import drives as make_drives
from workbench.engines.rss.adapter import lane_graph_from_map

N_DRIVES = 20
SEED = 1
CACHE = Path(__file__).resolve().parents[3] / "out" / f"adrss_drive_oracle_s{SEED}_n{N_DRIVES}.json"
SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
COMPAT_SETTINGS = SceneSettings(
    restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
)

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
    drives = make_drives(prep, SEED, N_DRIVES)
    return prep, drives, oracle_drives(drives, oracle_python, town, CACHE)


def test_drives_compat_mode_agrees(town01_drives: Answers) -> None:
    """``[scene] reproduce_adrss_5_0_defects``: the frames agree but for two known cases.

    Measured (docs/rss_scene.md, drive-level cross-check): 986 of 996 frames (98.996 %;
    4 frames where the reference's own check fails are not compared). Left: 9 frames of
    the "beside on a curve" lateral speeds (not reproduced by the mode yet) and one type
    difference (drive 6 frame 22).
    """
    prep, drives, theirs = town01_drives
    memo = SceneMemo()
    mine = [our_drive(prep, d, COMPAT_SETTINGS, memo) for d in drives]
    stats = compare_drives(mine, theirs)
    sys.stderr.write(f"drive cross-check, compat mode: {stats.summary()}\n")
    assert stats.frames >= 0.99 * N_DRIVES * 50
    assert stats.rate >= 0.985
    beside = [(d, k) for d, k in stats.missed if beside_on_curve(mine[d][k], theirs[d][k])]
    assert len(stats.missed) - len(beside) <= 1


def test_drives_default_mode_misses_no_danger(town01_drives: Answers) -> None:
    """Default mode: a frame the reference calls dangerous is dangerous for us too, except
    in the documented deviation cases (docs/rss_scene.md, deviation table).

    Measured: 954 of 996 frames agree (95.8 %); of the 545 frames the reference calls
    dangerous, 6 are safe for us, all "beside on a curve" (:func:`beside_on_curve`); the
    36 frames only we call dangerous are ad-rss' swapped route headings and turn
    directions (and 3 of "beside on a curve"). A missed frame is also explained where
    the compatibility mode, i.e. the default mode plus the documented ad-rss rules, calls
    it dangerous.
    """
    prep, drives, theirs = town01_drives
    memo = SceneMemo()
    mine = [our_drive(prep, d, SETTINGS, memo) for d in drives]
    stats = compare_drives(mine, theirs)
    sys.stderr.write(f"drive cross-check, default mode: {stats.summary()}\n")
    # a frame the compatibility mode (default + the documented ad-rss rules) calls
    # dangerous is explained by those rules
    compat = {
        d: our_drive(prep, drives[d], COMPAT_SETTINGS, memo) for d in {d for d, _ in stats.missed}
    }
    unexplained = [
        (d, k)
        for d, k in stats.missed
        if not beside_on_curve(mine[d][k], theirs[d][k]) and not compat[d][k]["dangerous"]
    ]
    assert unexplained == []
    assert stats.rate >= 0.95
