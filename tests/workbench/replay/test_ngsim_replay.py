"""Every real NGSIM CommonRoad scenario replays into an .rrd that reads back whole."""

import pytest
from rerun.chunk import RrdReader

from loaders import open_drive
from tests.conftest import EXTERNAL_DIR
from workbench.viewer.replay import replay_drive

pytestmark = pytest.mark.external

NGSIM_FILES = sorted((EXTERNAL_DIR / "commonroad_ngsim").glob("*.xml"))


@pytest.mark.parametrize("name", [p.name for p in NGSIM_FILES] or ["<none found>"])
def test_ngsim_scenario_replays(external_dir, name, tmp_path):
    path = external_dir / "commonroad_ngsim" / name
    assert path.is_file(), f"{path} missing"
    drive = open_drive(path)
    try:
        out = tmp_path / "ngsim.rrd"
        summary = replay_drive(drive, out=out)
        lanes = len(drive.lane_map) if drive.lane_map is not None else 0
    finally:
        drive.close()
    assert summary.frames == drive.info.frame_count > 0
    assert lanes > 0
    store = RrdReader(out).store().stream().collect()
    ego = store.reader(index="frame", contents="/world/ego").to_arrow_table()
    assert sorted(ego.column("frame").to_pylist()) == list(range(summary.frames))
    static = store.reader(index=None, contents="/world/map/**").to_arrow_table()
    assert any(name.endswith(":LineStrips3D:strips") for name in static.column_names)
