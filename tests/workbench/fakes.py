"""A tiny in-memory ``Drive`` for workbench tests and benchmarks: synthetic, seeded, streaming."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from loaders.drive import DriveInfo, TopicInfo, TopicRoles
from loaders.maps.model import Lane, LaneMap, LineType
from loaders.records import ActorTable, EgoState, Frame, ObjectClass, Plan
from workbench.engines.base import BoundRunner
from workbench.engines.registry import engine, find

if TYPE_CHECKING:
    from collections.abc import Iterator

    from workbench.engines.base import EngineRunner

__all__ = ["FakeDrive", "bound", "straight_road", "synthetic_frame"]

T0_NS = 1_700_000_000_000_000_000
DT_NS = 100_000_000  # 10 Hz


def bound(runner: EngineRunner) -> BoundRunner:
    """``runner`` with its registered engine's spec, as the driver takes it.

    A probe runner of no registered name gets a copy of the reach-set spec under its name
    (for driver tests that look at the frames only, never at a sink's output).
    """
    spec = find(runner.name) or dataclasses.replace(engine("reachsets"), name=runner.name)
    return BoundRunner(spec, runner)


def straight_road(length_m: float = 400.0, lanes: int = 3, width_m: float = 3.5) -> LaneMap:
    """A straight multi-lane road along +x; lane 0 is the rightmost (y = 0 .. width)."""
    xs = np.linspace(0.0, length_m, 9)
    out = {}
    for i in range(lanes):
        right = np.column_stack([xs, np.full_like(xs, i * width_m)])
        left = np.column_stack([xs, np.full_like(xs, (i + 1) * width_m)])
        out[f"l{i}"] = Lane(
            id=f"l{i}",
            left_m=left,
            right_m=right,
            centre_m=(left + right) / 2,
            left_line=LineType.SOLID if i == lanes - 1 else LineType.DASHED,
            right_line=LineType.SOLID if i == 0 else LineType.DASHED,
        )
    return LaneMap(lanes=out, source="synthetic", format="synthetic")


def synthetic_frame(index: int, n_actors: int, *, with_plan: bool = True) -> Frame:
    """Frame ``index`` of a 10 Hz drive: ego at 15 m/s along +x, ``n_actors`` cars ahead."""
    t_s = index * DT_NS / 1e9
    ego_x = 15.0 * t_s
    ego = EgoState(
        x_m=ego_x,
        y_m=1.75,
        z_m=0.0,
        yaw_rad=0.0,
        speed_mps=15.0,
        accel_mps2=0.1,
        yaw_rate_radps=0.0,
    )
    k = np.arange(n_actors)
    actors = ActorTable.from_columns(
        ids=[f"car{i}" for i in range(n_actors)],
        object_class=np.where(k % 5 == 4, ObjectClass.TRUCK, ObjectClass.CAR),
        x_m=ego_x + 10.0 + 8.0 * k,
        y_m=1.75 + 3.5 * (k % 3),
        z_m=np.full(n_actors, 0.75),
        yaw_rad=np.zeros(n_actors),
        vx_mps=np.full(n_actors, 14.0),
        vy_mps=np.zeros(n_actors),
        length_m=np.full(n_actors, 4.5),
        width_m=np.full(n_actors, 1.9),
    )
    plan = None
    if with_plan:
        px = ego_x + np.linspace(0.0, 45.0, 16)
        plan = Plan(
            x_m=px,
            y_m=np.full(16, 1.75),
            yaw_rad=np.zeros(16),
            t_offset_s=np.linspace(0.0, 3.0, 16),
            speed_mps=np.full(16, 15.0),
        )
    return Frame(index=index, t_ns=T0_NS + index * DT_NS, ego=ego, actors=actors, plan=plan)


@dataclass
class FakeDrive:
    """Implements ``loaders.drive.Drive`` over synthetic frames, generated lazily."""

    n_frames: int = 50
    n_actors: int = 3
    with_map: bool = True
    path: Path = field(default_factory=lambda: Path("fake_drive.mcap"))
    closed: bool = False

    @property
    def info(self) -> DriveInfo:
        """Metadata as a ROS 2 MCAP loader would report it."""
        return DriveInfo(
            path=self.path,
            source_format="fake",
            start_ns=T0_NS,
            end_ns=T0_NS + max(self.n_frames - 1, 0) * DT_NS,
            topics=(TopicInfo("/ego/odom", "nav_msgs/msg/Odometry", self.n_frames, "ego"),),
            roles=TopicRoles(ego="/ego/odom", objects=("/objects",), plan="/plan"),
            frame_count=self.n_frames,
            map_source="synthetic" if self.with_map else None,
            notes={"generator": "tests.workbench.fakes"},
        )

    @property
    def lane_map(self) -> LaneMap | None:
        """A straight three-lane road, or nothing."""
        return straight_road() if self.with_map else None

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield frames within ``[start_ns, end_ns)``, re-indexed densely from 0."""
        out = 0
        for i in range(self.n_frames):
            t_ns = T0_NS + i * DT_NS
            if (start_ns is not None and t_ns < start_ns) or (
                end_ns is not None and t_ns >= end_ns
            ):
                continue
            frame = synthetic_frame(i, self.n_actors)
            yield Frame(
                index=out, t_ns=frame.t_ns, ego=frame.ego, actors=frame.actors, plan=frame.plan
            )
            out += 1

    def close(self) -> None:
        """Mark the drive closed."""
        self.closed = True
