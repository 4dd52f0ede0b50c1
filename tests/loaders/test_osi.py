"""ASAM OSI ground truth (MCAP and ``.osi`` traces) read into the sample's frames and verdicts.

The ``highway_cut_in`` frames written as OSI GroundTruth / SensorView (``osi_logs``) must
read back into the same frames: times, ego pose (1e-9 m, 1e-9 rad), ego speed, yaw rate and
acceleration (1e-9), and actors (ids, classes, poses, velocities, sizes: 1e-9). The RSS
verdicts of the first 150 frames (``workbench evaluate --per-frame``) must equal those of
the original sample, up to the ``match_dt`` of the rows (OSI objects are at the frame time).
"""

from __future__ import annotations

import json
import struct
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING, Any

import betterosi
import numpy as np
import pytest
from typer.testing import CliRunner

from loaders import open_drive
from loaders.errors import CorruptLogError, UnsupportedFormatError
from tests.loaders.ego_logs import reference_frames
from tests.loaders.osi_logs import HOST_ID, VARIANTS, write_osi
from workbench.cli.main import app

if TYPE_CHECKING:
    from loaders.records import Frame

ROOT = Path(__file__).resolve().parents[2]
SOURCE = ROOT / "sample_logs" / "highway_cut_in.mcap"
TOL = 1e-9
VERDICT_FRAMES = 150
_ACTOR_FIELDS = ("x_m", "y_m", "z_m", "yaw_rad", "vx_mps", "vy_mps", "length_m", "width_m")

pytestmark = pytest.mark.skipif(not SOURCE.is_file(), reason="sample log not generated")


@pytest.fixture(scope="module")
def reference() -> list[Frame]:
    return reference_frames(ROOT)


def _frames(path: Path, **kwargs: Any) -> list[Frame]:
    with closing(open_drive(path, **kwargs)) as drive:
        return list(drive.frames())


@pytest.mark.parametrize("variant", VARIANTS)
def test_osi_reads_into_the_sample_frames(
    variant: str, reference: list[Frame], tmp_path: Path
) -> None:
    path = write_osi(reference, tmp_path, variant)
    with closing(open_drive(path)) as drive:
        info = drive.info
        frames = list(drive.frames())
    assert info.source_format == ("osi-trace" if path.suffix == ".osi" else "mcap-protobuf")
    assert info.roles.objects == (info.roles.ego,)
    assert [t.role for t in info.topics] == ["ego+objects"]
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference]
    for new, old in zip(frames, reference, strict=True):
        for name in ("x_m", "y_m", "z_m", "yaw_rad", "speed_mps", "yaw_rate_radps", "accel_mps2"):
            assert getattr(new.ego, name) == pytest.approx(getattr(old.ego, name), abs=TOL), name
        a, b = new.actors, old.actors
        assert list(a.ids) == list(b.ids)  # the host vehicle is the ego, not an actor
        assert (a.object_class == b.object_class).all()
        assert (a.match_dt_ns == 0).all()
        for name in _ACTOR_FIELDS:
            np.testing.assert_allclose(getattr(a, name), getattr(b, name), atol=TOL)
    assert str(HOST_ID) not in {i for f in frames for i in f.actors.ids}


def _verdicts(path: Path, out: Path, *extra: str) -> list[dict[str, Any]]:
    args = ["evaluate", str(path), "--engines", "rss", "--end", str(VERDICT_FRAMES / 20)]
    result = CliRunner().invoke(app, [*args, *extra, "--per-frame", str(out)])
    assert result.exit_code == 0, result.output
    return [json.loads(line)["rss"] for line in out.read_text().splitlines()]


@pytest.mark.parametrize("variant", ["gt_osi", "sv_mcap"])
def test_osi_gives_the_sample_rss_verdicts(
    variant: str, reference: list[Frame], tmp_path: Path
) -> None:
    want = _verdicts(SOURCE, tmp_path / "original.jsonl")
    path = write_osi(reference, tmp_path, variant)
    # the sample's lane map (OSI lanes are not read): --map
    got = _verdicts(path, tmp_path / "osi.jsonl", "--map", str(SOURCE.with_suffix(".osm")))
    assert len(got) == len(want) == VERDICT_FRAMES
    assert got == want
    assert any(not r["is_safe"] for r in want)  # the comparison covers unsafe frames


def test_trace_without_naming_convention_is_refused(reference: list[Frame], tmp_path: Path) -> None:
    path = write_osi(reference[:3], tmp_path, "gt_osi")
    plain = path.rename(tmp_path / "drive.osi")
    with pytest.raises(UnsupportedFormatError, match="naming convention"):
        open_drive(plain)


def test_truncated_trace_keeps_the_frames_before_the_break(
    reference: list[Frame], tmp_path: Path
) -> None:
    path = write_osi(reference[:20], tmp_path, "gt_osi")
    data = path.read_bytes()
    path.write_bytes(data[: len(data) - 10])
    frames: list[Frame] = []
    with pytest.raises(CorruptLogError) as err, closing(open_drive(path)) as drive:
        frames.extend(drive.frames())
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference[:19]]
    assert err.value.offset is not None
    assert "\n" not in str(err.value)


def test_ground_truth_without_host_vehicle_fails_typed(tmp_path: Path) -> None:
    gt = betterosi.GroundTruth(timestamp=betterosi.Timestamp(seconds=1, nanos=0))
    path = tmp_path / "20240101T000000Z_gt_3.8.0_7.0.0_2_nohost.osi"
    data = gt.to_binary()
    path.write_bytes((struct.pack("<I", len(data)) + data) * 2)
    with pytest.raises(CorruptLogError, match="host_vehicle_id"), closing(open_drive(path)) as d:
        list(d.frames())


def test_host_vehicle_dimension_is_the_ego_size(reference: list[Frame], tmp_path: Path) -> None:
    path = write_osi(reference[:5], tmp_path, "gt_osi")
    data = path.read_bytes()
    out, offset = b"", 0
    while offset < len(data):  # every record: the host vehicle 5.0 x 2.2 x 1.8 m
        (length,) = struct.unpack("<I", data[offset : offset + 4])
        gt = betterosi.GroundTruth.from_binary(data[offset + 4 : offset + 4 + length])
        host = next(o for o in gt.moving_object if o.id.value == HOST_ID)
        host.base.dimension = betterosi.Dimension3d(length=5.0, width=2.2, height=1.8)
        body = gt.to_binary()
        out += struct.pack("<I", len(body)) + body
        offset += 4 + length
    path.write_bytes(out)
    frames = _frames(path)
    assert len(frames) == 5
    assert {(f.ego.length_m, f.ego.width_m, f.ego.height_m) for f in frames} == {(5.0, 2.2, 1.8)}
