"""The ``rss`` engine runner on the sample drives: pinned records, scenario events, CLI.

The golden per-frame records of every engine are tests/goldens (docs/testing.md).
"""

import json
from pathlib import Path
from typing import Any

import pytest

from loaders.open import open_drive
from tests.workbench.cli_runs import run_workbench as _run
from tests.workbench.engines.helpers import record, step
from workbench.engines.rss.runner import RssRunner
from workbench.samples.generate import SCENARIOS as SAMPLE_BUILDERS

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
#: Every road sample, in generation order.
SCENARIOS = list(SAMPLE_BUILDERS)
PINNED = {
    "is_safe",
    "dangerous_objects",
    "longitudinal_response",
    "lateral_response_left",
    "lateral_response_right",
    "acceleration_restrictions",
    "constellations",
    "invalid_objects",
    "profile",
    "responsibility",
    "severity",
    "compliance",
}
T0_NS = 1_700_000_000_000_000_000


def _frames(name: str) -> list[dict[str, Any]]:
    drive = open_drive(SAMPLES / f"{name}.mcap")
    try:
        runner = RssRunner(drive.lane_map)
        out = []
        for frame in drive.frames():
            result = step(runner, frame)
            assert set(record(result)) == PINNED
            assert result.is_safe == (not result.culprits)
            out.append(
                {
                    "frame": frame.index,
                    "t_ns": frame.t_ns,
                    "is_safe": record(result)["is_safe"],
                    "dangerous_objects": record(result)["dangerous_objects"],
                }
            )
        return out
    finally:
        drive.close()


@pytest.fixture(scope="module")
def evaluated() -> dict[str, list[dict[str, Any]]]:
    return {name: _frames(name) for name in SCENARIOS}


def _unsafe_times(frames: list[dict[str, Any]], actor: str) -> list[float]:
    return [(f["t_ns"] - T0_NS) / 1e9 for f in frames if actor in f["dangerous_objects"]]


def test_scenarios_flag_the_expected_actor_when_expected(evaluated):
    cut_in = _unsafe_times(evaluated["highway_cut_in"], "1")
    assert 5.5 <= min(cut_in) <= 8.5
    wrong_way = _unsafe_times(evaluated["wrong_way_oncoming"], "1")
    assert 4.0 <= min(wrong_way) <= 6.5
    assert max(wrong_way) <= 10.9
    lead = _unsafe_times(evaluated["hard_braking_lead"], "00000000000000000000000000000001")
    assert any(5.0 <= t <= 8.0 for t in lead)
    # free flow: nobody but the scenario's culprit is ever dangerous on the highway
    assert {d for f in evaluated["highway_cut_in"] for d in f["dangerous_objects"]} == {"1"}


@pytest.mark.parametrize(
    "log",
    [
        "highway_cut_in.bag",
        "wrong_way_oncoming_rosbag2",
        "pedestrian_crossing_foxglove.mcap",
        "parking_lot.mcap",
        "racing_overtake.saa",
        "urban_intersection.mcap",
    ],
)
def test_cli_evaluate_with_rss(log, tmp_path, capsys):
    per_frame = tmp_path / "frames.jsonl"
    code = _run(["evaluate", str(SAMPLES / log), "--engines", "rss", "--per-frame", str(per_frame)])
    assert code == 0, capsys.readouterr().err
    lines = [json.loads(line) for line in per_frame.read_text().splitlines()]
    assert lines
    assert all(set(line["rss"]) == PINNED for line in lines)


def test_adapter_marks_junction_lanes_and_right_of_way():
    from loaders.maps.lanelet2 import read_lanelet2  # noqa: PLC0415
    from workbench.engines.rss.adapter import lane_graph_from_map  # noqa: PLC0415

    graph = lane_graph_from_map(read_lanelet2(SAMPLES / "urban_intersection.osm"))
    ids = list(graph.ids)
    junction = {ids[i] for i in range(len(ids)) if graph.is_intersection[i]}
    assert junction == {"212", "214", "216", "218", "243"}
    assert graph.priority[ids.index("212")] == 1
    assert graph.priority[ids.index("243")] == -1
    assert graph.priority[ids.index("157")] == 0
    assert ids[graph.successors[ids.index("157")][0]] in {"216", "243"}


def test_adapter_traffic_light_and_drivable_lanes_only():
    from loaders.maps.lanelet2 import read_lanelet2  # noqa: PLC0415
    from workbench.engines.rss.adapter import lane_graph_from_map  # noqa: PLC0415

    graph = lane_graph_from_map(read_lanelet2(SAMPLES / "pedestrian_crossing.osm"))
    assert "140" not in graph.ids  # crosswalk
    assert "61" not in graph.ids  # sidewalk
    assert graph.traffic_light[list(graph.ids).index("63")] == 0
    assert not graph.is_intersection.any()


def test_runner_without_map_is_safe_and_ids_are_strings():
    from workbench.engines.ids import ActorIds  # noqa: PLC0415

    drive = open_drive(SAMPLES / "hard_braking_lead.mcap")
    try:
        runner = RssRunner(None)
        frame = next(iter(drive.frames()))
        out = step(runner, frame)
    finally:
        drive.close()
    assert out.is_safe
    assert set(record(out)) == PINNED
    ids = ActorIds()
    assert ids.to_int("17") == 17
    hexed = "000102030405060708090a0b0c0d0e0f"
    assert ids.label(ids.to_int(hexed)) == hexed


def test_runner_with_road_boundaries_names_them():
    drive = open_drive(SAMPLES / "highway_cut_in.mcap")
    try:
        runner = RssRunner(drive.lane_map, road_boundaries=True)
        records = [
            record(step(runner, frame)) for _, frame in zip(range(20), drive.frames(), strict=False)
        ]
    finally:
        drive.close()
    assert all(r["constellations"] >= 2 for r in records[1:])
    names = {d for r in records for d in r["dangerous_objects"]}
    assert not {"road_boundary_left", "road_boundary_right"} & names  # ego keeps its lane


def _evaluate_rss(log: str, tmp_path: Path, *options: str) -> list[dict[str, Any]]:
    """``evaluate --engines rss`` on a sample: its per-frame lines."""
    per_frame = tmp_path / f"{log}.jsonl"
    args = ["evaluate", str(SAMPLES / log), "--engines", "rss", "--per-frame", str(per_frame)]
    assert _run([*args, *options]) == 0
    return [json.loads(line) for line in per_frame.read_text().splitlines()]


def _first_unsafe_s(log: str, tmp_path: Path, *options: str) -> tuple[float, set[str]]:
    unsafe = [line for line in _evaluate_rss(log, tmp_path, *options) if not line["rss"]["is_safe"]]
    first = min(((line["t_ns"] - T0_NS) / 1e9 for line in unsafe), default=float("inf"))
    return first, {d for line in unsafe for d in line["rss"]["dangerous_objects"]}


def test_evaluate_records_the_review_profile_by_default_and_the_chosen_one(tmp_path):
    for options, label in (((), "highway"), (("--rss-profile", "adrss-5.0"), "adrss-5.0")):
        lines = _evaluate_rss("highway_cut_in.mcap", tmp_path, "--end", "1", *options)
        assert {line["rss"]["profile"] for line in lines} == {label}


@pytest.mark.parametrize(
    ("log", "event_s", "actor"),
    [
        ("highway_cut_in.mcap", 5.0, "1"),
        ("hard_braking_lead.mcap", 4.5, "00000000000000000000000000000001"),
    ],
)
def test_review_default_free_flow_is_safe_before_the_scripted_event(log, event_s, actor, tmp_path):
    # docs/samples.md: the free-flow stretch before the scripted event; the event's actor named
    first, named = _first_unsafe_s(log, tmp_path)
    assert first >= event_s
    assert actor in named
    # under the conformance reference the car-following gap of hard_braking_lead is unsafe
    reference_first, _ = _first_unsafe_s(log, tmp_path, "--rss-profile", "adrss-5.0")
    assert reference_first <= first


def test_review_default_names_the_wrong_way_car_during_its_event(tmp_path):
    # docs/samples.md: car 1 drifts into the ego lane from 4 s and the cars pass at 10.9 s
    lines = _evaluate_rss("wrong_way_oncoming.mcap", tmp_path)
    times = [(line["t_ns"] - T0_NS) / 1e9 for line in lines]
    car = [
        t for t, line in zip(times, lines, strict=True) if "1" in line["rss"]["dangerous_objects"]
    ]
    assert car
    assert 4.0 <= min(car) <= max(car) <= 10.9
    # free flow before 3.5 s: safe in every frame, also in frames 0-2 where motorcycle 3
    # (vision_msgs, no velocity) is a first detection: its velocity is the forward
    # difference to its next message, not 0 (loaders.message_logs.matching)
    early = [
        t for t, line in zip(times, lines, strict=True) if t < 3.5 and not line["rss"]["is_safe"]
    ]
    assert early == []
