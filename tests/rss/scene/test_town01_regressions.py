"""The Town01 regression drives of ``../shared/conformance/town01_regressions`` (issue 27).

Two generated 20 Hz ROS 2 MCAP drives with ad-rss-map-integration 5.0's per-frame verdicts
(``drive_NNN.json``), where scene creation used to miss a vehicle ahead in the ego's own
lane, its route through a junction lane: in ``IncreasedSpeedLimit10`` mode the road area
takes the largest speed limit of its lanes, and ad-map gives a junction lane without a
speed record 50 km/h, where we ignored the lane (docs/rss_scene.md, "Town01 regression
drives"). Checked here in the compatibility mode (the drives' ``rss_params_compat.toml``)
through the workbench's loader and RSS engine, every frame against the reference: same
verdict and the same dangerous objects; in the default mode (the same TOML with the key
off) every object the reference calls dangerous is dangerous for us too.

The drives write each stamp's ``/carla/objects`` message *after* the ``/ego/odom``
message of the same stamp; the loader builds a frame from the object messages logged
before its ego message (docs/loaders.md), so the drive is first rewritten with each
stamp's object message first — the frames the reference saw (otherwise frame 0 has no
objects and later frames take the previous stamp's, extrapolated).
"""

from __future__ import annotations

import dataclasses
import json
from typing import TYPE_CHECKING, Any

import pytest
from mcap.reader import make_reader
from mcap.writer import Writer

from workbench.drives import open_log
from workbench.engines.rss.options import RssOptions, load_params
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    from pathlib import Path

DRIVES = ("drive_004", "drive_005")


def objects_first(src: Path, dst: Path) -> None:
    """Copy the MCAP ``src`` to ``dst``, each stamp's non-ego messages before its ego one."""
    with src.open("rb") as f:
        reader = make_reader(f)
        header, summary = reader.get_header(), reader.get_summary()
        assert summary is not None
        messages = list(reader.iter_messages())
    ego_topics = {c.id for c in summary.channels.values() if c.topic == "/ego/odom"}
    messages.sort(key=lambda m: (m[2].log_time, m[1].id in ego_topics))
    with dst.open("wb") as out:
        writer = Writer(out)
        writer.start(profile=header.profile, library=header.library)
        for schema in summary.schemas.values():
            writer.register_schema(schema.name, schema.encoding, schema.data)
        for channel in summary.channels.values():
            writer.register_channel(
                channel.topic, channel.message_encoding, channel.schema_id, channel.metadata
            )
        for _, channel, message in messages:
            writer.add_message(channel.id, message.log_time, message.data, message.publish_time)
        writer.finish()  # type: ignore[no-untyped-call]


def run_drive(
    town01_regressions: Path, external_dir: Path, name: str, tmp_path: Path, *, compat: bool = True
) -> list[Any]:
    """Our RSS verdicts per frame of one drive (compatibility mode, objects first).

    ``compat=False``: the same TOML with ``reproduce_adrss_5_0_defects`` off (the default
    mode).
    """
    mcap = tmp_path / f"{name}.mcap"
    objects_first(town01_regressions / f"{name}.mcap", mcap)
    drive = open_log(
        mcap, map_path=external_dir / "maps" / "Town01.xodr", profile=None, ego_id=None
    )
    try:
        params = load_params(
            RssOptions(params=town01_regressions / "rss_params_compat.toml"), drive.lane_map
        )
        assert params.scene.reproduce_adrss_5_0_defects
        if not compat:
            scene = dataclasses.replace(params.scene, reproduce_adrss_5_0_defects=False)
            params = dataclasses.replace(params, scene=scene)
        frames = list(drive.frames())
        return RssRunner(drive.lane_map, params).step_many(frames)
    finally:
        drive.close()


@pytest.mark.parametrize("name", DRIVES)
def test_regression_drive_agrees_on_every_frame(
    town01_regressions: Path, external_dir: Path, name: str, tmp_path: Path
) -> None:
    """Every frame: the reference's verdict and dangerous objects (50 / 50 frames)."""
    reference = json.loads((town01_regressions / f"{name}.json").read_text())
    verdicts = run_drive(town01_regressions, external_dir, name, tmp_path)
    assert len(verdicts) == reference["n_frames"] == len(reference["frames"])
    differ = []
    for k, (ours, theirs) in enumerate(zip(verdicts, reference["frames"], strict=True)):
        assert theirs["ok"]
        want = sorted(str(x) for x in theirs["dangerous_objects"])
        if ours.is_safe != theirs["is_safe"] or sorted(ours.culprits) != want:
            differ.append((k, sorted(ours.culprits), want))
    assert differ == []
    assert any(not f["is_safe"] for f in reference["frames"])  # the drive has its danger


@pytest.mark.parametrize("name", DRIVES)
def test_regression_drive_default_mode_misses_no_danger(
    town01_regressions: Path, external_dir: Path, name: str, tmp_path: Path
) -> None:
    """Default mode: every object the reference calls dangerous is dangerous for us too.

    The default mode may be more cautious than ad-rss (a lane without a speed limit is
    unbounded there, not ad-map's 50 km/h), never less.
    """
    reference = json.loads((town01_regressions / f"{name}.json").read_text())
    verdicts = run_drive(town01_regressions, external_dir, name, tmp_path, compat=False)
    missed = [
        (k, sorted(ours.culprits), theirs["dangerous_objects"])
        for k, (ours, theirs) in enumerate(zip(verdicts, reference["frames"], strict=True))
        if not {str(x) for x in theirs["dangerous_objects"]} <= set(ours.culprits)
    ]
    assert missed == []
