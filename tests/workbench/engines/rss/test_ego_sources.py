"""RSS verdicts of the ``highway_cut_in`` drive with its ego written as a /tf chain, a pose
with covariance and GNSS (+ IMU, about the map origin) equal those of its Odometry ego.

The written logs carry the sample's own object and plan messages at their own times, each
stamp's objects before its ego message where the sample has them after (see
``tests.loaders.ego_logs``). The new egos have no twist: speed and acceleration come from
pose differences (within 0.05 m/s of the Odometry speed), which changes no verdict here; the
sample's own pose-only ``/tf`` (``--ego-topic /tf``) gives the same verdicts too.
"""

from __future__ import annotations

from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from loaders import open_drive
from tests.loaders.ego_logs import SAMPLE, write_origin_map, write_variant
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    from loaders.maps.model import LaneMap

ROOT = Path(__file__).resolve().parents[4]


def _verdicts(
    path: Path, lane_map: LaneMap, osm: Path | None = None, ego_topic: str | None = None
) -> list[tuple[bool, tuple[str, ...]]]:
    with closing(open_drive(path, map=osm, ego_topic=ego_topic)) as drive:
        frames = list(drive.frames())
    runner = RssRunner(lane_map)
    return [(v.is_safe, v.culprits) for v in runner.step_many(frames)]


@pytest.mark.parametrize("variant", ["tf", "pose_cov", "gnss"])
def test_same_rss_verdicts_as_the_odometry_ego(tmp_path: Path, variant: str) -> None:
    with closing(open_drive(ROOT / SAMPLE)) as drive:
        lane_map = drive.lane_map
    assert lane_map is not None
    expected = _verdicts(ROOT / SAMPLE, lane_map)
    assert _verdicts(ROOT / SAMPLE, lane_map, ego_topic="/tf") == expected
    osm = write_origin_map(tmp_path / "origin.osm") if variant == "gnss" else None
    got = _verdicts(write_variant(ROOT, tmp_path, variant), lane_map, osm)
    assert got == expected
    assert not all(safe for safe, _ in expected)  # the cut-in is unsafe somewhere
