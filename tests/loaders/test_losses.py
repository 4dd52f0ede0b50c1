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


def _frames_line(output: str) -> str:
    return next(line for line in output.splitlines() if line.startswith("frames"))


def test_ros1_bag_with_a_tf_ego_info_and_evaluate_agree(tmp_path: Path) -> None:
    """The sample's ego as /tf in a ROS 1 bag: half the /tf messages move the lidar only."""
    from tests.loaders.ego_logs import reference_frames, write_variant  # noqa: PLC0415

    root = SAMPLES.parent
    bag = write_variant(root, tmp_path, "tf", storage="bag")
    reference = reference_frames(root)
    with closing(open_drive(bag)) as drive:
        assert drive.info.source_format == "ros1-bag"
        counted = count_frames(drive)
        frames = list(drive.frames())
        notes = drive.info.notes
        tf_messages = drive.info.frame_count
    assert counted == len(frames) == len(reference)
    assert [f.t_ns for f in frames] == [f.t_ns for f in reference]
    for new, old in zip(frames, reference, strict=True):
        assert (new.ego.x_m, new.ego.y_m) == pytest.approx((old.ego.x_m, old.ego.y_m), abs=1e-6)
    # every /tf message accounted for: a frame, or counted as moving other frames only
    assert int(notes["ego_messages_without_pose"]) == tf_messages - len(frames) == len(frames)
    info = runner.invoke(app, ["info", str(bag)])
    evaluated = runner.invoke(app, ["evaluate", str(bag), "--engines", "rss"])
    assert info.exit_code == evaluated.exit_code == 0, info.output + evaluated.output
    assert _frames_line(info.output) == f"frames      {len(frames)} (of {tf_messages} ego messages)"
    assert f"{len(frames)} frames evaluated" in evaluated.output
    lost = f"{len(frames)} ego-topic messages without an ego pose"
    assert lost in info.output
    assert lost in evaluated.output


def test_ignored_markers_are_counted_and_printed(tmp_path: Path) -> None:
    """Each re-written MarkerArray holds a text and a DELETEALL marker beside the cubes."""
    from tests.loaders.rewrite import rewrite_objects  # noqa: PLC0415

    source = SAMPLES / "highway_cut_in.mcap"
    path = rewrite_objects(source, tmp_path / "markers.mcap", "visualization_msgs/msg/MarkerArray")
    with closing(open_drive(path)) as drive:
        messages = next(t.count for t in drive.info.topics if t.topic == "/objects")
        list(drive.frames())
        notes = dict(drive.info.notes)
    assert notes["ignored_markers"] == str(2 * messages)
    line = f"{2 * messages} markers ignored"
    for command in ("info", "evaluate"):
        extra = ["--engines", "rss"] if command == "evaluate" else []
        result = runner.invoke(app, [command, str(path), *extra])
        assert result.exit_code == 0, result.output
        assert line in result.output, command
    verbose = runner.invoke(app, ["info", str(path), "--verbose"])
    assert f"lost: markers ignored: {2 * messages} (MarkerArray markers other than" in (
        verbose.output
    )
