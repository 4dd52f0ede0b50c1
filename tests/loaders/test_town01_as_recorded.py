"""The Town01 regression drives read as recorded (issue 27).

Both drives log each stamp's ``/carla/objects`` message *after* the ``/ego/odom`` message
of the same stamp (equal log times and header stamps). Every frame takes its own stamp's
objects all the same (docs/loaders.md, "Same stamp, any order"), so the README command of
``../shared/conformance/town01_regressions`` (``evaluate`` in the compatibility mode)
agrees with the reference on every frame, frame 0 included (49 / 50 on drive_004 when
frame 0 had no objects).
"""

from __future__ import annotations

import json
from contextlib import closing
from typing import TYPE_CHECKING, Any

import pytest
from mcap.reader import make_reader

from loaders import open_drive
from loaders.typestore import typestore
from tests.workbench.cli_runs import run_workbench

if TYPE_CHECKING:
    from pathlib import Path

DRIVES = ("drive_004", "drive_005")


def _recorded(path: Path) -> tuple[list[str], dict[int, set[str]]]:
    """Topics in file order, and the object ids of each objects message by header stamp."""
    store = typestore(2)
    order, objects = [], {}
    with path.open("rb") as f:
        for schema, channel, message in make_reader(f).iter_messages(log_time_order=False):
            order.append(channel.topic)
            if channel.topic == "/carla/objects":
                assert schema is not None
                msg: Any = store.deserialize_cdr(message.data, schema.name)
                stamp_ns = msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec
                assert stamp_ns == message.log_time
                objects[stamp_ns] = {str(o.id) for o in msg.objects}
    return order, objects


@pytest.mark.parametrize("name", DRIVES)
def test_every_frame_takes_its_own_stamps_objects(town01_regressions: Path, name: str) -> None:
    order, objects = _recorded(town01_regressions / f"{name}.mcap")
    # as recorded: each stamp's ego message, then its objects message
    assert order == ["/ego/odom", "/carla/objects"] * 50
    with closing(open_drive(town01_regressions / f"{name}.mcap")) as drive:
        frames = list(drive.frames())
        notes = drive.info.notes
    assert [f.t_ns for f in frames] == sorted(objects)
    for frame in frames:
        assert set(map(str, frame.actors.ids)) == objects[frame.t_ns]
        assert (frame.actors.match_dt_ns == 0).all()
    assert objects[frames[0].t_ns]  # frame 0 has its objects
    assert "unused_object_messages" not in notes


@pytest.mark.parametrize("name", DRIVES)
def test_readme_command_agrees_with_the_reference_on_every_frame(
    town01_regressions: Path, external_dir: Path, name: str, tmp_path: Path
) -> None:
    out = tmp_path / "out.jsonl"
    args = [
        "evaluate",
        str(town01_regressions / f"{name}.mcap"),
        *("--map", str(external_dir / "maps" / "Town01.xodr")),
        *("--engines", "rss"),
        *("--rss-params", str(town01_regressions / "rss_params_compat.toml")),
        *("--per-frame", str(out)),
    ]
    assert run_workbench(args) == 0
    ours = [json.loads(line) for line in out.read_text().splitlines()]
    reference = json.loads((town01_regressions / f"{name}.json").read_text())["frames"]
    assert len(ours) == len(reference) == 50
    got = [(o["t_ns"], o["rss"]["is_safe"], sorted(o["rss"]["dangerous_objects"])) for o in ours]
    want = [
        (r["t_ns"], r["is_safe"], sorted(str(d) for d in r["dangerous_objects"])) for r in reference
    ]
    assert got == want
    assert any(not r["is_safe"] for r in reference)  # the comparison covers dangers
