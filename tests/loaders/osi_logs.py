"""The ``highway_cut_in`` sample's frames written as ASAM OSI ground truth.

Each frame of the sample (as read from its ``Odometry`` ego and CARLA objects) becomes one
OSI message at the frame time: the ego as the host vehicle (:data:`HOST_ID`), every actor
as a moving object with the frame's (extrapolated) pose, map-frame velocity, size and class.

| variant | container | message | schema name |
|---|---|---|---|
| ``gt_mcap`` | MCAP written by ``betterosi.Writer`` | ``GroundTruth`` | ``GroundTruth`` |
| ``sv_mcap`` | MCAP written with ``mcap``'s writer | ``SensorView`` | ``osi3.SensorView`` |
| ``gt_osi`` | ``.osi`` trace (``betterosi.Writer``) | ``GroundTruth`` | (file name: ``_gt_``) |
| ``sv_osi`` | ``.osi`` trace (``betterosi.Writer``) | ``SensorView`` | (file name: ``_sv_``) |

The ``osi3.`` name is what the ASAM OSI tooling writes; betterosi writes the bare type name.
The class of an actor is written as the OSI type this table gives (the inverse of the
reader's mapping, written out independently).
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import betterosi
from mcap.writer import Writer as McapWriter

from loaders.records import ObjectClass

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.records import Frame

__all__ = ["HOST_ID", "VARIANTS", "write_osi"]

#: Id of the host vehicle (the ego); the sample's CARLA object ids are all smaller.
HOST_ID = 999
VARIANTS = ("gt_mcap", "sv_mcap", "gt_osi", "sv_osi")
#: Trace file names following the OSI trace file naming convention.
_NAMES = {
    "gt_osi": "20240101T000000Z_gt_3.8.0_7.0.0_{n}_highway_cut_in.osi",
    "sv_osi": "20240101T000000Z_sv_3.8.0_7.0.0_{n}_highway_cut_in.osi",
    "gt_mcap": "highway_cut_in_gt.mcap",
    "sv_mcap": "highway_cut_in_sv.mcap",
}
_MO = betterosi.MovingObject
_VC = _MO.VehicleClassification.Type
#: Our class → (MovingObject.Type, VehicleClassification.Type or None).
_OSI_CLASS: dict[int, tuple[Any, Any]] = {
    ObjectClass.UNKNOWN: (_MO.Type.UNKNOWN, None),
    ObjectClass.CAR: (_MO.Type.VEHICLE, _VC.COMPACT_CAR),
    ObjectClass.TRUCK: (_MO.Type.VEHICLE, _VC.HEAVY_TRUCK),
    ObjectClass.BUS: (_MO.Type.VEHICLE, _VC.BUS),
    ObjectClass.MOTORCYCLE: (_MO.Type.VEHICLE, _VC.MOTORBIKE),
    ObjectClass.BICYCLE: (_MO.Type.VEHICLE, _VC.BICYCLE),
    ObjectClass.PEDESTRIAN: (_MO.Type.PEDESTRIAN, None),
}


def _base(pose: tuple[float, float, float, float], v: tuple[float, float], size: Any) -> Any:
    x, y, z, yaw = pose
    return betterosi.BaseMoving(
        position=betterosi.Vector3d(x=x, y=y, z=z),
        orientation=betterosi.Orientation3d(yaw=yaw),
        velocity=betterosi.Vector3d(x=v[0], y=v[1], z=0.0),
        dimension=betterosi.Dimension3d(length=size[0], width=size[1], height=size[2]),
    )


def ground_truth(frame: Frame) -> Any:
    """One ``GroundTruth`` holding the frame's ego (host vehicle) and actors."""
    e = frame.ego
    host = _MO(
        id=betterosi.Identifier(value=HOST_ID),
        type=_MO.Type.VEHICLE,
        base=_base(
            (e.x_m, e.y_m, e.z_m, e.yaw_rad),
            (e.speed_mps * math.cos(e.yaw_rad), e.speed_mps * math.sin(e.yaw_rad)),
            (4.5, 2.0, 1.5),
        ),
        vehicle_classification=_MO.VehicleClassification(type=_VC.CAR),
    )
    host.base.orientation_rate = betterosi.Orientation3d(yaw=e.yaw_rate_radps)
    a = frame.actors
    objects = [host]
    for k in range(len(a)):
        kind, vehicle = _OSI_CLASS[int(a.object_class[k])]
        size = (float(a.length_m[k]), float(a.width_m[k]), float(a.height_m[k]))
        base = _base(
            (float(a.x_m[k]), float(a.y_m[k]), float(a.z_m[k]), float(a.yaw_rad[k])),
            (float(a.vx_mps[k]), float(a.vy_mps[k])),
            size,
        )
        obj = _MO(id=betterosi.Identifier(value=int(a.ids[k])), type=kind, base=base)
        if vehicle is not None:
            obj.vehicle_classification = _MO.VehicleClassification(type=vehicle)
        objects.append(obj)
    seconds, nanos = divmod(frame.t_ns, 1_000_000_000)
    return betterosi.GroundTruth(
        timestamp=betterosi.Timestamp(seconds=seconds, nanos=nanos),
        host_vehicle_id=betterosi.Identifier(value=HOST_ID),
        moving_object=objects,
    )


def _sensor_view(gt: Any) -> Any:
    return betterosi.SensorView(
        timestamp=gt.timestamp, host_vehicle_id=gt.host_vehicle_id, global_ground_truth=gt
    )


def write_osi(frames: list[Frame], out_dir: Path, variant: str) -> Path:
    """Write ``frames`` as OSI ``variant`` (see the module table) into ``out_dir``."""
    path = out_dir / _NAMES[variant].format(n=len(frames))
    messages = [ground_truth(f) for f in frames]
    if variant.startswith("sv"):
        messages = [_sensor_view(gt) for gt in messages]
    if variant == "sv_mcap":
        with path.open("wb") as f:
            writer = McapWriter(f, chunk_size=64 * 1024)
            writer.start(profile="", library="rss-workbench tests")
            schema = writer.register_schema(
                "osi3.SensorView", "protobuf", betterosi.load_descriptor_set()
            )
            channel = writer.register_channel("/osi/sensor_view", "protobuf", schema)
            for frame, msg in zip(frames, messages, strict=True):
                writer.add_message(channel, frame.t_ns, msg.to_binary(), frame.t_ns)
            writer.finish()  # type: ignore[no-untyped-call]
        return path
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the messages carry no InterfaceVersion
        with betterosi.Writer(path) as writer:
            for frame, msg in zip(frames, messages, strict=True):
                writer.add(msg, log_time=frame.t_ns)
    return path
