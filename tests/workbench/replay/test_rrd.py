"""Write an .rrd from a fake drive and read it back without a viewer."""

import contextlib
import socket
import subprocess
import sys
import time
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import rerun as rr
from rerun.chunk import RrdReader

from loaders import open_drive
from loaders.errors import CorruptLogError
from tests.workbench.fakes import T0_NS, FakeDrive
from workbench.viewer import ReplayError, replay_drive


def _store(path: Path) -> Any:
    return RrdReader(path).store().stream().collect()


def _rows(store: Any, entity: str) -> Any:
    return store.reader(index="frame", contents=entity).to_arrow_table()


def test_replay_writes_entities_timelines_and_properties(tmp_path):
    out = tmp_path / "sub" / "drive.rrd"
    summary = replay_drive(FakeDrive(n_frames=23, n_actors=4), out=out, send_frames=10)
    assert out.is_file()
    assert (summary.frames, summary.actors_seen) == (23, 4)
    assert summary.duration_s == pytest.approx(2.2)
    assert summary.output == str(out)

    store = _store(out)
    for entity in (
        "/world/ego",
        "/world/ego/trail",
        "/world/ego/plan",
        "/world/actors",
        "/world/actors/velocity",
        "/plots/ego/speed_mps",
        "/plots/ego/accel_mps2",
        "/plots/actors/count",
        "/plots/actors/min_distance_m",
    ):
        table = _rows(store, entity)
        assert table.num_rows == 23, entity
        assert sorted(table.column("frame").to_pylist()) == list(range(23))

    actors = _rows(store, "/world/actors").to_pydict()
    # actors are labelled by the drive's short label (numbered as they appear), full id beside
    assert actors["/world/actors:Boxes3D:labels"][0] == ["#1", "#2", "#3", "#4"]
    assert actors["/world/actors:object_id"][0] == ["car0", "car1", "car2", "car3"]
    stamps = _rows(store, "/world/ego").column("log_time").cast("int64").to_numpy()
    np.testing.assert_array_equal(np.sort(stamps), T0_NS + np.arange(23) * 100_000_000)

    static = store.reader(index=None, contents="/world/**").to_arrow_table().column_names
    assert "/world/map/borders/solid:LineStrips3D:strips" in static
    assert "/world/map/centre/road:LineStrips3D:strips" in static
    assert "/world:AnnotationContext:context" in static
    assert "/world:ViewCoordinates:xyz" in static

    props = store.reader(index=None, contents="/__properties/**").to_arrow_table().to_pydict()
    assert props["property:drive:format"] == [["fake"]]
    assert props["property:drive:frame_count"] == [[23]]
    assert props["property:drive:ego_topic"] == [["/ego/odom"]]
    assert props["property:RecordingInfo:name"] == [["fake_drive.mcap (fake)"]]
    assert props["property:RecordingInfo:start_time"] == [[T0_NS]]
    assert props["property:software:rss_workbench"] == [[metadata.version("rss-workbench")]]
    assert props["property:software:rerun_sdk"] == [[rr.__version__]]
    assert props["property:software:engines"] == [["none"]]  # no engine ran


def test_no_wall_clock_timeline_and_a_default_blueprint(tmp_path):
    out = tmp_path / "d.rrd"
    replay_drive(FakeDrive(n_frames=3), out=out)
    reader = RrdReader(out)
    assert len(reader.blueprints()) == 1
    stamps = _rows(_store(out), "/world/ego").column("log_time").cast("int64").to_pylist()
    assert min(stamps) >= T0_NS  # drive time, not the time the replay ran
    assert max(stamps) < T0_NS + 10**9


def test_time_window_and_drive_without_map_or_actors(tmp_path):
    out = tmp_path / "w.rrd"
    drive = FakeDrive(n_frames=40, n_actors=0, with_map=False)
    summary = replay_drive(drive, out=out, start_ns=T0_NS + 10**9, end_ns=T0_NS + 2 * 10**9)
    assert summary.frames == 10
    assert summary.actors_seen == 0
    store = _store(out)
    assert _rows(store, "/world/ego").num_rows == 10
    names = store.reader(index=None, contents="/world/**").to_arrow_table().column_names
    assert not any(name.startswith("/world/map") for name in names)


def test_exactly_one_destination(tmp_path):
    with pytest.raises(ReplayError, match="exactly one"):
        replay_drive(FakeDrive(n_frames=1), out=tmp_path / "x.rrd", spawn=True)
    with pytest.raises(ReplayError, match="exactly one"):
        replay_drive(FakeDrive(n_frames=1))


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _listeners(port: int) -> set[str]:
    """Local addresses (hex, as in /proc/net/tcp*) listening on ``port``."""
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        with contextlib.suppress(OSError), Path(table).open() as fh:
            for line in fh.readlines()[1:]:
                fields = line.split()
                addr, port_hex = fields[1].rsplit(":", 1)
                if int(port_hex, 16) == port and fields[3] == "0A":  # 0A = LISTEN
                    found.add(addr)
    return found


def test_serve_binds_grpc_and_web_viewer_to_localhost_only():
    grpc_port, web_port = _free_port(), _free_port()
    seen: list[str] = []
    bound: dict[int, set[str]] = {}

    def served(url: str) -> None:
        seen.append(url)
        bound.update({port: _listeners(port) for port in (grpc_port, web_port)})

    summary = replay_drive(
        FakeDrive(n_frames=5), serve=True, ports=(grpc_port, web_port), on_served=served
    )
    assert seen == [summary.output]
    assert f"rerun+http://127.0.0.1:{grpc_port}/proxy" in summary.output
    assert summary.output.startswith(f"http://127.0.0.1:{web_port}/")
    loopback = "0100007F"  # 127.0.0.1 in /proc/net/tcp byte order
    assert bound == {grpc_port: {loopback}, web_port: {loopback}}
    assert _listeners(grpc_port) == set(), "the server must stop with the replay"


def test_truncated_log_keeps_the_readable_frames_in_the_rrd(tmp_path):
    sample = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"
    cut = tmp_path / "cut.mcap"
    data = sample.read_bytes()
    cut.write_bytes(data[: len(data) // 2])
    out = tmp_path / "cut.rrd"
    drive = open_drive(cut)
    try:
        summary = replay_drive(drive, out=out, send_frames=100)
    finally:
        drive.close()
    assert isinstance(summary.stopped_by, CorruptLogError)
    assert summary.frames > 100
    rows = _rows(_store(out), "/world/ego")
    assert rows.num_rows == summary.frames


@pytest.mark.skipif(sys.platform != "linux", reason="the parent-death signal is Linux's prctl")
def test_a_killed_replay_takes_its_served_viewer_with_it(tmp_path):
    # SIGKILL leaves no chance to clean up: the kernel's parent-death signal stops the server
    grpc_port, web_port = _free_port(), _free_port()
    sample = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"
    cmd = [sys.executable, "-c", "from workbench.cli.main import main; main()", "replay"]
    cmd += [str(sample), "--end", "1", "--serve"]
    cmd += ["--grpc-port", str(grpc_port), "--web-port", str(web_port)]
    replay = subprocess.Popen(  # noqa: S603 - this interpreter, fixed arguments
        cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, cwd=tmp_path, text=True
    )
    try:
        assert replay.stdout is not None
        for line in replay.stdout:  # the URL is printed once the server listens
            if "press Ctrl-C" in line:
                break
        assert _listeners(grpc_port), "the server should be listening"
        replay.kill()
        replay.wait()
        deadline = time.monotonic() + 10.0
        while _listeners(grpc_port) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _listeners(grpc_port) == set(), "the viewer outlived the killed replay"
    finally:
        replay.kill()
