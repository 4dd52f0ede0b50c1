"""Egos from /tf, PoseWithCovarianceStamped and NavSatFix (+ Imu) against the sample's Odometry.

Tolerances: poses 1e-6 m / 1e-6 rad (TF, pose with covariance: float64 compositions);
GNSS 1 cm in position (WGS-84 round trip) and 1e-6 rad with IMU heading; heading from the
track 0.02 rad on this drive (the cut-in makes no sharp turns); speeds 0.05 m/s (finite
differences of poses against the Odometry twist).
"""

from __future__ import annotations

import math
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders import open_drive
from loaders.errors import ProfileError
from loaders.profile import load_profile
from tests.loaders.ego_logs import ORIGIN_DEG, reference_frames, write_origin_map, write_variant

if TYPE_CHECKING:
    from loaders.drive import DriveInfo
    from loaders.records import Frame

ROOT = Path(__file__).resolve().parents[2]


def _read(
    path: Path, *, osm: Path | None = None, profile: Path | None = None
) -> tuple[list[Frame], DriveInfo]:
    with closing(open_drive(path, map=osm, profile=profile)) as drive:
        return list(drive.frames()), drive.info


def _poses(frames: list[Frame]) -> np.ndarray:
    return np.array(
        [(f.t_ns, f.ego.x_m, f.ego.y_m, f.ego.yaw_rad, f.ego.speed_mps) for f in frames]
    )


@pytest.fixture(scope="module")
def reference() -> np.ndarray:
    return _poses(reference_frames(ROOT))


@pytest.mark.parametrize(
    ("variant", "tol_m"), [("tf", 1e-6), ("tf_footprint", 1e-6), ("pose_cov", 1e-9)]
)
def test_pose_egos_match_reference(
    tmp_path: Path, reference: np.ndarray, variant: str, tol_m: float
) -> None:
    frames, info = _read(write_variant(ROOT, tmp_path, variant))
    got = _poses(frames)
    assert got.shape == reference.shape
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference_frames(ROOT)]
    np.testing.assert_allclose(got[:, 1:3], reference[:, 1:3], atol=tol_m)
    np.testing.assert_allclose(got[:, 3], reference[:, 3], atol=1e-6)
    np.testing.assert_allclose(got[:, 4], reference[:, 4], atol=0.05)
    assert all(len(f.actors.ids) > 0 for f in frames[1:])
    assert info.roles.ego in {"/tf", "/localization/pose_with_covariance"}


@pytest.mark.parametrize("storage", ["bag", "sqlite3"])
def test_tf_ego_composed_through_a_static_footprint_link(
    tmp_path: Path, reference: np.ndarray, storage: str
) -> None:
    """odom -> base_footprint on /tf, base_footprint -> base_link on /tf_static: a frame each."""
    frames, info = _read(write_variant(ROOT, tmp_path, "tf_footprint", storage=storage))
    assert len(frames) == len(reference)
    np.testing.assert_allclose(_poses(frames)[:, 1:4], reference[:, 1:4], atol=1e-6)
    assert "ego_messages_without_pose" not in info.notes
    assert info.source_format == ("ros1-bag" if storage == "bag" else "rosbag2-sqlite3")


def test_tf_vehicle_frame_from_profile(tmp_path: Path, reference: np.ndarray) -> None:
    bag = write_variant(ROOT, tmp_path, "tf")
    toml = tmp_path / "p.toml"
    toml.write_text('[tf]\nvehicle_frame = "/lidar"\n', encoding="utf-8")
    frames, _ = _read(bag, profile=toml)
    # base_link -> lidar (1.2 m ahead) comes 0.1 ms before each base_link update: the first
    # finds no base_link yet, each later one composes with the previous base_link pose.
    got = _poses(frames)
    assert len(frames) == len(reference) - 1
    times = [f.t_ns for f in reference_frames(ROOT)]
    assert [f.t_ns for f in frames] == [t - 100_000 for t in times[1:]]
    yaw = reference[:-1, 3]
    np.testing.assert_allclose(got[:, 1], reference[:-1, 1] + 1.2 * np.cos(yaw), atol=1e-6)
    np.testing.assert_allclose(got[:, 2], reference[:-1, 2] + 1.2 * np.sin(yaw), atol=1e-6)
    assert load_profile(toml).tf.vehicle_frame == "lidar"


def test_tf_profile_rejects_unknown_keys(tmp_path: Path) -> None:
    toml = tmp_path / "p.toml"
    toml.write_text('[tf]\nbase = "x"\n', encoding="utf-8")
    with pytest.raises(ProfileError, match="unknown keys"):
        load_profile(toml)


def test_gnss_with_imu_lands_on_the_map_origin(tmp_path: Path, reference: np.ndarray) -> None:
    bag = write_variant(ROOT, tmp_path, "gnss")
    osm = write_origin_map(tmp_path / "origin.osm")
    frames, info = _read(bag, osm=osm)
    got = _poses(frames)
    with closing(open_drive(bag, map=osm)) as drive:
        assert drive.lane_map is not None
        assert drive.lane_map.origin_deg == pytest.approx(ORIGIN_DEG)
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference_frames(ROOT)]
    np.testing.assert_allclose(got[:, 1:3], reference[:, 1:3], atol=0.01)
    np.testing.assert_allclose(got[:, 3], reference[:, 3], atol=1e-6)
    np.testing.assert_allclose(got[:, 4], reference[:, 4], atol=0.05)
    assert info.roles.ego == "/gnss/fix"


def test_gnss_without_map_starts_at_the_first_fix(tmp_path: Path, reference: np.ndarray) -> None:
    frames, _ = _read(write_variant(ROOT, tmp_path, "gnss"))
    got = _poses(frames)
    assert got[0, 1:3] == pytest.approx((0.0, 0.0), abs=1e-9)
    np.testing.assert_allclose(
        got[:, 1:3] - got[0, 1:3], reference[:, 1:3] - reference[0, 1:3], atol=0.02
    )


def test_gnss_heading_from_track_without_imu(tmp_path: Path, reference: np.ndarray) -> None:
    osm = write_origin_map(tmp_path / "origin.osm")
    frames, _ = _read(write_variant(ROOT, tmp_path, "gnss_no_imu"), osm=osm)
    got = _poses(frames)
    np.testing.assert_allclose(got[:, 1:3], reference[:, 1:3], atol=0.01)
    yaw_err = np.abs((got[:, 3] - reference[:, 3] + math.pi) % (2 * math.pi) - math.pi)
    assert float(yaw_err.max()) < 0.02
    np.testing.assert_allclose(got[:, 4], reference[:, 4], atol=0.05)


def test_objects_logged_after_later_egos_take_their_stamps_frames_on_the_header_clock(
    tmp_path: Path,
) -> None:
    # the boxes logged 120 ms (2.4 ego periods) after their header stamp: on the header
    # clock every frame still takes the box of its stamp, or the one before, extrapolated
    path = write_variant(ROOT, tmp_path, "pose_cov", latency_ns=120_000_000)
    profile = tmp_path / "header.toml"
    profile.write_text('[frames]\nclock = "header"\n')
    frames, info = _read(path, profile=profile)
    reference = reference_frames(ROOT)
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference]
    for got, want in zip(frames, reference, strict=True):
        assert list(got.actors.ids) == list(want.actors.ids)
        assert list(got.actors.match_dt_ns) == list(want.actors.match_dt_ns)
        np.testing.assert_allclose(got.actors.x_m, want.actors.x_m, atol=1e-9)
        np.testing.assert_allclose(got.actors.y_m, want.actors.y_m, atol=1e-9)
    assert "unused_object_messages" not in info.notes
    # on the log clock the boxes fall between ego messages: no frame has a box of its time
    late, _ = _read(path)
    assert min(int(f.actors.match_dt_ns.min()) for f in late[3:] if len(f.actors)) > 0
