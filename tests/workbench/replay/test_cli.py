"""CLI tests for ``workbench replay`` and ``workbench demo`` against a fake ``open_drive``."""

from pathlib import Path

import pytest
from rerun.chunk import RrdReader
from typer.testing import CliRunner

import loaders
from loaders.errors import UnsupportedFormatError
from tests.workbench.fakes import FakeDrive
from workbench.cli.main import app, main
from workbench.demo import find_sample_logs, output_names, primary_logs

runner = CliRunner()


@pytest.fixture
def opened(monkeypatch):
    """Replace ``loaders.open_drive`` with one returning fake drives; record the calls."""
    calls = []

    def fake_open_drive(path, *, map=None, profile=None, ego_id=None, ego_topic=None):  # noqa: A002
        calls.append(
            {
                "path": Path(path),
                "map": map,
                "profile": profile,
                "ego_id": ego_id,
                "ego_topic": ego_topic,
            }
        )
        if Path(path).name.startswith("broken"):
            raise UnsupportedFormatError(path, "not a drive")
        return FakeDrive(n_frames=12, n_actors=2, path=Path(path))

    monkeypatch.setattr(loaders, "open_drive", fake_open_drive, raising=False)
    return calls


def _log(tmp_path: Path, name: str = "drive.mcap") -> Path:
    path = tmp_path / name
    path.write_bytes(b"")
    return path


def test_replay_writes_default_output_and_says_how_to_open(tmp_path, monkeypatch, opened):
    log = _log(tmp_path)
    monkeypatch.chdir(tmp_path)
    args = ["replay", str(log), "--ego-id", "7", "--map", "m.osm", "--ego-topic", "/tf"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    expected = Path("out") / "drive.rrd"
    assert (tmp_path / expected).is_file()
    assert f"wrote {expected}" in result.output
    assert f"rerun {expected}" in result.output
    assert "12 frames, 2 actors" in result.output
    assert opened[0]["ego_id"] == "7"
    assert opened[0]["ego_topic"] == "/tf"
    assert opened[0]["map"] == Path("m.osm")


def test_replay_out_and_time_window(tmp_path, opened):
    log = _log(tmp_path)
    out = tmp_path / "x" / "y.rrd"
    result = runner.invoke(app, ["replay", str(log), "--out", str(out), "--start", "0.3"])
    assert result.exit_code == 0, result.output
    assert f"wrote {out}" in result.output
    store = RrdReader(out).store().stream().collect()
    assert store.reader(index="frame", contents="/world/ego").to_arrow_table().num_rows == 9


def test_nonexistent_log_is_one_line_exit_2(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["replay", str(tmp_path / "missing.mcap")])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0
    assert "missing.mcap: no such file or directory" in err


def test_conflicting_destinations_exit_2(tmp_path, capsys, opened):
    log = _log(tmp_path)
    with pytest.raises(SystemExit) as exc:
        main(["replay", str(log), "--spawn", "--out", str(tmp_path / "a.rrd")])
    assert exc.value.code == 2
    assert "mutually exclusive" in capsys.readouterr().err


def test_loader_error_is_one_line_exit_2(tmp_path, capsys, opened):
    log = _log(tmp_path, "broken.bag")
    with pytest.raises(SystemExit) as exc:
        main(["replay", str(log)])
    assert exc.value.code == 2
    assert "not a drive" in capsys.readouterr().err


def test_find_sample_logs_picks_drives_only(tmp_path):
    for name in ("b.mcap", "a.bag", "c.xml", "notes.txt", "c.expected.json"):
        _log(tmp_path, name)
    (tmp_path / "bag2").mkdir()
    (tmp_path / "bag2" / "metadata.yaml").write_text("rosbag2_bagfile_information: {}\n")
    (tmp_path / "other_dir").mkdir()
    assert [p.name for p in find_sample_logs(tmp_path)] == ["a.bag", "b.mcap", "bag2", "c.xml"]


def test_demo_replays_every_log_and_reports_failures(tmp_path, opened):
    samples = tmp_path / "samples"
    samples.mkdir()
    _log(samples, "one.mcap")
    _log(samples, "broken.bag")
    (samples / "two").mkdir()
    (samples / "two" / "metadata.yaml").write_text("x: 1\n")
    out = tmp_path / "demo"
    result = runner.invoke(app, ["demo", str(samples), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in out.iterdir()) == ["one.rrd", "two.rrd"]
    assert "failed" in result.output
    assert "not a drive" in result.output
    assert f"rerun {out / 'one.rrd'}" in result.output
    assert "2 of 3 logs" in result.output


def test_demo_output_names_never_collide():
    logs = [Path("s/a.bag"), Path("s/a.mcap"), Path("s/a.xml"), Path("s/b.bag")]
    names = output_names(logs)
    assert names[Path("s/a.mcap")] == "a.rrd"
    assert names[Path("s/a.bag")] == "a_bag.rrd"
    assert names[Path("s/a.xml")] == "a_xml.rrd"
    assert names[Path("s/b.bag")] == "b.rrd"


def test_demo_without_logs_is_an_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["demo", str(tmp_path), "--out", str(tmp_path / "o")])
    assert exc.value.code == 2
    assert "no .mcap" in capsys.readouterr().err


def test_demo_evaluates_one_log_per_drive():
    logs = [
        Path("d/a.bag"),
        Path("d/a.mcap"),
        Path("d/a_rosbag2"),
        Path("d/b.bag"),
        Path("d/b_rosbag2"),
        Path("d/c.xml"),
    ]
    assert primary_logs(logs) == {Path("d/a.mcap"), Path("d/b_rosbag2"), Path("d/c.xml")}
