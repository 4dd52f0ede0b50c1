"""ASAM OSI ``GroundTruth`` and ``SensorView`` (betterosi message classes): ego and objects.

One OSI message holds the whole scene, so its decoder returns both the ego sample and the
object list (``EgoWithObjects``):

- ego = the moving object whose id is ``host_vehicle_id`` (``SensorView.host_vehicle_id``,
  else that of its ``global_ground_truth``): ``base.position`` (the bounding-box centre),
  ``base.orientation.yaw``, speed = ``base.velocity`` (global frame) projected on the
  heading, yaw rate = ``base.orientation_rate.yaw``; a missing velocity or rate is NaN
  (finite differences); ``base.dimension`` is the ego size (when all three are positive);
- objects = every other moving object: ``base.position``/``orientation.yaw``, map-frame
  ``base.velocity`` (estimated per id when some object has none), ``base.dimension`` (full
  length/width/height), class from ``type`` and ``vehicle_classification.type``
  (:data:`VEHICLE_CLASSES`);
- stationary objects, lanes and lane boundaries are not read (use ``--map``).

The time is ``timestamp`` (seconds + nanos).
"""

from __future__ import annotations

import math
from typing import Any

from loaders.message_logs.samples import EgoSample, EgoWithObjects, ObjectColumns
from loaders.records import ObjectClass

__all__ = [
    "OSI_GROUND_TRUTH",
    "OSI_SENSOR_VIEW",
    "VEHICLE_CLASSES",
    "decode_ground_truth",
    "decode_sensor_view",
    "osi_stamp_ns",
]

#: Normalised type names of the OSI messages read (MCAP schema ``osi3.<Type>`` or ``<Type>``).
OSI_GROUND_TRUTH = "osi3.GroundTruth"
OSI_SENSOR_VIEW = "osi3.SensorView"

_PEDESTRIAN = 3  # MovingObject.Type.PEDESTRIAN
_VEHICLE = 2  # MovingObject.Type.VEHICLE
#: ``MovingObject.VehicleClassification.Type`` values → class (others: unknown).
VEHICLE_CLASSES: dict[int, ObjectClass] = {
    2: ObjectClass.CAR,  # SMALL_CAR
    3: ObjectClass.CAR,  # COMPACT_CAR
    4: ObjectClass.CAR,  # CAR
    5: ObjectClass.CAR,  # LUXURY_CAR
    6: ObjectClass.CAR,  # DELIVERY_VAN
    7: ObjectClass.TRUCK,  # HEAVY_TRUCK
    16: ObjectClass.TRUCK,  # SEMITRACTOR
    8: ObjectClass.TRUCK,  # SEMITRAILER
    9: ObjectClass.TRUCK,  # TRAILER
    10: ObjectClass.MOTORCYCLE,  # MOTORBIKE
    11: ObjectClass.BICYCLE,  # BICYCLE
    12: ObjectClass.BUS,  # BUS
}
_NAN = float("nan")


def osi_stamp_ns(msg: Any) -> int | None:
    """``timestamp`` (``seconds`` + ``nanos``) in ns, or None when unset."""
    stamp = msg.timestamp
    if stamp is None:
        return None
    return int(stamp.seconds or 0) * 1_000_000_000 + int(stamp.nanos or 0)


def _class(obj: Any) -> ObjectClass:
    kind = int(obj.type or 0)
    if kind == _PEDESTRIAN:
        return ObjectClass.PEDESTRIAN
    if kind != _VEHICLE or obj.vehicle_classification is None:
        return ObjectClass.UNKNOWN
    return VEHICLE_CLASSES.get(int(obj.vehicle_classification.type or 0), ObjectClass.UNKNOWN)


def _xyz(vector: Any) -> tuple[float, float, float]:
    if vector is None:
        return _NAN, _NAN, _NAN
    return float(vector.x or 0.0), float(vector.y or 0.0), float(vector.z or 0.0)


def _yaw(base: Any) -> float:
    return _NAN if base.orientation is None else float(base.orientation.yaw or 0.0)


def _size(dim: Any) -> tuple[float, float, float] | None:
    """``(length, width, height)`` of a ``Dimension3d`` when all three are positive."""
    if dim is None:
        return None
    size = (float(dim.length or 0.0), float(dim.width or 0.0), float(dim.height or 0.0))
    return size if all(math.isfinite(v) and v > 0 for v in size) else None


def _ego(stamp: int | None, base: Any) -> EgoSample:
    x, y, z = _xyz(base.position)
    yaw = _yaw(base)
    vx, vy, _ = _xyz(base.velocity)
    rate = base.orientation_rate
    return EgoSample(
        stamp,
        x,
        y,
        z,
        yaw,
        speed_mps=vx * math.cos(yaw) + vy * math.sin(yaw),
        yaw_rate_radps=_NAN if rate is None else float(rate.yaw or 0.0),
        size_m=_size(base.dimension),
    )


def _id(identifier: Any) -> int | None:
    return None if identifier is None else int(identifier.value or 0)


def _decode(gt: Any, host: int | None) -> EgoWithObjects:
    if host is None:
        msg = "OSI GroundTruth without host_vehicle_id (the ego)"
        raise ValueError(msg)
    stamp = osi_stamp_ns(gt)
    ego: EgoSample | None = None
    ids, classes, rows = [], [], []
    with_velocity = True
    for obj in gt.moving_object:
        base = obj.base
        if base is None:
            continue
        oid = _id(obj.id)
        if oid == host:
            ego = _ego(stamp, base)
            continue
        vx, vy, _ = _xyz(base.velocity)
        with_velocity = with_velocity and base.velocity is not None
        dim = base.dimension
        size = (_NAN,) * 3 if dim is None else (dim.length, dim.width, dim.height)
        ids.append(str(oid))
        classes.append(_class(obj))
        rows.append((*_xyz(base.position), _yaw(base), vx, vy, *(float(s or 0.0) for s in size)))
    if ego is None:
        msg = f"OSI GroundTruth has no moving object with the host_vehicle_id {host}"
        raise ValueError(msg)
    objects = ObjectColumns.from_rows(stamp, ids, classes, rows, has_velocity=with_velocity)
    return EgoWithObjects(ego, objects)


def decode_ground_truth(gt: Any) -> EgoWithObjects:
    """``osi3.GroundTruth``: the host vehicle as ego, the other moving objects as objects."""
    return _decode(gt, _id(gt.host_vehicle_id))


def decode_sensor_view(sv: Any) -> EgoWithObjects:
    """``osi3.SensorView``: its ``global_ground_truth`` (host id from the view, else the GT)."""
    gt = sv.global_ground_truth
    if gt is None:
        msg = "OSI SensorView without global_ground_truth"
        raise ValueError(msg)
    host = _id(sv.host_vehicle_id)
    return _decode(gt, _id(gt.host_vehicle_id) if host is None else host)
