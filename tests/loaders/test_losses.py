"""Nothing lost without a word: dropped messages are counted, ``info`` and ``evaluate`` agree.

Also the CLI side of damaged files: ``info`` fails (exit 2, one line) on a damaged chunk and
``replay`` leaves no ``.rrd`` behind when no frame could be read.
"""

from __future__ import annotations

import dataclasses
import shutil
from contextlib import closing
from pathlib import Path

import pytest
from typer.testing import CliRunner

from loaders import open_drive
from loaders.losses import count_frames, loss_details, loss_summary
from tests.loaders.fixtures import ODOM, ros_entries, write_ros1_bag
from workbench.cli.main import app, main

SAMPLES = Path(__file__).resolve().parents[2] / "sample_logs"
runner = CliRunner()


@pytest.fixture(scope="module")
def repeated_times(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The synthetic ROS 1 drive with 3 ego messages logged at their predecessor's time."""
    entries = ros_entries(1, ODOM, "derived_object_msgs/msg/ObjectArray", None)
    ego = [k for k, e in enumerate(entries) if e.topic == "/ego/odometry"]
    for k in ego[5:20:5]:
        previous = max(j for j in ego if j < k)
        entries[k] = dataclasses.replace(entries[k], t_ns=entries[previous].t_ns)
    path = tmp_path_factory.mktemp("losses") / "repeated.bag"
    return write_ros1_bag(path, sorted(entries, key=lambda e: e.t_ns))


def test_repeated_ego_times_are_counted_and_count_frames_is_exact(repeated_times: Path) -> None:
    with closing(open_drive(repeated_times)) as drive:
        counted = count_frames(drive)
        assert drive.info.notes["skipped_out_of_order_ego"] == "3"
        frames = list(drive.frames())
        assert counted == len(frames) == drive.info.frame_count - 3
        notes = drive.info.notes
    assert loss_summary(notes) == (
        "not in any frame: 3 ego messages dropped; 3 object messages used by no frame "
        "(details: --verbose)"
    )
    assert loss_details(notes)[0].startswith("ego messages dropped: 3 (time not after")
    assert loss_summary({}) is None


def test_info_and_evaluate_agree_and_say_what_was_dropped(repeated_times: Path) -> None:
    info = runner.invoke(app, ["info", str(repeated_times)])
    assert info.exit_code == 0, info.output
    assert "frames      27 (of 30 ego messages)" in info.output
    assert "not in any frame: 3 ego messages dropped" in info.output
    evaluated = runner.invoke(app, ["evaluate", str(repeated_times), "--engines", "rss"])
    assert evaluated.exit_code == 0, evaluated.output
    assert "27 frames evaluated" in evaluated.output
    assert "not in any frame: 3 ego messages dropped" in evaluated.output
    verbose = runner.invoke(app, ["info", str(repeated_times), "--verbose"])
    assert "lost: ego messages dropped: 3 (time not after" in verbose.output


def test_info_fails_on_a_damaged_mcap_chunk(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "damaged.mcap"
    data = bytearray((SAMPLES / "highway_cut_in.mcap").read_bytes())
    data[17635 + 6000 : 17635 + 6064] = bytes(range(64))  # inside the second zstd chunk
    path.write_bytes(bytes(data))
    with pytest.raises(SystemExit) as info:
        main(["info", str(path)])
    assert info.value.code == 2
    captured = capsys.readouterr()
    assert "frames" in captured.out
    err = captured.err.strip()
    assert err.startswith(f"error: {path}")
    assert "t=" in err
    assert len(err.splitlines()) == 1


def test_replay_of_an_unreadable_drive_leaves_no_rrd(tmp_path: Path) -> None:
    bag = tmp_path / "zeroed.bag"
    shutil.copy(SAMPLES / "highway_cut_in.bag", bag)
    data = bytearray(bag.read_bytes())
    middle = len(data) // 2
    data[middle : middle + 4096] = bytes(4096)  # inside the only LZ4 chunk
    bag.write_bytes(bytes(data))
    out = tmp_path / "out.rrd"
    result = runner.invoke(app, ["replay", str(bag), "--out", str(out)])
    assert result.exit_code != 0
    assert "0 frames" in result.output
    assert "wrote" not in result.output
    assert not out.exists()
