"""``workbench info``: the summary table and the one-line error for a bad file."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from workbench.cli.main import app, main


def test_info_prints_topics_roles_and_clock(drive_files):
    result = CliRunner().invoke(app, ["info", str(drive_files["ros1-bag"])])
    assert result.exit_code == 0, result.output
    out = result.output
    assert "ros1-bag" in out
    assert "frames      30" in out
    assert "/ego/odometry" in out
    assert "nav_msgs/Odometry" in out
    assert "objects" in out
    assert "log_time, match tolerance 0.150 s" in out
    assert "map         none" in out


def test_info_bad_file_is_one_line_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(b"not an mcap at all")
    with pytest.raises(SystemExit) as info:
        main(["info", str(bad)])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ")
    assert str(bad) in err
    assert len(err.splitlines()) == 1


def test_info_missing_file_exit_2(tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        main(["info", str(tmp_path / "nope.bag")])
    assert info.value.code == 2
    assert "no such file" in capsys.readouterr().err
