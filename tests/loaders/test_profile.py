"""TOML profiles: parsing, role overrides, header clock and tolerance."""

from __future__ import annotations

from contextlib import closing

import pytest

from loaders import open_drive
from loaders.errors import ProfileError
from loaders.profile import DEFAULT_TOLERANCE_NS, load_profile
from tests.loaders import synthetic as syn


def test_full_profile(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(
        '[topics]\nego = "/a"\nobjects = "/b"\nplan = "/c"\n'
        '[frames]\nclock = "header"\nmatch_tolerance_s = 0.05\ninvalid_ego = "skip"\n'
    )
    profile = load_profile(path)
    assert (profile.ego, profile.objects, profile.plan) == ("/a", ("/b",), "/c")
    assert profile.clock == "header"
    assert profile.match_tolerance_ns == 50_000_000
    assert profile.invalid_ego == "skip"
    assert profile.source == path


def test_empty_profile_keeps_defaults(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text("match_tolerance_s = 0.2\n")
    profile = load_profile(path)
    assert profile.ego is None
    assert profile.objects is None
    assert profile.match_tolerance_ns == 200_000_000
    path.write_text("")
    assert load_profile(path).match_tolerance_ns == DEFAULT_TOLERANCE_NS


@pytest.mark.parametrize(
    "text",
    [
        "[topics\n",
        "[topics]\nego = 3\n",
        "[topics]\nobjects = [1, 2]\n",
        '[frames]\nclock = "gps"\n',
        "[frames]\nmatch_tolerance_s = -1\n",
        '[frames]\nmatch_tolerance_s = "x"\n',
        "[extra]\na = 1\n",
        "topics = 3\n",
    ],
)
def test_malformed_profiles(tmp_path, text):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ProfileError) as info:
        load_profile(path)
    assert str(path) in str(info.value)


def test_missing_profile_file(tmp_path):
    with pytest.raises(ProfileError, match="cannot read"):
        load_profile(tmp_path / "nope.toml")


def test_tolerance_drops_old_objects(drive_files, tmp_path):
    path = tmp_path / "tight.toml"
    path.write_text("[frames]\nmatch_tolerance_s = 0.01\n")  # objects are 20 ms old
    with closing(open_drive(drive_files["ros1-bag"], profile=path)) as drive:
        frames = list(drive.frames())
        assert drive.info.match_tolerance_ns == 10_000_000
    assert all(len(f.actors) == 0 for f in frames)


def test_header_clock(drive_files, tmp_path):
    path = tmp_path / "header.toml"
    path.write_text('[frames]\nclock = "header"\n')
    with closing(open_drive(drive_files["ros2-mcap"], profile=path)) as drive:
        frames = list(drive.frames())
        assert drive.info.clock == "header"
    assert [f.t_ns for f in frames] == syn.ego_times()
    assert (frames[3].actors.match_dt_ns == syn.OBJECT_LEAD_NS).all()


def test_profile_overrides_roles(drive_files, tmp_path):
    path = tmp_path / "roles.toml"
    path.write_text('[topics]\nego = "/ego/odometry"\nobjects = []\n')
    with closing(open_drive(drive_files["ros1-bag"], profile=path)) as drive:
        assert drive.info.roles.objects == ()
        frames = list(drive.frames())
    assert all(len(f.actors) == 0 for f in frames)
