"""Loader throughput and peak memory on a large ROS 2 MCAP drive.

Generates (into a temporary directory) a drive with a 10 Hz ``nav_msgs/Odometry`` ego,
a 10 Hz ``derived_object_msgs/ObjectArray`` with 30 actors, and a 10 Hz
``sensor_msgs/PointCloud2`` padding topic the loader skips: ~1 GB full, ~50 MB quick.
Iterating all frames runs in a fresh subprocess so its peak RSS
(``bench.child.peak_rss_mib``) is the loader's own.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from mcap.writer import CompressionType

from loaders.typestore import typestore
from tests.loaders.fixtures import Entry, write_ros2_mcap
from tests.loaders.msgbuild import build, header, pose
from tests.loaders.rosmsgs import odometry

if TYPE_CHECKING:
    from collections.abc import Iterator

N_ACTORS = 30
CLOUD_BYTES = 160_000
T0 = 1_700_000_000_000_000_000
DT_NS = 100_000_000
CARLA = "derived_object_msgs/msg/ObjectArray"
CLOUD = "sensor_msgs/msg/PointCloud2"

_CHILD = """
import json, os, sys, time
from bench.child import peak_rss_mib
os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
from loaders import open_drive
t0 = time.perf_counter()
drive = open_drive(sys.argv[1])
n = actors = 0
for frame in drive.frames():
    n += 1
    actors += len(frame.actors)
dt = time.perf_counter() - t0
drive.close()
print(json.dumps({"frames": n, "actors": actors, "seconds": dt,
                  "peak_rss_mb": peak_rss_mib()}))
"""

_CHILD_REPLAY = """
import json, os, sys, time
from bench.child import peak_rss_mib
os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
from pathlib import Path
from loaders import open_drive
from workbench.viewer.replay import replay_drive
t0 = time.perf_counter()
drive = open_drive(sys.argv[1])
summary = replay_drive(drive, out=Path(sys.argv[2]))
dt = time.perf_counter() - t0
drive.close()
print(json.dumps({"frames": summary.frames, "seconds": dt,
                  "rrd_mb": Path(sys.argv[2]).stat().st_size / 2**20,
                  "peak_rss_mb": peak_rss_mib()}))
"""

_BASELINE = """
import json
from bench.child import peak_rss_mib
import loaders, loaders.open, numpy, rosbags.highlevel, mcap.reader
print(json.dumps({"peak_rss_mb": peak_rss_mib()}))
"""


def _objects_template(ts: Any) -> Any:
    objs = []
    for k in range(N_ACTORS):
        shape = build(
            ts, "shape_msgs/msg/SolidPrimitive", type=1, dimensions=np.array([4.5, 1.9, 1.5])
        )
        twist = build(
            ts,
            "geometry_msgs/msg/Twist",
            linear=build(ts, "geometry_msgs/msg/Vector3", x=10.0 + k % 5),
        )
        objs.append(
            build(
                ts,
                "derived_object_msgs/msg/Object",
                header=header(ts, T0),
                id=k + 1,
                pose=pose(ts, 0.0, 0.0, 0.75, 0.0),
                twist=twist,
                shape=shape,
                classification=6,
            )
        )
    return build(ts, CARLA, header=header(ts, T0), objects=objs)


def _entries(n_frames: int) -> Iterator[Entry]:
    ts = typestore(2)
    rng = np.random.default_rng(7)
    objects = _objects_template(ts)
    cloud = build(
        ts,
        CLOUD,
        header=header(ts, T0, "lidar"),
        height=1,
        width=CLOUD_BYTES // 16,
        point_step=16,
        row_step=CLOUD_BYTES,
        data=rng.integers(0, 255, CLOUD_BYTES, dtype=np.uint8),
    )
    for i in range(n_frames):
        t = T0 + i * DT_NS
        yield Entry("/carla/ego_vehicle/lidar", CLOUD, t - 50_000_000, cloud)
        objects.header = header(ts, t - 20_000_000)
        for k, obj in enumerate(objects.objects):
            obj.pose.position.x = 12.0 * i * 0.1 + 8.0 * (k % 10)
            obj.pose.position.y = 3.5 * (k // 10) + math.sin(i * 0.01)
        yield Entry("/carla/ego_vehicle/objects", CARLA, t - 20_000_000, objects)
        yield Entry("/carla/ego_vehicle/odometry", "nav_msgs/msg/Odometry", t, odometry(ts, t))


def _child(code: str, *args: str) -> dict[str, float]:
    out = subprocess.run(  # noqa: S603 - our own interpreter and script
        [sys.executable, "-c", code, *args], capture_output=True, text=True, check=True
    )
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


def run(quick: bool) -> str:  # noqa: FBT001 - harness signature
    """Generate the drive, load it in a subprocess, return the Markdown section."""
    n_frames = 300 if quick else 6000
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "large_drive.mcap"
        t0 = time.perf_counter()
        write_ros2_mcap(
            path, _entries(n_frames), chunk_size=1024 * 1024, compression=CompressionType.NONE
        )
        gen_s = time.perf_counter() - t0
        size_mb = path.stat().st_size / 2**20
        base = _child(_BASELINE)
        result = _child(_CHILD, str(path))
        replay = _child(_CHILD_REPLAY, str(path), str(Path(tmp) / "large_drive.rrd"))
    fps = result["frames"] / result["seconds"]
    replay_fps = replay["frames"] / replay["seconds"]
    return (
        "## Loaders and replay: a large ROS 2 MCAP, throughput and memory\n\n"
        f"Drive: {size_mb:.0f} MiB ROS 2 MCAP (uncompressed chunks of 1 MiB), {n_frames} frames "
        f"at 10 Hz, {N_ACTORS} actors (`derived_object_msgs/ObjectArray`), plus a "
        f"{CLOUD_BYTES // 1000} kB `sensor_msgs/PointCloud2` per frame that the loader skips; "
        f"generated in {gen_s:.1f} s. Each row runs in a fresh process pinned to one core: "
        "loading only (`open_drive` + iterating all frames), and loading + logging the whole "
        "drive to an `.rrd` (`replay_drive`, what `workbench replay` does).\n\n"
        "| metric | value | target |\n|---|---|---|\n"
        f"| frames | {int(result['frames'])} | = {n_frames} |\n"
        f"| actor rows | {int(result['actors'])} | |\n"
        f"| load time | {result['seconds']:.2f} s | |\n"
        f"| throughput | {fps:.0f} frames/s | >= 500 |\n"
        f"| peak RSS | {result['peak_rss_mb']:.0f} MiB | < 400 |\n"
        f"| peak RSS after imports only | {base['peak_rss_mb']:.0f} MiB | |\n"
        f"| load + log to .rrd: throughput | {replay_fps:.0f} frames/s | >= 500 |\n"
        f"| load + log to .rrd: peak RSS | {replay['peak_rss_mb']:.0f} MiB | < 400 |\n"
        f"| load + log to .rrd: file size | {replay['rrd_mb']:.0f} MiB | |\n"
    )


if __name__ == "__main__":
    print(run(quick="--quick" in sys.argv))
