"""ScenarioArchitect reader: the generated racing sample round-trips; damage is typed."""

from __future__ import annotations

import math
import zipfile

import numpy as np
import pytest

from loaders.errors import CorruptLogError, LoaderError, UnsupportedFormatError
from loaders.records import PlanKind
from loaders.scenario_architect import north0_to_enu, open_scenario_architect
from workbench.samples.racing import racing_centre, write_racing_sample


@pytest.fixture(scope="module")
def sample(tmp_path_factory):
    return write_racing_sample(tmp_path_factory.mktemp("racing"))[0]


def test_sample_is_small_and_deterministic(sample, tmp_path):
    again = write_racing_sample(tmp_path)[0]
    assert sample.read_bytes() == again.read_bytes()
    assert sample.stat().st_size < 300_000


def test_sample_round_trips(sample):
    with open_scenario_architect(sample) as drive:
        frames = list(drive.frames())
        info = drive.info
        lane_map = drive.lane_map
    assert info.source_format == "scenario-architect"
    assert len(frames) == info.frame_count == 81
    assert frames[10].t_ns == 1_000_000_000
    assert lane_map.format == "track"
    left, right = lane_map.boundaries_m
    assert left.shape == right.shape == (120, 2)
    f0 = frames[0]
    assert f0.ego.x_m == pytest.approx(0.0)
    assert f0.ego.yaw_rad == pytest.approx(0.0, abs=1e-4)  # north-0 -pi/2 -> ENU 0
    assert f0.ego.speed_mps == pytest.approx(38.0)
    assert list(f0.actors.ids) == ["veh_2"]
    assert f0.actors.x_m[0] == pytest.approx(40.0)
    assert f0.actors.vx_mps[0] == pytest.approx(32.0, abs=1e-3)
    assert f0.plan is not None
    assert len(f0.plan) == 30
    assert f0.plan.speed_mps[-1] == pytest.approx(0.0)
    assert np.all(np.isnan(f0.plan.t_offset_s))
    assert f0.extras["labels"] == {"safety_dyn": True, "safety_stat": None}
    assert set(f0.extras["trajectories"]) == {"performance", "emergency"}
    assert f0.plan_kind is PlanKind.EMERGENCY
    assert "plan_kind" not in f0.extras


def test_performance_plan_and_window(sample):
    drive = open_scenario_architect(sample, plan="performance")
    frames = list(drive.frames(start_ns=2_000_000_000, end_ns=3_000_000_000))
    assert [f.index for f in frames] == list(range(20, 30))
    plan = frames[0].plan
    assert plan is not None
    assert frames[0].plan_kind is PlanKind.NOMINAL
    assert plan.speed_mps[-1] == pytest.approx(38.0)
    x, _, _, _ = racing_centre(np.array([38.0 * 2.0]))
    assert frames[0].ego.x_m == pytest.approx(float(x[0]), abs=0.1)


def test_heading_conversion():
    assert north0_to_enu(0.0) == pytest.approx(math.pi / 2)
    assert north0_to_enu(-math.pi / 2) == pytest.approx(0.0)
    assert north0_to_enu(math.pi) == pytest.approx(-math.pi / 2)


def test_bad_zip_is_a_typed_error_naming_the_file(tmp_path):
    bad = tmp_path / "broken.saa"
    bad.write_bytes(b"PK\x03\x04 not really a zip")
    with pytest.raises(CorruptLogError) as err:
        open_scenario_architect(bad)
    assert "broken.saa" in str(err.value)
    assert isinstance(err.value, LoaderError)


def test_archive_without_scn_member(tmp_path):
    path = tmp_path / "empty.saa"
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("x.sas", b"\x80\x04not parsed")
    with pytest.raises(UnsupportedFormatError):
        open_scenario_architect(path)


def test_bad_row_yields_readable_frames_then_raises(sample, tmp_path):
    with zipfile.ZipFile(sample) as zf:
        text = zf.read("racing_overtake.scn").decode()
    lines = text.splitlines()
    lines[3 + 5] = lines[3 + 5].replace(";[[", ";[[oops", 1)
    path = tmp_path / "damaged.scn"
    path.write_text("\n".join(lines) + "\n")
    drive = open_scenario_architect(path)
    got: list[int] = []
    with pytest.raises(CorruptLogError) as err:
        got.extend(f.index for f in drive.frames())
    assert got == [0, 1, 2, 3, 4]
    assert err.value.offset == 8


def test_truncated_archive(sample, tmp_path):
    data = sample.read_bytes()
    path = tmp_path / "cut.saa"
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(CorruptLogError):
        list(open_scenario_architect(path).frames())


def test_unknown_plan_rejected(sample):
    with pytest.raises(UnsupportedFormatError):
        open_scenario_architect(sample, plan="optimal")


@pytest.mark.external
def test_external_logs_have_the_documented_labels(external_dir):
    path = external_dir / "trajectory_supervisor" / "modena_T1_cutin_collision.saa"
    drive = open_scenario_architect(path)
    frames = list(drive.frames())
    assert len(frames) == 106
    unsafe = [round(f.t_ns / 1e9, 1) for f in frames if f.extras["labels"]["safety_dyn"] is False]
    assert unsafe[0] == 6.4
    assert unsafe[-1] == 7.3
    left, right = drive.lane_map.boundaries_m
    assert (len(left), len(right)) == (101, 101)  # the notes said 101/100; the file has 101/101
    assert "ggv" in drive.csv_members
