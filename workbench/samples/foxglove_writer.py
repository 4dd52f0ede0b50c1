"""Write a scenario as a non-ROS MCAP: Foxglove protobuf schemas plus a JSON plan channel.

Channels (documented in ``docs/samples.md``):

- ``/ego/odometry``: ``foxglove.Odometry`` (pose in ``map``, body-frame velocity), 20 Hz;
- ``/scene/objects``: ``foxglove.SceneUpdate``, one entity per visible object, one cube
  each, metadata ``class``, ``vx_mps``, ``vy_mps``, 10 Hz;
- ``/planning/plan``: JSON, schema ``rss_workbench.Plan`` (``jsonschema``), 10 Hz.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from foxglove_schemas_protobuf.Color_pb2 import Color
from foxglove_schemas_protobuf.CubePrimitive_pb2 import CubePrimitive
from foxglove_schemas_protobuf.KeyValuePair_pb2 import KeyValuePair
from foxglove_schemas_protobuf.Odometry_pb2 import Odometry
from foxglove_schemas_protobuf.Pose_pb2 import Pose
from foxglove_schemas_protobuf.Quaternion_pb2 import Quaternion
from foxglove_schemas_protobuf.SceneEntity_pb2 import SceneEntity
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate
from foxglove_schemas_protobuf.Vector3_pb2 import Vector3
from google.protobuf.duration_pb2 import Duration
from google.protobuf.timestamp_pb2 import Timestamp
from mcap.writer import CompressionType
from mcap.writer import Writer as McapWriter
from mcap_protobuf.schema import register_schema

from loaders.timebase import s_to_ns
from workbench.outputs import json_text
from workbench.samples.motion import DT_S
from workbench.samples.quantise import ANGLE_STEPS, quantise
from workbench.samples.ros_messages import T0_NS
from workbench.samples.ros_objects import plan_indices
from workbench.samples.ros_writers import GENERATOR_VERSION, drive_metadata

if TYPE_CHECKING:
    from pathlib import Path

    from workbench.samples.motion import Track
    from workbench.samples.scenario import Scenario

__all__ = ["FOXGLOVE_TOPICS", "PLAN_SCHEMA", "write_foxglove_mcap"]

FOXGLOVE_TOPICS = {
    "/ego/odometry": "foxglove.Odometry",
    "/scene/objects": "foxglove.SceneUpdate",
    "/planning/plan": "rss_workbench.Plan",
}

#: JSON schema of the plan channel.
PLAN_SCHEMA: dict[str, Any] = {
    "title": "rss_workbench.Plan",
    "type": "object",
    "required": ["t_ns", "x_m", "y_m", "yaw_rad", "t_offset_s", "speed_mps"],
    "properties": {
        "t_ns": {"type": "integer", "description": "plan stamp, ns since the Unix epoch"},
        "x_m": {"type": "array", "items": {"type": "number"}},
        "y_m": {"type": "array", "items": {"type": "number"}},
        "yaw_rad": {"type": "array", "items": {"type": "number"}},
        "t_offset_s": {"type": "array", "items": {"type": "number"}},
        "speed_mps": {"type": "array", "items": {"type": "number"}},
    },
}


def _ts(t_ns: int) -> Timestamp:
    sec, nsec = divmod(t_ns, 10**9)
    return Timestamp(seconds=sec, nanos=nsec)


def _vec3(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Vector3:
    """A ``Vector3`` on the 1e-6 grid of :mod:`workbench.samples.quantise`."""
    return Vector3(x=quantise(x), y=quantise(y), z=quantise(z))


def _pose(x: float, y: float, z: float, yaw: float) -> Pose:
    """A yaw-only pose; position on the 1e-6 grid, quaternion components on the 1e-9 grid."""
    z_q, w_q = (quantise(f(yaw / 2), ANGLE_STEPS) for f in (math.sin, math.cos))
    return Pose(position=_vec3(x, y, z), orientation=Quaternion(x=0.0, y=0.0, z=z_q, w=w_q))


def _entity(tr: Track, k: int, t_ns: int) -> SceneEntity:
    m = tr.motion
    v, yaw = float(m.speed_mps[k]), float(m.yaw_rad[k])
    meta = {
        "class": tr.object_class.label,
        "vx_mps": f"{quantise(v * math.cos(yaw)):.4f}",
        "vy_mps": f"{quantise(v * math.sin(yaw)):.4f}",
    }
    return SceneEntity(
        timestamp=_ts(t_ns),
        frame_id="map",
        id=str(tr.id),
        lifetime=Duration(nanos=200_000_000),
        frame_locked=False,
        metadata=[KeyValuePair(key=key, value=value) for key, value in meta.items()],
        cubes=[
            CubePrimitive(
                pose=_pose(m.x_m[k], m.y_m[k], tr.height_m / 2, yaw),
                size=_vec3(tr.length_m, tr.width_m, tr.height_m),
                color=Color(r=0.2, g=0.5, b=1.0, a=0.8),
            )
        ],
    )


def _plan(sc: Scenario, k: int, t_ns: int) -> bytes:
    """The JSON plan; numbers are the quantised values rounded to 4 decimals (yaw 5)."""
    idx = plan_indices(sc, k)
    m = sc.ego.motion
    plan = {
        "t_ns": t_ns,
        "x_m": [round(quantise(m.x_m[i]), 4) for i in idx],
        "y_m": [round(quantise(m.y_m[i]), 4) for i in idx],
        "yaw_rad": [round(quantise(m.yaw_rad[i], ANGLE_STEPS), 5) for i in idx],
        "t_offset_s": [round((i - k) * DT_S, 3) for i in idx],
        "speed_mps": [round(quantise(m.speed_mps[i]), 4) for i in idx],
    }
    return json_text(plan, compact=True).encode()


def write_foxglove_mcap(sc: Scenario, path: Path, osm: bytes) -> None:
    """Write the Foxglove/JSON variant of ``sc`` with the map attachment and metadata."""
    step_ns = s_to_ns(DT_S)
    with path.open("wb") as stream:
        writer = McapWriter(stream, chunk_size=256 * 1024, compression=CompressionType.ZSTD)
        writer.start(profile="", library=f"rss-workbench samples {GENERATOR_VERSION}")
        odom_ch = writer.register_channel(
            "/ego/odometry", "protobuf", register_schema(writer, Odometry)
        )
        scene_ch = writer.register_channel(
            "/scene/objects", "protobuf", register_schema(writer, SceneUpdate)
        )
        plan_schema = writer.register_schema(
            "rss_workbench.Plan", "jsonschema", json_text(PLAN_SCHEMA, sort_keys=True).encode()
        )
        plan_ch = writer.register_channel("/planning/plan", "json", plan_schema)
        ego = sc.ego
        for k in range(len(sc.t_s)):
            t_ns = T0_NS + k * step_ns
            odom = Odometry(
                timestamp=_ts(t_ns),
                frame_id="map",
                body_frame_id="base_link",
                pose=_pose(ego.motion.x_m[k], ego.motion.y_m[k], 0.0, ego.motion.yaw_rad[k]),
                linear_velocity=_vec3(ego.motion.speed_mps[k]),
                angular_velocity=_vec3(z=ego.yaw_rate_radps[k]),
            )
            writer.add_message(odom_ch, t_ns, odom.SerializeToString(), t_ns, k)
            if k % 2:
                continue
            update = SceneUpdate(
                entities=[_entity(tr, k, t_ns) for tr in sc.actors if tr.visible[k]]
            )
            writer.add_message(scene_ch, t_ns, update.SerializeToString(), t_ns, k // 2)
            writer.add_message(plan_ch, t_ns, _plan(sc, k, t_ns), t_ns, k // 2)
        writer.add_attachment(T0_NS, T0_NS, f"{sc.name}.osm", "application/xml", osm)
        writer.add_metadata("drive", {**drive_metadata(sc), "variant": "foxglove"})
        writer.finish()  # type: ignore[no-untyped-call]
