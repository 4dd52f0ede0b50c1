"""The ``highway_cut_in`` sample's ego rewritten as other ego message types (rosbag2, MCAP).

Objects and plan are copied message by message from the sample at their own log time. Each
object message shares its time with an ego message: the sample stores such ties ego first,
the written logs objects first (entries are sorted stably, copies before egos), and a frame
takes its stamp's objects whatever their order (docs/loaders.md), so both give the same
frames. The ego poses of the sample's frames (from its ``nav_msgs/Odometry``) are written as:

| variant | topics |
|---|---|
| ``tf`` | ``/tf_static`` map→odom (fixed offset), ``/tf`` odom→base_link per frame and a |
|        | base_link→lidar transform in messages of their own (must not make frames) |
| ``tf_footprint`` | ``/tf`` odom→base_footprint per frame, ``/tf_static`` |
|        | base_footprint→base_link (:data:`FOOTPRINT_TO_LINK`): the ego is base_link in odom |
| ``pose_cov`` | ``/localization/pose_with_covariance`` (``PoseWithCovarianceStamped``) |
| ``gnss`` | ``/gnss/fix`` (``NavSatFix``) + ``/imu/data`` (``Imu``, 1 ms before each fix) |
| ``gnss_no_imu`` | ``/gnss/fix`` only |

GNSS fixes are the frame positions mapped to WGS-84 about :data:`ORIGIN_DEG` with
``pymap3d.enu2geodetic``; :func:`write_origin_map` writes a one-lanelet Lanelet2 map whose
first node is that origin, so a drive opened with it lands in the sample's frame.
"""

from __future__ import annotations

import math
from contextlib import closing
from typing import TYPE_CHECKING, Any

import pymap3d
from rosbags.highlevel import AnyReader

from loaders import open_drive
from loaders.typestore import typestore
from tests.loaders.fixtures import Entry, write_ros1_bag, write_rosbag2
from tests.loaders.msgbuild import build, header, pose, quat

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.records import Frame

__all__ = [
    "ORIGIN_DEG",
    "SAMPLE",
    "VARIANTS",
    "reference_frames",
    "write_origin_map",
    "write_variant",
]

#: The reference drive (relative to the repository root).
SAMPLE = "sample_logs/highway_cut_in.mcap"
#: WGS-84 origin of the GNSS variants' local frame.
ORIGIN_DEG = (49.0, 8.4)
#: Fixed map -> odom transform of the TF variant: translation (m) and yaw (rad).
MAP_TO_ODOM = (12.0, -7.5, 0.4)
#: Static base_footprint -> base_link transform of the ``tf_footprint`` variant (x m, y m, yaw).
FOOTPRINT_TO_LINK = (0.8, 0.0, 0.0)
VARIANTS = ("tf", "tf_footprint", "pose_cov", "gnss", "gnss_no_imu")
_COPIED = ("/carla/ego_vehicle/objects", "/planning/path")


def reference_frames(root: Path) -> list[Frame]:
    """Frames of the sample as read from its own ``Odometry`` ego."""
    with closing(open_drive(root / SAMPLE)) as drive:
        return list(drive.frames())


def _copied(root: Path, source: str = SAMPLE, delay_ns: int = 0) -> list[Entry]:
    out = []
    with AnyReader([root / source]) as reader:
        conns = [c for c in reader.connections if c.topic in _COPIED]
        for conn, t_ns, raw in reader.messages(connections=conns):
            msg = reader.deserialize(raw, conn.msgtype)
            out.append(Entry(conn.topic, conn.msgtype, t_ns + delay_ns, msg))
    return out


def _transform(ts: Any, t_ns: int, parent: str, child: str, xyyaw: tuple[float, ...]) -> Any:
    x, y, yaw = xyyaw
    tr = build(
        ts,
        "geometry_msgs/msg/Transform",
        translation=build(ts, "geometry_msgs/msg/Vector3", x=x, y=y, z=0.0),
        rotation=quat(ts, yaw),
    )
    return build(
        ts,
        "geometry_msgs/msg/TransformStamped",
        header=header(ts, t_ns, parent),
        child_frame_id=child,
        transform=tr,
    )


def _tf(ts: Any, transforms: list[Any]) -> Any:
    return build(ts, "tf2_msgs/msg/TFMessage", transforms=transforms)


def _odom_pose(frame: Frame) -> tuple[float, float, float]:
    """The frame's ego pose in the odom frame: inverse(map->odom) * map pose."""
    ox, oy, oyaw = MAP_TO_ODOM
    dx, dy = frame.ego.x_m - ox, frame.ego.y_m - oy
    c, s = math.cos(oyaw), math.sin(oyaw)
    return c * dx + s * dy, -s * dx + c * dy, frame.ego.yaw_rad - oyaw


def _footprint_pose(frame: Frame) -> tuple[float, float, float]:
    """base_footprint in odom (= map here) such that base_link lands on the frame's pose."""
    dx = FOOTPRINT_TO_LINK[0]
    yaw = frame.ego.yaw_rad
    return frame.ego.x_m - dx * math.cos(yaw), frame.ego.y_m - dx * math.sin(yaw), yaw


def _footprint_entries(ts: Any, frames: list[Frame]) -> list[Entry]:
    tf_type = "tf2_msgs/msg/TFMessage"
    static = _transform(ts, frames[0].t_ns, "base_footprint", "base_link", FOOTPRINT_TO_LINK)
    out = [Entry("/tf_static", tf_type, frames[0].t_ns - 10**6, _tf(ts, [static]))]
    for f in frames:
        moving = _transform(ts, f.t_ns, "odom", "base_footprint", _footprint_pose(f))
        out.append(Entry("/tf", tf_type, f.t_ns, _tf(ts, [moving])))
    return out


def _ego_entries(ts: Any, frames: list[Frame], variant: str) -> list[Entry]:
    tf_type, fix_type = "tf2_msgs/msg/TFMessage", "sensor_msgs/msg/NavSatFix"
    out: list[Entry] = []
    if variant == "tf_footprint":
        return _footprint_entries(ts, frames)
    if variant == "tf":
        static = _transform(ts, frames[0].t_ns, "map", "odom", MAP_TO_ODOM)
        out.append(Entry("/tf_static", tf_type, frames[0].t_ns - 10**6, _tf(ts, [static])))
    for f in frames:
        e, t = f.ego, f.t_ns
        if variant == "tf":
            link = _transform(ts, t, "odom", "base_link", _odom_pose(f))
            lidar = _transform(ts, t, "base_link", "lidar", (1.2, 0.0, 0.0))
            out.append(Entry("/tf", tf_type, t - 10**5, _tf(ts, [lidar])))
            out.append(Entry("/tf", tf_type, t, _tf(ts, [link])))
        elif variant == "pose_cov":
            body = build(
                ts,
                "geometry_msgs/msg/PoseWithCovariance",
                pose=pose(ts, e.x_m, e.y_m, 0, e.yaw_rad),
            )
            msg = build(
                ts, "geometry_msgs/msg/PoseWithCovarianceStamped", header=header(ts, t), pose=body
            )
            out.append(Entry("/localization/pose_with_covariance", msg.__msgtype__, t, msg))
        else:
            lat, lon, alt = pymap3d.enu2geodetic(e.x_m, e.y_m, 0.0, *ORIGIN_DEG, 0.0)
            fix = build(
                ts,
                fix_type,
                header=header(ts, t, "gnss"),
                latitude=float(lat),
                longitude=float(lon),
                altitude=float(alt),
            )
            out.append(Entry("/gnss/fix", fix_type, t, fix))
            if variant == "gnss":
                imu = build(
                    ts,
                    "sensor_msgs/msg/Imu",
                    header=header(ts, t, "imu"),
                    orientation=quat(ts, e.yaw_rad),
                )
                out.append(Entry("/imu/data", "sensor_msgs/msg/Imu", t - 10**6, imu))
    return out


def write_variant(
    root: Path, out_dir: Path, variant: str, storage: str = "mcap", *, latency_ns: int = 0
) -> Path:
    """Write the sample with its ego as ``variant``; return its path.

    ``storage`` ``mcap`` or ``sqlite3`` gives a rosbag2 directory, ``bag`` a ROS 1 bag (the
    objects and path copied from the sample's ROS 1 twin ``highway_cut_in.bag``).
    ``latency_ns`` logs the copied messages that much after their header stamp (a
    perception pipeline's latency).
    """
    if storage == "bag":
        ts = typestore(1)
        entries = _copied(root, SAMPLE.replace(".mcap", ".bag"), latency_ns)
        entries += _ego_entries(ts, reference_frames(root), variant)
        entries.sort(key=lambda e: e.t_ns)
        return write_ros1_bag(out_dir / f"highway_{variant}.bag", entries)
    ts = typestore(2)
    entries = _copied(root, delay_ns=latency_ns) + _ego_entries(ts, reference_frames(root), variant)
    entries.sort(key=lambda e: e.t_ns)
    return write_rosbag2(out_dir / f"highway_{variant}", entries, storage)


def write_origin_map(path: Path) -> Path:
    """A one-lanelet Lanelet2 map in latitude/longitude whose first node is :data:`ORIGIN_DEG`."""
    nodes = []
    for k, (east, north) in enumerate([(0.0, 0.0), (50.0, 0.0), (0.0, 3.5), (50.0, 3.5)], start=1):
        lat, lon, _ = pymap3d.enu2geodetic(east, north, 0.0, *ORIGIN_DEG, 0.0)
        nodes.append(f'  <node id="{k}" lat="{lat:.12f}" lon="{lon:.12f}"/>')
    path.write_text(
        "<?xml version='1.0' encoding='utf-8'?>\n<osm version=\"0.6\">\n"
        + "\n".join(nodes)
        + '\n  <way id="10"><nd ref="1"/><nd ref="2"/></way>'
        + '\n  <way id="11"><nd ref="3"/><nd ref="4"/></way>'
        + '\n  <relation id="20"><member type="way" ref="11" role="left"/>'
        + '<member type="way" ref="10" role="right"/><tag k="type" v="lanelet"/>'
        + '<tag k="subtype" v="road"/></relation>\n</osm>\n',
        encoding="utf-8",
    )
    return path
