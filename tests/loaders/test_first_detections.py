"""First detections of object types without velocity: forward difference, never a silent 0.

A 20 Hz ego and a 10 Hz box topic whose message of a stamp comes *after* the ego message of
the same stamp (as in the sample logs): a frame's first detection only gets its next
message two ego messages later. The assembler holds the frame until then.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders.drive import TopicRoles
from loaders.message_logs.assemble import MAX_HELD, AssemblyOptions, FrameAssembler
from loaders.message_logs.samples import EgoSample, ObjectColumns

if TYPE_CHECKING:
    from loaders.records import Frame

T0 = 1_000_000_000_000
EGO_DT = 50_000_000
OBJ_DT = 100_000_000
#: Car "a" drives at 8 m/s along x from the start; car "b" appears at 0.3 s at 3 m/s along
#: y; car "c" is in one message only (0.9 s).
VX_A, VY_B = 8.0, 3.0


def _boxes(t_ns: int, rows: dict[str, tuple[float, float]]) -> ObjectColumns:
    n = len(rows)
    return ObjectColumns(
        stamp_ns=t_ns,
        ids=list(rows),
        object_class=np.zeros(n, dtype=np.int8),
        x_m=np.array([p[0] for p in rows.values()]),
        y_m=np.array([p[1] for p in rows.values()]),
        z_m=np.zeros(n),
        yaw_rad=np.zeros(n),
        vx_mps=np.full(n, np.nan),
        vy_mps=np.full(n, np.nan),
        length_m=np.full(n, 4.5),
        width_m=np.full(n, 1.9),
        height_m=np.full(n, 1.5),
        has_velocity=False,
    )


def _objects_at(t_ns: int, end_ns: int) -> dict[str, tuple[float, float]]:
    s = (t_ns - T0) / 1e9
    rows = {"a": (10.0 + VX_A * s, 0.0)}
    if t_ns >= T0 + 300_000_000:
        rows["b"] = (30.0, VY_B * (s - 0.3))
    if t_ns == end_ns - OBJ_DT:
        rows["c"] = (50.0, 0.0)  # in one message only
    return rows


def _stream(end_ns: int) -> list[tuple[str, int, object]]:
    out: list[tuple[str, int, object]] = []
    for t in range(T0, end_ns + 1, EGO_DT):
        out.append(("/ego", t, EgoSample(t, 0.0, 0.0, 0.0, 0.0, speed_mps=0.0)))
        if (t - T0) % OBJ_DT == 0:  # after the ego message of the same stamp
            out.append(("/boxes", t, _boxes(t, _objects_at(t, end_ns))))
    return out


def _assemble(end_ns: int) -> tuple[list[Frame], FrameAssembler]:
    roles = TopicRoles(ego="/ego", objects=("/boxes",))
    decoders = {"/ego": lambda m: m, "/boxes": lambda m: m}
    assembler = FrameAssembler(Path("synthetic.mcap"), roles, decoders, AssemblyOptions())
    return list(assembler.run(_stream(end_ns))), assembler


def test_first_detection_takes_the_forward_difference():
    frames, assembler = _assemble(T0 + 1_000_000_000)
    assert len(frames) == 21
    assert [f.index for f in frames] == list(range(21))
    assert len(frames[0].actors) == 0  # the 0 s boxes come after the 0 s ego message
    first = frames[1]  # 0.05 s: takes the 0 s message, where every car is new
    assert list(first.actors.ids) == ["a"]
    assert first.actors.vx_mps[0] == pytest.approx(VX_A)
    # extrapolated over its 50 ms match age like every row
    assert first.actors.x_m[0] == pytest.approx(10.0 + VX_A * 0.05)
    # car b from its first frames on (0.35 s and 0.4 s take the 0.3 s message, which comes
    # after the 0.3 s ego message)
    assert "b" not in frames[6].actors.ids
    for k in (7, 8):
        b = list(frames[k].actors.ids).index("b")
        assert frames[k].actors.vy_mps[b] == pytest.approx(VY_B)
        assert frames[k].actors.vx_mps[b] == pytest.approx(0.0)
    # every row of a and b has its true velocity; c, in one message (two frames), is counted
    for f in frames:
        for k, oid in enumerate(f.actors.ids):
            want = {"a": (VX_A, 0.0), "b": (0.0, VY_B), "c": (0.0, 0.0)}[str(oid)]
            assert (f.actors.vx_mps[k], f.actors.vy_mps[k]) == pytest.approx(want)
    assert [f.index for f in frames if "c" in f.actors.ids] == [19, 20]
    assert assembler.first_detections_at_rest == 2


def test_a_topic_that_stops_holds_no_more_than_max_held_frames():
    # the box topic publishes once, then falls silent: the frames are not held for ever
    roles = TopicRoles(ego="/ego", objects=("/boxes",))
    decoders = {"/ego": lambda m: m, "/boxes": lambda m: m}
    assembler = FrameAssembler(Path("synthetic.mcap"), roles, decoders, AssemblyOptions())
    stream: list[tuple[str, int, object]] = [("/boxes", T0, _boxes(T0, {"a": (0.0, 0.0)}))]
    stream += [
        ("/ego", t, EgoSample(t, 0.0, 0.0, 0.0, 0.0, speed_mps=0.0))
        for t in range(T0, T0 + (MAX_HELD + 10) * EGO_DT, EGO_DT)
    ]
    seen = 0
    for k, (_, frame) in enumerate(zip(range(10), assembler.run(stream), strict=False)):
        assert frame.index == k
        seen += 1
    assert seen == 10
