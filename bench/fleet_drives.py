"""Generated drives for the fleet benchmark: a straight 3-lane road, an ego and N objects.

The ego drives at 20 m/s in the middle lane; the objects are cars spread over the three lanes
from 250 m behind to 350 m ahead of it, each at its own constant speed (16-24 m/s, seeded),
all inside the sensor range for the whole drive, so every frame holds all N of them. Same-lane
objects close in on slower ones, so the RSS engine finds incidents. Written with the sample
writers (``workbench.samples``) as a ROS 2 MCAP with its Lanelet2 map beside it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from loaders.records import ObjectClass
from workbench.samples.geometry import build_path
from workbench.samples.lanelet2_writer import to_osm_bytes
from workbench.samples.lanelet_map import MapBuilder
from workbench.samples.motion import Track, drive, time_axis
from workbench.samples.roads import add_road
from workbench.samples.ros_writers import write_mcap
from workbench.samples.scenario import SIZE_M, RosLayout, Scenario, actor
from workbench.samples.scenarios_roads import highway_spec

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["EGO_SPEED_MPS", "fleet_drive", "write_fleet_drive"]

#: The ego's speed [m/s].
EGO_SPEED_MPS = 20.0
_SECTION_M = 300.0


def fleet_drive(name: str, objects: int, duration_s: float, seed: int) -> Scenario:
    """A drive of ``duration_s`` [s] at 20 Hz with ``objects`` cars in every frame."""
    rng = np.random.default_rng(seed)
    length_m = _SECTION_M * np.ceil((700.0 + 25.0 * duration_s) / _SECTION_M)
    b = MapBuilder()
    ref = build_path((0.0, 0.0), 0.0, [(float(length_m), 0.0)], step_m=10.0)
    spec = highway_spec()
    lanes = add_road(b, ref, tuple(np.arange(0.0, length_m + 1.0, _SECTION_M)), spec)
    t = time_axis(duration_s)
    offsets = [spec.centre_offset_m(i) for i in range(3)]
    ego = drive(ref, t, s0_m=260.0, v0_mps=EGO_SPEED_MPS, offset_m=offsets[1])
    actors = []
    for k in range(objects):
        lane = int(rng.integers(3))
        motion = drive(
            ref,
            t,
            s0_m=float(rng.uniform(10.0, 610.0)),
            v0_mps=float(rng.uniform(16.0, 24.0)),
            offset_m=offsets[lane],
        )
        cls = ObjectClass.CAR
        actors.append(actor(rng, k + 1, cls, motion, lanes[lane], ego=ego, range_m=1e9))
    return Scenario(
        name=name,
        summary=f"{objects} cars around an ego at 20 m/s for {duration_s:g} s (fleet benchmark).",
        seed=seed,
        t_s=t,
        ego=Track.of(0, ObjectClass.CAR, SIZE_M["car"], ego, lanes[1]),
        actors=tuple(actors),
        lane_map=b,
        layout=RosLayout("odometry", "/localization/kinematic_state", "object_array", "path"),
        road_lanelets=3 * (len(lanes[0]) if lanes else 0),
    )


def write_fleet_drive(folder: Path, name: str, objects: int, duration_s: float, seed: int) -> Path:
    """Write ``folder/<name>.mcap`` (and its ``.osm``); return the log."""
    sc = fleet_drive(name, objects, duration_s, seed)
    osm = to_osm_bytes(sc.lane_map)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.osm").write_bytes(osm)
    log = folder / f"{name}.mcap"
    write_mcap(sc, log, osm)
    return log
