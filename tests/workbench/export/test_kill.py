"""A kill -9 during an export leaves no file under a final name that does not validate."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader
from rosbags.highlevel import AnyReader

from loaders.message_logs.mapsource import read_map

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
RERUN = Path(sys.executable).parent / "rerun"
#: Kill once the directory holds this many entries (.part files included).
KILL_AFTER = (1, 3, 6, 10)


def _validate(path: Path) -> None:
    name = path.name
    if name.endswith(".mcap"):
        with path.open("rb") as f:
            reader = make_reader(f)
            assert reader.get_summary() is not None, name
            assert sum(1 for _ in reader.iter_messages()) > 0, name
    elif name.endswith(".bag"):
        with AnyReader([path]) as bag:
            assert any(True for _ in bag.messages()), name
    elif name.endswith(".rrd"):
        done = subprocess.run(  # noqa: S603 - the venv's rerun on our own file
            [str(RERUN), "rrd", "verify", str(path)], capture_output=True, check=False
        )
        assert done.returncode == 0, (name, done.stderr)
    elif name.endswith(".json"):
        json.loads(path.read_text(), parse_constant=lambda token: pytest.fail(f"{name}: {token}"))
    elif name.endswith(".osm"):
        assert read_map(path, str(path)).lanes
    elif name.endswith(".csv"):
        assert path.read_text().startswith("stem,")
    else:
        pytest.fail(f"unexpected file {name}")


def _final(out: Path) -> list[Path]:
    return [p for p in out.iterdir() if not p.name.endswith(".part") and ".part." not in p.name]


@pytest.mark.parametrize("log", ["urban_intersection.mcap", "urban_intersection.bag"])
def test_kill_during_export_leaves_only_valid_files(tmp_path: Path, log: str) -> None:
    checked = 0
    for k, after in enumerate(KILL_AFTER):
        out = tmp_path / f"out{k}"
        args = [str(SAMPLES / log), "--all", "--engines", "rss", "--no-thumbnails"]
        args += ["--out", str(out), "--store", str(tmp_path / "l.sqlite")]
        code = "import sys; from workbench.cli.main import main; main(sys.argv[1:])"
        with subprocess.Popen(  # noqa: S603 - our own CLI
            [sys.executable, "-c", code, "export", *args],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        ) as child:
            while child.poll() is None and (not out.is_dir() or len(list(out.iterdir())) < after):
                time.sleep(0.02)
            if child.poll() is None:
                os.kill(child.pid, signal.SIGKILL)
            child.wait()
        for path in _final(out) if out.is_dir() else []:
            _validate(path)
            checked += 1
    assert checked > 0
