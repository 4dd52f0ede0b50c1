import math
import time
from pathlib import Path

import numpy as np
import pytest

from loaders.commonroad import PLAN_HORIZON_NS, commonroad_ego_candidates, open_commonroad
from loaders.errors import (
    CorruptLogError,
    EmptyLogError,
    InvalidValueError,
    LoaderError,
    MissingEgoTopicError,
    UnsupportedFormatError,
)
from loaders.maps.model import LaneMap
from loaders.records import Frame, ObjectClass
from tests.loaders.maps.commonroad_xml import scenario

NGSIM = [
    ("USA_Lanker-1_1_T-1.xml", "2018b", 24),
    ("USA_Lanker-1_4_T-1.xml", "2020a", 34),
    ("USA_Lanker-2_23_T-1.xml", "2020a", 53),
    ("USA_Peach-3_1_T-1.xml", "2020a", 5),
    ("USA_Peach-4_8_T-1.xml", "2020a", 9),
    ("USA_US101-23_1_T-1.xml", "2020a", 57),
    ("USA_US101-24_2_T-1.xml", "2020a", 52),
    ("USA_US101-3_1_T-1.xml", "2018b", 35),
    ("USA_US101-3_3_T-1.xml", "2018b", 12),
    ("USA_US101-4_1_T-1.xml", "2020a", 22),
    ("USA_US101-5_1_T-1.xml", "2020a", 25),
]

#: One recorded state: step, x, y, orientation, velocity, acceleration (None: absent).
State = tuple[int, float, float, float, float, float | None]


def _state(tag: str, state: State) -> str:
    step, x, y, yaw, v, acc = state
    accel = "" if acc is None else f"<acceleration><exact>{acc}</exact></acceleration>"
    return (
        f"<{tag}><position><point><x>{x}</x><y>{y}</y></point></position>"
        f"<orientation><exact>{yaw}</exact></orientation><time><exact>{step}</exact></time>"
        f"<velocity><exact>{v}</exact></velocity>{accel}</{tag}>"
    )


def obstacle(
    version: str, oid: int, kind: str, states: list[State], *, dynamic: bool = True
) -> str:
    first, *rest = states
    trajectory = "".join(_state("state", s) for s in rest)
    body = (
        f"<type>{kind}</type><shape><rectangle><length>4.0</length><width>2.0</width>"
        f"</rectangle></shape>{_state('initialState', first)}"
        + (f"<trajectory>{trajectory}</trajectory>" if rest else "")
    )
    if version == "2018b":
        role = "dynamic" if dynamic else "static"
        return f'<obstacle id="{oid}"><role>{role}</role>{body}</obstacle>'
    tag = "dynamicObstacle" if dynamic else "staticObstacle"
    return f'<{tag} id="{oid}">{body}</{tag}>'


def straight(
    steps: range, *, v: float = 10.0, y: float = 0.0, acc: float | None = None
) -> list[State]:
    return [(k, v * k * 0.1, y, 0.0, v, acc) for k in steps]


def write(tmp_path: Path, version: str, body: str, *, dt: str | None = "0.1") -> Path:
    path = tmp_path / f"scenario_{version}.xml"
    path.write_bytes(scenario(version, body, dt=dt))
    return path


def basic(version: str) -> str:
    return (
        obstacle(version, 10, "car", straight(range(5)))
        + obstacle(version, 20, "truck", straight(range(1, 3), y=3.5))
        + obstacle(version, 30, "pedestrian", straight(range(6), v=1.0, y=-5))
        + obstacle(version, 40, "parkedVehicle", straight(range(1), v=0.0, y=8), dynamic=False)
    )


@pytest.mark.parametrize("version", ["2018b", "2020a"])
def test_frames_on_the_ego_grid(tmp_path, version):
    path = write(tmp_path, version, basic(version))
    assert commonroad_ego_candidates(path) == ["10", "20"]  # pedestrians are no candidates
    drive = open_commonroad(path)
    info = drive.info
    assert info.source_format == f"commonroad-{version}"
    assert info.roles.ego == "obstacle/10"
    assert (info.start_ns, info.end_ns, info.frame_count) == (0, 400_000_000, 5)
    assert info.notes["ego_id"] == "10"
    assert info.notes["ego_candidates"] == "2"
    frames = list(drive.frames())
    assert [f.t_ns for f in frames] == [k * 100_000_000 for k in range(5)]
    assert [f.index for f in frames] == list(range(5))
    ids = [f.actors.ids.tolist() for f in frames]
    assert ids == [["30", "40"], ["20", "30", "40"], ["20", "30", "40"], ["30", "40"], ["30", "40"]]
    ego = frames[2].ego
    assert (ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps) == (2.0, 0.0, 0.0, 10.0)
    assert (ego.length_m, ego.width_m) == (4.0, 2.0)
    assert ego.accel_mps2 == 0.0
    truck = frames[1].actors
    assert truck.object_class.tolist() == [
        ObjectClass.TRUCK,
        ObjectClass.PEDESTRIAN,
        ObjectClass.UNKNOWN,
    ]
    np.testing.assert_allclose(truck.vx_mps, [10.0, 1.0, 0.0])
    np.testing.assert_allclose(truck.vy_mps, [0.0, 0.0, 0.0], atol=1e-12)
    assert truck.match_dt_ns.tolist() == [0, 0, 0]
    assert truck.valid.all()
    assert isinstance(drive.lane_map, LaneMap)
    assert len(drive.lane_map) == 3


def test_yaw_rate_unwraps_and_acceleration_falls_back_to_speed_difference(tmp_path):
    # Heading turns at 1 rad/s through +-pi; speed grows by 1 m/s per step (10 m/s^2).
    yaws = [3.0, 3.1, 3.2 - 2 * math.pi, 3.3 - 2 * math.pi]
    states: list[State] = [(k, float(k), 0.0, yaws[k], 10.0 + k, None) for k in range(4)]
    path = write(tmp_path, "2018b", obstacle("2018b", 7, "car", states))
    frames = list(open_commonroad(path).frames())
    np.testing.assert_allclose([f.ego.yaw_rate_radps for f in frames], [1.0] * 4, atol=1e-9)
    np.testing.assert_allclose([f.ego.accel_mps2 for f in frames], [10.0] * 4, atol=1e-9)


def test_recorded_acceleration_is_used(tmp_path):
    path = write(tmp_path, "2020a", obstacle("2020a", 7, "car", straight(range(3), acc=-2.5)))
    assert [f.ego.accel_mps2 for f in open_commonroad(path).frames()] == [-2.5] * 3


def test_plan_is_the_recorded_future_over_four_seconds(tmp_path):
    path = write(tmp_path, "2020a", obstacle("2020a", 7, "car", straight(range(60))))
    frames = list(open_commonroad(path).frames())
    plan = frames[0].plan
    assert plan is not None
    assert len(plan) == PLAN_HORIZON_NS // 100_000_000 + 1
    np.testing.assert_allclose(plan.t_offset_s, np.arange(41) * 0.1)
    np.testing.assert_allclose(plan.x_m, np.arange(41) * 1.0)
    np.testing.assert_allclose(plan.speed_mps, 10.0)
    last = frames[-1].plan
    assert last is not None
    assert len(last) == 1
    assert last.t_offset_s.tolist() == [0.0]


def test_time_window(tmp_path):
    path = write(tmp_path, "2020a", basic("2020a"))
    frames = list(open_commonroad(path).frames(start_ns=100_000_000, end_ns=300_000_000))
    assert [f.index for f in frames] == [1, 2]


def test_explicit_ego_and_map_override(tmp_path):
    path = write(tmp_path, "2020a", basic("2020a"))
    override = LaneMap(lanes={}, source="other.osm", format="lanelet2")
    drive = open_commonroad(path, ego_id="20", lane_map=override)
    assert drive.lane_map is override
    assert drive.info.map_source == "other.osm"
    frames = list(drive.frames())
    assert [f.t_ns for f in frames] == [100_000_000, 200_000_000]
    assert "20" not in frames[0].actors.ids.tolist()
    assert "10" in frames[0].actors.ids.tolist()


def test_bad_ego_id_lists_candidates(tmp_path):
    path = write(tmp_path, "2020a", basic("2020a"))
    with pytest.raises(MissingEgoTopicError, match=r"candidates: 10, 20") as info:
        open_commonroad(path, ego_id="30")
    assert isinstance(info.value, LoaderError)
    assert info.value.topic == "obstacle/30"


def test_nan_actor_value_only_invalidates_its_row(tmp_path):
    actor = straight(range(3), y=3.5)
    actor[1] = (1, math.nan, 3.5, 0.0, 10.0, None)
    body = obstacle("2020a", 1, "car", straight(range(3))) + obstacle("2020a", 2, "bus", actor)
    path = write(tmp_path, "2020a", body.replace("<x>nan</x>", "<x>garbage</x>"))
    frames = list(open_commonroad(path, ego_id="1").frames())
    assert [f.actors.valid.tolist() for f in frames] == [[True], [False], [True]]


def test_nan_ego_pose_stops_with_a_typed_error(tmp_path):
    states = straight(range(4))
    states[2] = (2, 2.0, math.nan, 0.0, 10.0, None)
    path = write(tmp_path, "2018b", obstacle("2018b", 5, "car", states))
    frames: list[Frame] = []
    with pytest.raises(InvalidValueError, match=r"time step 2: y_m") as info:
        frames.extend(open_commonroad(path).frames())
    assert [f.index for f in frames] == [0, 1]
    assert info.value.t_ns == 200_000_000
    assert str(path) in str(info.value)
    assert math.isnan(info.value.value)
    assert all(np.isfinite(f.ego.yaw_rate_radps) for f in frames)


@pytest.mark.parametrize("version", ["2018b", "2020a"])
def test_empty_scenario(tmp_path, version):
    path = write(tmp_path, version, "")
    with pytest.raises(EmptyLogError):
        open_commonroad(path)
    assert commonroad_ego_candidates(path) == []


def test_malformed_and_foreign_files(tmp_path):
    cut = tmp_path / "cut.xml"
    cut.write_bytes(scenario("2020a", basic("2020a"))[:-40])
    with pytest.raises(CorruptLogError, match="malformed XML"):
        open_commonroad(cut)
    other = tmp_path / "other.xml"
    other.write_bytes(b"<osm/>")
    with pytest.raises(UnsupportedFormatError, match="not <commonRoad>"):
        open_commonroad(other)
    with pytest.raises(UnsupportedFormatError, match="cannot open"):
        open_commonroad(tmp_path / "absent.xml")


def test_missing_time_step_size(tmp_path):
    path = write(tmp_path, "2020a", basic("2020a"), dt=None)
    with pytest.raises(InvalidValueError, match="timeStepSize"):
        open_commonroad(path)


def _check_frames(drive, ego_id, frames) -> int:
    last = -1
    for frame in frames:
        assert frame.t_ns > last
        last = frame.t_ns
        ego = frame.ego
        values = [ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps, ego.accel_mps2, ego.yaw_rate_radps]
        assert np.isfinite(values).all()
        assert ego_id not in frame.actors.ids.tolist()
        assert frame.plan is not None
        assert frame.plan.t_offset_s[0] == 0.0
        assert frame.t_ns % 100_000_000 == 0
    return last


@pytest.mark.external
@pytest.mark.parametrize(("name", "version", "count"), NGSIM)
def test_ngsim_every_candidate_ego(external_dir, name, version, count):
    path = external_dir / "commonroad_ngsim" / name
    started = time.perf_counter()
    candidates = commonroad_ego_candidates(path)
    assert len(candidates) == count
    default = open_commonroad(path)
    assert default.info.notes["ego_id"] == candidates[0]
    assert default.info.source_format == f"commonroad-{version}"
    assert len(default.lane_map) > 0
    for ego_id in candidates:
        drive = open_commonroad(path, ego_id=ego_id)
        last = _check_frames(drive, ego_id, drive.frames())
        assert last == drive.info.end_ns
        assert drive.info.frame_count == round((last - drive.info.start_ns) / 1e8) + 1
    assert time.perf_counter() - started < 10.0
