"""The ``unstructured`` engine: adapter, pair selection, runner, CLI, scenario events.

The golden per-frame records of every engine are tests/goldens (docs/testing.md).
"""

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from loaders import open_drive
from loaders.maps.model import Lane, LaneKind, LaneMap
from loaders.records import ActorTable, EgoState, Frame, ObjectClass
from rss.model import ObjectType
from rss.params import ConstellationCreationMode, RssParams, SceneSettings
from rss.params import ObjectClass as DynClass
from rss.unstructured import UnstructuredMemory
from tests.rss.unstructured.frames_check import assert_same_memory, assert_same_result
from tests.workbench.cli_runs import run_workbench as _run
from tests.workbench.engines.helpers import record, step
from tests.workbench.fakes import straight_road
from workbench.engines.ids import EGO_OBJECT_ID, ActorIds
from workbench.engines.unstructured.adapter import UnstructuredScope, frame_to_agents
from workbench.engines.unstructured.runner import UnstructuredRunner

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
T0_NS = 1_700_000_000_000_000_000
PINNED = {
    "is_safe",
    "dangerous_objects",
    "decisions",
    "longitudinal_response",
    "unstructured_constellation_response",
    "heading_ranges",
    "acceleration_restrictions",
    "constellations",
    "invalid_objects",
}


def _frame(
    rows: list[dict[str, Any]], *, ego_speed: float = 10.0, ego_xy=(10.0, 1.75), index: int = 0
) -> Frame:
    """Ego along +x on lane 0 of ``straight_road``; one actor per row (defaults: a car)."""
    ego = EgoState(
        x_m=ego_xy[0],
        y_m=ego_xy[1],
        z_m=0.0,
        yaw_rad=0.0,
        speed_mps=ego_speed,
        accel_mps2=0.0,
        yaw_rate_radps=0.05,
    )
    n = len(rows)

    def col(key: str, default: float) -> list[float]:
        return [float(r.get(key, default)) for r in rows]

    actors = ActorTable.from_columns(
        ids=[str(r["id"]) for r in rows],
        object_class=[int(r.get("cls", ObjectClass.CAR)) for r in rows],
        x_m=col("x", 0.0),
        y_m=col("y", 1.75),
        yaw_rad=col("yaw", 0.0),
        vx_mps=col("vx", 0.0),
        vy_mps=col("vy", 0.0),
        length_m=col("length", 4.5 if n else 0.0),
        width_m=col("width", 1.9),
    )
    return Frame(index=index, t_ns=T0_NS + index * 100_000_000, ego=ego, actors=actors)


def _pedestrian(x: float, y: float, vy: float = 1.4) -> dict[str, Any]:
    return {
        "id": 7,
        "cls": ObjectClass.PEDESTRIAN,
        "x": x,
        "y": y,
        "yaw": math.pi,
        "vy": vy,
        "length": 0.5,
        "width": 0.5,
    }


# --- adapter ---------------------------------------------------------------------------------


def test_agents_units_classes_and_headings():
    frame = _frame(
        [
            {"id": 1, "x": 30.0, "vx": 3.0, "vy": 4.0, "yaw": math.atan2(4, 3)},
            {"id": 2, "x": 40.0, "yaw": 0.0, "vx": -1.2},  # reversing
            _pedestrian(50.0, -2.0),
            {"id": 4, "cls": ObjectClass.BICYCLE, "x": 60.0, "vx": 5.0},
            {"id": 5, "cls": ObjectClass.TRUCK, "x": 70.0, "length": float("nan")},
        ]
    )
    params = RssParams()
    out = frame_to_agents(frame, np.ones(5, dtype=bool), params, ActorIds())
    assert out.actor_ids == ("1", "2", "7", "4")
    assert out.invalid == ("5",)
    a = out.agents
    np.testing.assert_allclose(a.speed_max_mps, [5.0, 1.2, 1.4, 5.0])
    np.testing.assert_allclose(a.speed_min_mps, a.speed_max_mps)
    np.testing.assert_allclose(a.yaw_rad, [math.atan2(4, 3), -math.pi, math.pi / 2, 0.0])
    assert list(a.object_type) == [
        ObjectType.OtherVehicle,
        ObjectType.OtherVehicle,
        ObjectType.Pedestrian,
        ObjectType.Bicycle,
    ]
    np.testing.assert_allclose(a.yaw_rate_radps, 0.0)
    assert out.dynamics[2] == params.for_class(DynClass.PEDESTRIAN)
    assert out.dynamics[3] == params.for_class(DynClass.BICYCLE)
    assert list(a.object_id) == [1, 2, 7, 4]
    ego = out.ego
    assert int(ego.object_id[0]) == EGO_OBJECT_ID
    assert int(ego.object_type[0]) == ObjectType.EgoVehicle
    assert float(ego.speed_max_mps[0]) == 10.0
    assert float(ego.yaw_rate_radps[0]) == 0.05
    assert float(ego.length_m[0]) == frame.ego.length_m


def test_reversing_ego_gets_heading_of_travel():
    frame = _frame([], ego_speed=-2.0)
    out = frame_to_agents(frame, np.zeros(0, dtype=bool), RssParams(), ActorIds())
    assert float(out.ego.speed_max_mps[0]) == 2.0
    assert float(out.ego.yaw_rad[0]) == pytest.approx(-math.pi)


def _parking_map() -> LaneMap:
    road = straight_road(lanes=1)
    xs = np.array([0.0, 10.0])
    space = Lane(
        id="p1",
        left_m=np.column_stack([xs, np.full(2, 8.5)]),
        right_m=np.column_stack([xs, np.full(2, 3.5)]),
        centre_m=np.column_stack([xs, np.full(2, 6.0)]),
        kind=LaneKind.PARKING,
    )
    return LaneMap(lanes={**road.lanes, "p1": space}, source="synthetic", format="synthetic")


def test_scope_selects_pedestrians_and_off_lane_actors_on_a_road():
    frame = _frame(
        [
            {"id": 1, "x": 30.0},  # on the road
            _pedestrian(40.0, 1.75),
            {"id": 3, "x": 50.0, "y": 20.0},  # off every lane
        ]
    )
    scope = UnstructuredScope(straight_road(lanes=1), ConstellationCreationMode.STRUCTURED)
    assert list(scope.select(frame)) == [False, True, True]
    every = UnstructuredScope(straight_road(lanes=1), ConstellationCreationMode.UNSTRUCTURED)
    assert every.select(frame).all()
    assert UnstructuredScope(None, ConstellationCreationMode.STRUCTURED).select(frame).all()
    off_road = _frame([{"id": 1, "x": 30.0}], ego_xy=(10.0, 30.0))
    assert scope.select(off_road).all()


def test_scope_parking_lot_and_aisle():
    lot = UnstructuredScope(_parking_map(), ConstellationCreationMode.STRUCTURED)
    # the road touches the parking lanelet: it is an aisle, everything is unstructured
    assert lot.select(_frame([{"id": 1, "x": 30.0}])).all()
    road = UnstructuredScope(straight_road(lanes=1), ConstellationCreationMode.STRUCTURED)
    assert not road.select(_frame([{"id": 1, "x": 30.0}])).any()


# --- runner ----------------------------------------------------------------------------------


def _runner(mode: ConstellationCreationMode = ConstellationCreationMode.STRUCTURED):
    params = RssParams(scene=SceneSettings(constellation_creation_mode=mode))
    return UnstructuredRunner(straight_road(lanes=2), params)


def test_pedestrian_stepping_in_front_means_brake():
    out = step(_runner(), _frame([_pedestrian(25.0, 0.0)]))
    assert set(record(out)) == PINNED
    assert not out.is_safe
    assert out.culprits == ("7",)
    assert record(out)["decisions"] == {"7": "Brake"}
    assert record(out)["longitudinal_response"] == "BrakeMin"
    assert record(out)["unstructured_constellation_response"] == "Brake"
    assert out.cause == "unstructured: brake"
    assert out.margin == 0.0
    lon = record(out)["acceleration_restrictions"]["longitudinal"]
    assert lon[1] == RssParams().for_class(DynClass.EGO).brake_min_mps2
    assert out.detail.actor_ids == ("7",)


def test_far_pedestrian_is_safe_and_cars_on_lanes_are_left_to_structured_rss():
    out = step(_runner(), _frame([_pedestrian(200.0, -3.0, vy=0.0), {"id": 1, "x": 20.0}]))
    assert out.is_safe
    assert out.culprits == ()
    assert record(out)["decisions"] == {"7": "ContinueForward"}
    assert record(out)["constellations"] == 1
    assert record(out)["heading_ranges"] == []


def test_no_pairs_is_safe_without_detail():
    out = step(_runner(), _frame([{"id": 1, "x": 20.0}]))
    assert out.is_safe
    assert set(record(out)) == PINNED
    assert record(out)["constellations"] == 0
    assert out.detail is None


def test_both_stopped_and_close_means_drive_away_with_memory():
    runner = _runner(ConstellationCreationMode.UNSTRUCTURED)
    car = {"id": 9, "x": 16.0}  # stopped right in front of the stopped ego
    first = step(runner, _frame([car], ego_speed=0.0))
    assert record(first)["decisions"] == {"9": "DriveAway"}
    assert record(first)["unstructured_constellation_response"] == "DriveAway"
    assert first.cause == "unstructured: drive-away"
    assert len(record(first)["heading_ranges"]) == 1
    # the other moves: the drive-away state is dropped and the ego must brake
    moved = step(runner, _frame([{**car, "x": 16.5, "vx": 0.5}], ego_speed=0.0, index=1))
    assert record(moved)["decisions"] == {"9": "Brake"}


@pytest.mark.parametrize("name", ["pedestrian_crossing", "parking_lot"])
def test_step_many_equals_step_by_step_on_the_sample_drives(name):
    """Records, verdicts, the detail (sets, decisions) and the memory after each chunk."""
    drive = open_drive(SAMPLES / f"{name}.mcap")
    frames = list(drive.frames())
    drive.close()
    one, many = UnstructuredRunner(drive.lane_map), UnstructuredRunner(drive.lane_map)
    expected, got = [], []
    for lo in range(0, len(frames), 29):  # chunks that start mid-run of frames with pairs
        chunk = frames[lo : lo + 29]
        expected += [step(one, f) for f in chunk]
        got += many.step_many(chunk)
        assert_same_memory(many._memory or UnstructuredMemory.empty(), one._memory)
    assert len(got) == len(frames)
    checked = 0
    for g, e in zip(got, expected, strict=True):
        assert (record(g), g.is_safe, g.culprits, g.cause, g.margin) == (
            record(e),
            e.is_safe,
            e.culprits,
            e.cause,
            e.margin,
        )
        assert (g.detail is None) == (e.detail is None)
        if e.detail is not None:
            assert g.detail is not None
            assert g.detail.actor_ids == e.detail.actor_ids
            for field in e.detail.ego.__dataclass_fields__:
                np.testing.assert_array_equal(
                    getattr(g.detail.ego, field), getattr(e.detail.ego, field)
                )
            assert_same_result(g.detail.result, e.detail.result)
            checked += 1
    assert checked > 20
    assert any(not e.is_safe for e in expected)


# --- CLI and scenario events -----------------------------------------------------------------


def _event_frames(lines: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [
        {
            "frame": line["frame"],
            "t_ns": line["t_ns"],
            "is_safe": line["unstructured"]["is_safe"],
            "dangerous_objects": line["unstructured"]["dangerous_objects"],
            "decisions": line["unstructured"]["decisions"],
        }
        for line in lines
    ]


@pytest.fixture(scope="module")
def evaluated(tmp_path_factory) -> dict[str, list[dict[str, Any]]]:
    out = {}
    for name in ("pedestrian_crossing", "parking_lot"):
        per_frame = tmp_path_factory.mktemp(name) / "frames.jsonl"
        code = _run(
            [
                "evaluate",
                str(SAMPLES / f"{name}.mcap"),
                "--engines",
                "unstructured",
                "--per-frame",
                str(per_frame),
                # the reference dynamics the event times below were read with (auto: urban)
                "--rss-profile",
                "adrss-5.0",
            ]
        )
        assert code == 0
        out[name] = [json.loads(line) for line in per_frame.read_text().splitlines()]
    return out


def test_cli_evaluate_end_to_end(evaluated):
    lines = evaluated["pedestrian_crossing"]
    assert len(lines) == 401
    assert all(set(line) == {"t_ns", "frame", "unstructured"} for line in lines)
    assert all(set(line["unstructured"]) == PINNED for line in lines)


def _dangerous_times(frames: list[dict[str, Any]], actor: str) -> list[float]:
    return [(f["t_ns"] - T0_NS) / 1e9 for f in frames if actor in f["dangerous_objects"]]


def test_scenarios_brake_when_expected(evaluated):
    crossing = _event_frames(evaluated["pedestrian_crossing"])
    walker = _dangerous_times(crossing, "1")
    # the pedestrian steps off at t = 3 s and leaves the ego lane at t = 7.9 s
    assert 3.0 <= min(walker) <= 5.2
    assert max(walker) <= 7.9
    braking = [f["decisions"]["1"] for f in crossing if "1" in f["dangerous_objects"]]
    assert set(braking) == {"Brake"}
    lot = _event_frames(evaluated["parking_lot"])
    car = "00000000000000000000000000000001"
    reversing = _dangerous_times(lot, car)
    assert 3.0 <= min(reversing) <= 9.5
    assert any(f["decisions"].get(car) == "DriveAway" for f in lot)
