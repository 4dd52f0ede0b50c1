"""Compare two drives frame by frame, and their verdicts, for the drive-to-MCAP tests.

Tolerances (what ``workbench.samples.drive_mcap`` documents as surviving the round trip):
positions, speeds, velocities, sizes and the ego yaw rate exactly; yaws within 1e-12 rad
after wrapping (a quaternion in between); plan times within 1 ns (a ``Duration``) and
plan speeds within float32 resolution. The ego acceleration is not compared: ``Odometry``
has none, the MCAP reader derives it from the speeds, and no engine reads it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from workbench.driver.run import DriveRun, EgoSize
from workbench.engines import build_runners
from workbench.sinks.per_frame import frame_records

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.drive import Drive
    from loaders.records import Frame

__all__ = [
    "ENGINES",
    "assert_same_frames",
    "assert_same_verdicts",
    "ego_size_of",
    "verdict_records",
]

#: Relative tolerance of the margins: RSS's is a distance ratio computed from yaws that pass
#: through a quaternion (1e-12 rad), so its last bits may differ on another CPU or path.
MARGIN_RTOL = 1e-9

#: Every engine of the acceptance run.
ENGINES = ("rss", "unstructured", "reachsets")
_EXACT_EGO = ("x_m", "y_m", "z_m", "speed_mps", "yaw_rate_radps")
_EXACT_ACTORS = ("x_m", "y_m", "z_m", "vx_mps", "vy_mps", "length_m", "width_m", "height_m")


def _wrapped(a: NDArray[np.float64] | float, b: NDArray[np.float64] | float) -> Any:
    return np.abs((np.asarray(a) - np.asarray(b) + np.pi) % (2 * np.pi) - np.pi)


def assert_same_frames(expected: Sequence[Frame], got: Sequence[Frame]) -> None:
    """Every frame of ``got`` equals the one of ``expected`` within the module's tolerances."""
    assert len(got) == len(expected)
    for a, b in zip(expected, got, strict=True):
        where = f"frame {a.index}"
        assert (b.index, b.t_ns) == (a.index, a.t_ns), where
        for name in _EXACT_EGO:
            assert getattr(b.ego, name) == getattr(a.ego, name), f"{where} ego.{name}"
        assert _wrapped(a.ego.yaw_rad, b.ego.yaw_rad) < 1e-12, where
        assert b.actors.ids.tolist() == a.actors.ids.tolist(), where
        assert b.actors.object_class.tolist() == a.actors.object_class.tolist(), where
        assert b.actors.valid.tolist() == a.actors.valid.tolist(), where
        assert not b.actors.match_dt_ns.any(), f"{where}: objects matched from another time"
        for name in _EXACT_ACTORS:
            np.testing.assert_array_equal(getattr(b.actors, name), getattr(a.actors, name), where)
        assert np.all(_wrapped(a.actors.yaw_rad, b.actors.yaw_rad) < 1e-12), where
        assert a.plan is not None, where
        assert b.plan is not None, where
        np.testing.assert_array_equal(b.plan.x_m, a.plan.x_m, where)
        np.testing.assert_array_equal(b.plan.y_m, a.plan.y_m, where)
        assert np.all(_wrapped(a.plan.yaw_rad, b.plan.yaw_rad) < 1e-12), where
        np.testing.assert_allclose(b.plan.t_offset_s, a.plan.t_offset_s, rtol=0, atol=1e-9)
        np.testing.assert_allclose(b.plan.speed_mps, a.plan.speed_mps, rtol=1e-7, atol=1e-6)


def ego_size_of(frame: Frame) -> EgoSize:
    """The ego size of ``frame`` (what ``--rss-params [scene] ego_*`` gives the MCAP)."""
    e = frame.ego
    return EgoSize(e.length_m, e.width_m, e.height_m)


def verdict_records(
    drive: Drive, size: EgoSize, window: tuple[int | None, int | None] = (None, None)
) -> tuple[list[dict[str, Any]], list[tuple[float, ...]]]:
    """Per-frame JSON records and margins of every engine over ``window`` of ``drive``."""
    runners = build_runners(list(ENGINES), drive.lane_map)
    records: list[dict[str, Any]] = []
    margins: list[tuple[float, ...]] = []
    for chunk in DriveRun(drive, runners, start_ns=window[0], end_ns=window[1], ego_size=size):
        records += frame_records(chunk)
        margins += [
            tuple(chunk.verdicts[name][k].margin for name in ENGINES)
            for k in range(len(chunk.frames))
        ]
    return records, margins


def assert_same_verdicts(
    got: tuple[list[dict[str, Any]], list[tuple[float, ...]]],
    want: tuple[list[dict[str, Any]], list[tuple[float, ...]]],
) -> None:
    """Equal per-frame records; margins equal within :data:`MARGIN_RTOL`."""
    assert got[0] == want[0]
    assert len(got[1]) == len(want[1])
    for k, (a, b) in enumerate(zip(got[1], want[1], strict=True)):
        np.testing.assert_allclose(a, b, rtol=MARGIN_RTOL, atol=0, err_msg=f"frame {k} margins")
