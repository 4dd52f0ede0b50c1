"""First detections of object types without velocity: forward difference, never a silent 0.

A 20 Hz ego and a 10 Hz box topic whose message of a stamp comes *after* the ego message of
the same stamp (as in the sample logs): the frame of that stamp still takes it (it is
completed only at the next ego message), and a frame's first detection only gets its next
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
    # the 0 s boxes come after the 0 s ego message, stamped 0 s: they belong to frame 0
    first = frames[0]  # every car is new in the 0 s message
    assert list(first.actors.ids) == ["a"]
    assert first.actors.match_dt_ns[0] == 0
    assert first.actors.vx_mps[0] == pytest.approx(VX_A)
    assert first.actors.x_m[0] == pytest.approx(10.0)
    # 0.05 s takes the 0 s message, extrapolated over its 50 ms match age like every row
    assert frames[1].actors.match_dt_ns[0] == EGO_DT
    assert frames[1].actors.x_m[0] == pytest.approx(10.0 + VX_A * 0.05)
    # car b from its first frame on (0.3 s takes the 0.3 s message logged after it)
    assert "b" not in frames[5].actors.ids
    for k in (6, 7):
        b = list(frames[k].actors.ids).index("b")
        assert frames[k].actors.vy_mps[b] == pytest.approx(VY_B)
        assert frames[k].actors.vx_mps[b] == pytest.approx(0.0)
    # every row of a and b has its true velocity; c, in one message (two frames), is counted
    for f in frames:
        for k, oid in enumerate(f.actors.ids):
            want = {"a": (VX_A, 0.0), "b": (0.0, VY_B), "c": (0.0, 0.0)}[str(oid)]
            assert (f.actors.vx_mps[k], f.actors.vy_mps[k]) == pytest.approx(want)
    assert [f.index for f in frames if "c" in f.actors.ids] == [18, 19]
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


def _ego(t_ns: int) -> tuple[str, int, object]:
    return ("/ego", t_ns, EgoSample(t_ns, 0.0, 0.0, 0.0, 0.0, speed_mps=0.0))


def _box(t_ns: int, x_m: float, log_ns: int | None = None) -> tuple[str, int, object]:
    cols = _boxes(t_ns, {"a": (x_m, 0.0)})
    object.__setattr__(cols, "has_velocity", True)
    object.__setattr__(cols, "vx_mps", np.zeros(1))
    object.__setattr__(cols, "vy_mps", np.zeros(1))
    return ("/boxes", t_ns if log_ns is None else log_ns, cols)


def _frames_of(stream: list[tuple[str, int, object]]) -> list[Frame]:
    roles = TopicRoles(ego="/ego", objects=("/boxes",))
    decoders = {"/ego": lambda m: m, "/boxes": lambda m: m}
    options = AssemblyOptions(clock="header")
    return list(FrameAssembler(Path("synthetic.mcap"), roles, decoders, options).run(stream))


def test_a_frame_takes_the_closest_message_stamped_at_or_before_it_wherever_it_is_logged():
    t1, t2, t3 = T0 + EGO_DT, T0 + 2 * EGO_DT, T0 + 3 * EGO_DT
    stream = [
        _box(T0, 1.0),
        _ego(T0),
        _box(T0 + 10_000_000, 2.0),  # logged after the 0 s ego message, stamped after it
        _ego(t1),
        _box(t1, 3.0),  # the stamp of the frame just before: taken by it
        _ego(t2),
        _ego(t3),
        # stamped t2 but logged after the t3 ego message (perception latency on the header
        # clock): frame 2 is still held, its topic has nothing stamped after t2 yet
        _box(t2, 4.0, log_ns=t3 + 1),
        _box(t3 + EGO_DT // 2, 5.0),  # after frame 3: settles it, taken by none
    ]
    frames = _frames_of(stream)
    xs = [float(f.actors.x_m[0]) for f in frames]
    dts = [int(f.actors.match_dt_ns[0]) for f in frames]
    # frame 0 keeps its own stamp's message (a newer stamp is never used)
    assert xs == pytest.approx([1.0, 3.0, 4.0, 4.0])
    assert dts == [0, 0, 0, EGO_DT]


def test_messages_are_counted_unused_only_when_no_final_frame_took_them():
    t1 = T0 + EGO_DT
    stream = [_ego(T0), _box(T0 - EGO_DT // 2, 1.0), _box(T0, 2.0), _ego(t1), _box(t1, 3.0)]
    roles = TopicRoles(ego="/ego", objects=("/boxes",))
    decoders = {"/ego": lambda m: m, "/boxes": lambda m: m}
    assembler = FrameAssembler(
        Path("synthetic.mcap"), roles, decoders, AssemblyOptions(clock="header")
    )
    frames = list(assembler.run(stream))
    assert [float(f.actors.x_m[0]) for f in frames] == [pytest.approx(2.0), pytest.approx(3.0)]
    # the -25 ms message was frame 0's pick until its own stamp's message replaced it
    assert assembler.unused_objects == 1
