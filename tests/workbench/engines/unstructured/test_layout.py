"""Unstructured RSS in Rerun: pure layout (triangles, colours, fan), an ``.rrd`` round trip."""

from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pytest
import rerun as rr
import shapely
from rerun.chunk import RrdReader

from rss.params import ConstellationCreationMode, RssParams, SceneSettings
from tests.workbench.engines.helpers import step
from tests.workbench.engines.unstructured.test_runner import _frame, _pedestrian
from tests.workbench.fakes import straight_road
from workbench.cli.main import main
from workbench.engines.unstructured.layout import (
    COLORS,
    EGO_SET_COLOR,
    Category,
    layout_unstructured,
    triangulate,
)
from workbench.engines.unstructured.runner import UnstructuredRunner
from workbench.engines.unstructured.sink import ROOT, STATE_PATH, UnstructuredSink
from workbench.engines.unstructured.verdict import UnstructuredDetail
from workbench.replay.strips import SIMPLIFY_M


def _detail(
    rows: list[dict[str, Any]],
    *,
    ego_speed: float = 10.0,
    mode: ConstellationCreationMode = ConstellationCreationMode.STRUCTURED,
) -> UnstructuredDetail:
    params = RssParams(scene=SceneSettings(constellation_creation_mode=mode))
    out = step(
        UnstructuredRunner(straight_road(lanes=2), params), _frame(rows, ego_speed=ego_speed)
    )
    assert isinstance(out.detail, UnstructuredDetail)
    return out.detail


@pytest.fixture(scope="module")
def details():
    brake = _detail([_pedestrian(25.0, 0.0)])
    safe = _detail([{**_pedestrian(200.0, -3.0, vy=0.0), "id": 8}])
    drive_away = _detail(
        [{"id": 9, "x": 16.0}], ego_speed=0.0, mode=ConstellationCreationMode.UNSTRUCTURED
    )
    return {"brake": brake, "safe": safe, "drive_away": drive_away}


def _rgb(color: int) -> int:
    return color & 0xFFFFFF00


def test_triangles_match_the_polygons_triangulation(details):
    for detail in details.values():
        cols = layout_unstructured([detail])
        sets = detail.result.agent_sets.polygons(brake=True)
        expected = shapely.get_parts(
            shapely.constrained_delaunay_triangles(shapely.simplify(sets, SIMPLIFY_M))
        )
        assert cols.agent_sets.triangle_counts.tolist() == [len(expected)]
        assert cols.agent_sets.vertex_counts.tolist() == [3 * len(expected)]
        assert cols.agent_sets.triangles.shape == (len(expected), 3)
        assert cols.agent_sets.triangles.max() == 3 * len(expected) - 1
        corners, owner = triangulate(shapely.simplify(sets, SIMPLIFY_M))
        area = sum(shapely.area(shapely.Polygon(c)) for c in corners)
        assert area == pytest.approx(float(shapely.area(shapely.simplify(sets, SIMPLIFY_M)[0])))
        assert set(owner.tolist()) == {0}


def test_colours_follow_the_decision(details):
    cols = layout_unstructured(list(details.values()))
    assert cols.states.tolist() == ["brake", "safe", "drive-away"]
    n = cols.agent_sets.vertex_counts
    colors = np.split(cols.agent_sets.colors, np.cumsum(n)[:-1])
    expected = (Category.BRAKE, Category.SAFE, Category.DRIVE_AWAY)
    for frame_colors, cat in zip(colors, expected, strict=True):
        assert len(frame_colors)
        assert set((frame_colors & 0xFFFFFF00).tolist()) == {_rgb(COLORS[cat])}
    assert set((cols.ego_sets.colors & 0xFFFFFF00).tolist()) == {_rgb(EGO_SET_COLOR)}
    # brake outline opaque, continue-forward outline fainter, both per agent
    assert cols.agent_outlines.counts.tolist() == [2, 2, 2]
    # only the drive-away frame has a heading fan, drawn from the ego centre
    assert cols.fan.counts[:2].tolist() == [0, 0]
    assert cols.fan.counts[2] > 2
    ego_xy = np.array([details["drive_away"].ego.x_m[0], details["drive_away"].ego.y_m[0]])
    np.testing.assert_allclose(cols.fan.strips[0, 0, :2], ego_xy, atol=1e-5)
    assert set(cols.fan.colors.tolist()) == {COLORS[Category.DRIVE_AWAY]}


def test_frames_without_pairs_are_empty_and_safe(details):
    cols = layout_unstructured([None, details["brake"], None])
    assert cols.states.tolist() == ["safe", "brake", "safe"]
    assert cols.agent_sets.vertex_counts[[0, 2]].tolist() == [0, 0]
    assert cols.ego_outlines.counts[[0, 2]].tolist() == [0, 0]


def _read(path: Path, entity: str) -> pa.Table:
    store = RrdReader(str(path)).store().stream().collect()
    return store.reader(index="frame", contents=entity).to_arrow_table()


def test_rrd_round_trip(tmp_path, details):
    path = tmp_path / "unstructured.rrd"
    rec = rr.RecordingStream("test-unstructured", recording_id="r1")
    rec.save(str(path))
    rec.set_log_time_enabled(False)
    sink = UnstructuredSink(rec)
    frames = [None, details["brake"], details["drive_away"]]
    cols = layout_unstructured(frames)
    t_ns = 1_700_000_000_000_000_000 + np.arange(3, dtype=np.int64) * 50_000_000
    sink.send_columns(np.arange(3, dtype=np.int64), t_ns, cols)
    rec.flush()
    rec.disconnect()
    agents = _read(path, f"/{ROOT}/agent_sets")
    vertices = agents.column(f"/{ROOT}/agent_sets:Mesh3D:vertex_positions").to_pylist()
    triangles = agents.column(f"/{ROOT}/agent_sets:Mesh3D:triangle_indices").to_pylist()
    assert [len(v) for v in vertices] == cols.agent_sets.vertex_counts.tolist()
    assert [len(t) for t in triangles] == cols.agent_sets.triangle_counts.tolist()
    fan = _read(path, f"/{ROOT}/heading_ranges")
    strips = fan.column(f"/{ROOT}/heading_ranges:LineStrips3D:strips").to_pylist()
    assert [len(s) for s in strips] == cols.fan.counts.tolist()
    state = _read(path, f"/{STATE_PATH}")
    values = state.column(f"/{STATE_PATH}:StateChange:state").to_pylist()
    assert [v[0] for v in values] == ["safe", "brake", "drive-away"]


def test_cli_replay_logs_the_unstructured_entities(tmp_path):
    log = Path(__file__).resolve().parents[4] / "sample_logs" / "pedestrian_crossing.mcap"
    out = tmp_path / "ped.rrd"
    args = ["replay", str(log), "--engines", "unstructured", "--out", str(out)]
    with pytest.raises(SystemExit) as info:
        main([*args, "--start", "5", "--end", "6"])
    assert info.value.code in {0, None}
    state = _read(out, f"/{STATE_PATH}")
    values = state.column(f"/{STATE_PATH}:StateChange:state").to_pylist()
    assert {v[0] for v in values} == {"brake"}
    agents = _read(out, f"/{ROOT}/agent_sets")
    assert agents.num_rows == len(values)
