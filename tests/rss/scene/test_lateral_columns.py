"""Road areas with a segment that lacks lanes on the left keep their lateral frame (issue 27).

On the NGSIM scenario USA_Peach-4_8 (CommonRoad, Peachtree Street) the ego stands on the
start of a right-turn lane (43640) that forks off the rightmost through lane; the cars
564 and 569 drive one lane further left. The road area of the route from the turn lane
back to them has a segment holding the turn lane alone: ad-rss places lanes by their
column in the segment, so the turn lane sat in column 0, beside the cars' lane, and the
constellation came out laterally overlapping (distance ratio 0.0, "overlapping") while
the boxes are 1.2-4.5 m apart. The default mode pads such segments with the missing
columns (``rss.scene.corridor``); the compatibility mode keeps ad-rss' columns.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import pytest
import shapely

from workbench.drives import open_log
from workbench.engines.rss.options import RssOptions, load_params
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.records import Frame
    from workbench.engines.rss.verdict import RssVerdict

SCENARIO = "commonroad_ngsim/USA_Peach-4_8_T-1.xml"
CARS = ("564", "569")
#: A car counts as clear of the ego when the boxes are this far apart (m).
CLEAR_M = 0.5


def _box(x: float, y: float, yaw: float, length: float, width: float) -> shapely.Polygon:
    c, s = np.cos(yaw), np.sin(yaw)
    corners = [(length / 2, width / 2), (length / 2, -width / 2), (-length / 2, -width / 2)]
    corners.append((-length / 2, width / 2))
    return shapely.Polygon([(x + c * u - s * v, y + s * u + c * v) for u, v in corners])


def _gap_m(frame: Frame, car: str) -> float | None:
    ids = [str(a) for a in frame.actors.ids]
    if car not in ids:
        return None
    a, e, j = frame.actors, frame.ego, ids.index(car)
    ego = _box(e.x_m, e.y_m, e.yaw_rad, e.length_m, e.width_m)
    return float(ego.distance(_box(a.x_m[j], a.y_m[j], a.yaw_rad[j], a.length_m[j], a.width_m[j])))


@pytest.fixture(scope="module")
def peach(external_dir: Path) -> tuple[list[Frame], list[RssVerdict], list[RssVerdict]]:
    """The frames and the RSS verdicts of both modes (default profile, as the CLI)."""
    drive = open_log(external_dir / SCENARIO, map_path=None, profile=None, ego_id=None)
    try:
        params = load_params(RssOptions(), drive.lane_map)
        frames = list(drive.frames())
        default = RssRunner(drive.lane_map, params).step_many(frames)
        compat_scene = dataclasses.replace(params.scene, reproduce_adrss_5_0_defects=True)
        compat_params = dataclasses.replace(params, scene=compat_scene)
        compat = RssRunner(drive.lane_map, compat_params).step_many(frames)
    finally:
        drive.close()
    return frames, default, compat


def _lateral_m(verdict: RssVerdict, car: str) -> float | None:
    """The car's smallest lateral distance over its constellations (None: none)."""
    if verdict.result is None:
        return None
    rows = [i for i, label in enumerate(verdict.labels) if label == car]
    if not rows:
        return None
    return float(np.min(verdict.result.relative.lat_distance_m[rows]))


def _ratio(verdict: RssVerdict, car: str) -> float:
    """The car's smallest distance ratio over its constellations (inf: none)."""
    result = verdict.result
    if result is None or result.severity is None:
        return float("inf")
    rows = [i for i, label in enumerate(verdict.labels) if label == car]
    return float(np.min(result.severity.distance_ratio[rows])) if rows else float("inf")


def test_cars_beside_the_turn_lane_are_laterally_apart(
    peach: tuple[list[Frame], list[RssVerdict], list[RssVerdict]],
) -> None:
    """No frame gives 564 or 569 ratio 0.0 while their box is clear of the ego's; the
    frames where the ego's turn lane used to make them overlap now have the lateral gap."""
    frames, default, _ = peach
    clear = [
        (k, car)
        for k, frame in enumerate(frames)
        for car in CARS
        if (gap := _gap_m(frame, car)) is not None and gap > CLEAR_M
    ]
    assert len(clear) > 40  # the cars are beside the ego for most of the drive
    assert [(k, car) for k, car in clear if _ratio(default[k], car) == 0.0] == []
    lateral = [_lateral_m(default[k], "564") for k in range(29, 37)]
    assert all(v is not None and v > CLEAR_M for v in lateral), lateral


def test_compat_mode_keeps_adrss_columns(
    peach: tuple[list[Frame], list[RssVerdict], list[RssVerdict]],
) -> None:
    """The compatibility mode keeps ad-rss' columns: car 564 overlaps in frames 29-36."""
    _, _, compat = peach
    assert [_lateral_m(compat[k], "564") for k in range(29, 37)] == [0.0] * 8
