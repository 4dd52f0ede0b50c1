"""One ego size for every engine and the viewer: the log's, or the user's ``--ego-size``."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest
from rerun.chunk import RrdReader
from typer.testing import CliRunner

from loaders import open_drive
from loaders.records import DEFAULT_EGO_HEIGHT_M, DEFAULT_EGO_LENGTH_M, DEFAULT_EGO_WIDTH_M
from rss.params import RssParams
from rss.scene import prepare
from tests.workbench.fakes import bound
from workbench.cli.main import app
from workbench.driver import DriveRun, EgoSize
from workbench.drives import parse_ego_size
from workbench.engines.base import VerdictSummary
from workbench.engines.ids import ActorIds
from workbench.engines.rss.adapter import frame_to_scene, lane_graph_from_map
from workbench.engines.rss.options import RssOptions, load_params, scene_sized
from workbench.engines.unstructured.adapter import UnstructuredScope, frame_to_agents
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.records import Frame

SAMPLE = Path(__file__).resolve().parents[3] / "sample_logs" / "highway_cut_in.mcap"


class _Seen:
    name = "seen"

    def __init__(self) -> None:
        self.sizes: set[tuple[float, float, float]] = set()

    def step_many(self, frames: Sequence[Frame]) -> list[VerdictSummary]:
        self.sizes.update((f.ego.length_m, f.ego.width_m, f.ego.height_m) for f in frames)
        return [VerdictSummary(is_safe=True) for _ in frames]


def test_ros_logs_carry_the_one_default_size_and_the_rss_engines_read_it():
    drive = open_drive(SAMPLE)
    frame = next(iter(drive.frames()))
    assert (frame.ego.length_m, frame.ego.width_m) == (DEFAULT_EGO_LENGTH_M, DEFAULT_EGO_WIDTH_M)
    assert drive.lane_map is not None
    prep = prepare(lane_graph_from_map(drive.lane_map))
    ego, _, _ = frame_to_scene(frame, prep, RssParams(), ActorIds())
    assert (ego.length_m, ego.width_m) == (frame.ego.length_m, frame.ego.width_m)
    scope = UnstructuredScope(drive.lane_map, RssParams().scene.constellation_creation_mode)
    agents = frame_to_agents(frame, scope.select(frame), RssParams(), ActorIds())
    assert float(agents.ego.length_m[0]) == frame.ego.length_m
    assert float(agents.ego.width_m[0]) == frame.ego.width_m
    drive.close()


def test_the_users_size_replaces_the_logs_in_every_frame_engines_see():
    drive = open_drive(SAMPLE)
    seen = _Seen()
    run = DriveRun(
        drive, [bound(seen)], end_ns=drive.info.start_ns + 10**9, ego_size=EgoSize(6.0, 2.5)
    )
    frames = [f for chunk in run for f in chunk.frames]
    drive.close()
    assert seen.sizes == {(6.0, 2.5, frames[0].ego.height_m)}
    assert {(f.ego.length_m, f.ego.width_m) for f in frames} == {(6.0, 2.5)}


def test_the_ego_size_option_reaches_the_viewers_ego_box(tmp_path):
    out = tmp_path / "cut_in.rrd"
    args = ["replay", str(SAMPLE), "--end", "1", "--out", str(out), "--engines", "rss"]
    result = CliRunner().invoke(app, [*args, "--ego-size", "6.0,2.5"])
    assert result.exit_code == 0, result.output
    store = RrdReader(str(out)).store().stream().collect()
    table = store.reader(index="frame", contents="/world/ego").to_arrow_table()
    half = table.column("/world/ego:Boxes3D:half_sizes").to_pylist()
    sizes = {tuple(np.round(np.asarray(h[0][:2]) * 2, 3)) for h in half if h}
    assert sizes == {(6.0, 2.5)}


@pytest.mark.parametrize("text", ["6", "6,x", "6,0", "6,2,1,1", "nan,2", "inf,2"])
def test_a_bad_ego_size_is_a_one_line_error(text: str) -> None:
    with pytest.raises(WorkbenchError, match="--ego-size"):
        parse_ego_size(text)


def test_the_rss_scene_ego_size_sizes_the_rss_engines_only(tmp_path):
    """``[scene] ego_length`` of ``--rss-params`` (the pinned file format): RSS scenes only."""
    params = tmp_path / "params.toml"
    params.write_text("[scene]\nego_length = 6.0\nego_width = 2.5\n")
    loaded = load_params(RssOptions(params=params), None)
    seen = _Seen()
    drive = open_drive(SAMPLE)
    frames = list(
        DriveRun(drive, [bound(scene_sized(seen, loaded))], end_ns=drive.info.start_ns + 10**9)
    )
    drive.close()
    assert seen.sizes == {(6.0, 2.5, DEFAULT_EGO_HEIGHT_M)}
    logged = {(f.ego.length_m, f.ego.width_m) for chunk in frames for f in chunk.frames}
    assert logged == {(DEFAULT_EGO_LENGTH_M, DEFAULT_EGO_WIDTH_M)}
    assert scene_sized(seen, load_params(RssOptions(), None)) is seen
