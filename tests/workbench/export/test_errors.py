"""``workbench export`` and ``labels export``: what the user got wrong is one line, exit 2."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from tests.workbench.cli_runs import run_workbench

if TYPE_CHECKING:
    import pytest

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = str(SAMPLES / "highway_cut_in.mcap")


def _error(capsys: pytest.CaptureFixture[str], args: list[str]) -> str:
    assert run_workbench(args) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("error: ")
    assert "Traceback" not in lines[0]
    return lines[0]


def test_infinite_margin(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for margin in ("inf", "nan", "1e300", "-1"):
        line = _error(capsys, ["export", LOG, "--all", "--out", str(tmp_path), "--margin", margin])
        assert f"--margin {float(margin)}" in line


def test_unwritable_export_directory(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "file").write_text("")
    out = tmp_path / "file" / "clips"
    store = tmp_path / "labels.sqlite"
    args = ["export", LOG, "--all", "--engines", "rss", "--no-rrd", "--store", str(store)]
    line = _error(capsys, [*args, "--out", str(out)])
    assert str(out) in line


def test_unwritable_openlabel_target(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = str(tmp_path / "labels.sqlite")
    args = ["labels", "export", LOG, "--engines", "rss", "--store", store, "--out"]
    line = _error(capsys, [*args, str(tmp_path)])
    assert f"{tmp_path}: cannot write OpenLABEL" in line
    (tmp_path / "file").write_text("")
    line = _error(capsys, [*args, str(tmp_path / "file" / "labels.json")])
    assert "cannot write OpenLABEL" in line


def test_huge_inputs_are_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = str(tmp_path / "out")
    line = _error(capsys, ["export", LOG, "--window", "1e309:1e310", "--out", out])
    assert "--window 1e309:1e310" in line
    line = _error(capsys, ["export", LOG, "--window", f"#{10**30}:#{10**31}", "--out", out])
    assert "no frame within --window" in line
    store = str(tmp_path / "labels.sqlite")
    label = ["label", LOG, "rss-x", "--verdict", "confirmed", "--engines", "rss"]
    line = _error(capsys, [*label, "--store", store])
    assert "no incident 'rss-x'" in line
    line = _error(capsys, ["export", LOG, "--incident", "x" * 100_000, "--out", out])
    assert "no incident" in line
