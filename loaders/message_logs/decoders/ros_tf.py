"""Ego pose from ``tf2_msgs/TFMessage`` on ``/tf`` (+ ``/tf_static``): the transform chain.

The buffer keeps the latest transform per child frame (``child -> parent``). The ego pose is
the composition of the chain from the vehicle frame up to the map frame, or to the odometry
frame when the chain does not reach the map frame::

    map --(map->odom, e.g. amcl)--> odom --(odom->base_link, wheel odometry)--> base_link

    T_map_base = T_map_odom * T_odom_base     (p_map = R_mo (R_ob p + t_ob) + t_mo)

A sample is produced only by a message that moves the vehicle frame: the transform whose
child is the vehicle frame or, when that one is static, the first frame up the chain with a
dynamic (``/tf``) transform. In the common tree::

    odom --(/tf, odometry)--> base_footprint --(/tf_static)--> base_link

every ``odom -> base_footprint`` update is a frame. So there is one frame per update of the
vehicle's pose; messages moving other frames only update the buffer. Frame ids are compared
without a leading ``/`` (ROS 1 style ids).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from loaders.message_logs.poses import ros_stamp_ns, yaw_from_quaternion
from loaders.message_logs.samples import EgoSample

if TYPE_CHECKING:
    from collections.abc import Iterable

__all__ = ["TF_TYPE", "TfChain", "TfFrames", "compose", "frame_id"]

#: The transform message type (normalised spelling).
TF_TYPE = "tf2_msgs/TFMessage"

#: A rigid transform: translation ``(x, y, z)`` metres and quaternion ``(x, y, z, w)``.
Transform = tuple[tuple[float, float, float], tuple[float, float, float, float]]


@dataclass(frozen=True, slots=True)
class TfFrames:
    """Frame names of the chain (profile ``[tf]``).

    Attributes:
        map_frame: The fixed frame the ego pose is expressed in.
        odom_frame: Used instead when the chain does not reach ``map_frame``.
        vehicle_frame: The ego's body frame.
    """

    map_frame: str = "map"
    odom_frame: str = "odom"
    vehicle_frame: str = "base_link"


def frame_id(name: str) -> str:
    """A frame id without the leading ``/`` of ROS 1 ids."""
    return name.lstrip("/")


def _qmul(
    a: tuple[float, float, float, float], b: tuple[float, float, float, float]
) -> tuple[float, float, float, float]:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def _rotate(
    q: tuple[float, float, float, float], v: tuple[float, float, float]
) -> tuple[float, float, float]:
    qx, qy, qz, qw = q
    vx, vy, vz = v
    # v' = v + 2 w (q x v) + 2 q x (q x v)
    cx, cy, cz = qy * vz - qz * vy, qz * vx - qx * vz, qx * vy - qy * vx
    dx, dy, dz = qy * cz - qz * cy, qz * cx - qx * cz, qx * cy - qy * cx
    return (vx + 2 * (qw * cx + dx), vy + 2 * (qw * cy + dy), vz + 2 * (qw * cz + dz))


def compose(parent: Transform, child: Transform) -> Transform:
    """``parent * child``: a pose in the child's parent frame re-expressed one level up."""
    (t1, q1), (t2, q2) = parent, child
    r = _rotate(q1, t2)
    return (t1[0] + r[0], t1[1] + r[1], t1[2] + r[2]), _qmul(q1, q2)


def _normalised(q: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    n = math.sqrt(sum(c * c for c in q))
    return q if n == 0 else (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


@dataclass(slots=True)
class TfChain:
    """Stateful ego decoder for ``/tf``: feed messages, get a sample per vehicle update."""

    frames: TfFrames = field(default_factory=TfFrames)
    _edges: dict[str, tuple[str, Transform]] = field(default_factory=dict)
    _static: set[str] = field(default_factory=set)

    def add_static(self, transforms: Iterable[Any]) -> None:
        """Add ``/tf_static`` transforms (``geometry_msgs/TransformStamped``)."""
        for tr in transforms:
            self._static.add(self._add(tr))

    def moving_frame(self) -> str:
        """The frame whose ``/tf`` updates move the vehicle: up its static links, if any."""
        node = self.frames.vehicle_frame
        seen = {node}
        while node in self._static:
            parent = self._edges[node][0]
            if parent in seen:  # a loop of static links: not a chain
                break
            seen.add(parent)
            node = parent
        return node

    def _add(self, tr: Any) -> str:
        t, q = tr.transform.translation, tr.transform.rotation
        child = frame_id(tr.child_frame_id)
        transform: Transform = (
            (float(t.x), float(t.y), float(t.z)),
            _normalised((float(q.x), float(q.y), float(q.z), float(q.w))),
        )
        self._edges[child] = (frame_id(tr.header.frame_id), transform)
        return child

    def resolve(self) -> Transform | None:
        """The vehicle pose in the map frame (else the odometry frame), or None."""
        frames = self.frames
        pose: Transform = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        node = frames.vehicle_frame
        reached_odom: Transform | None = None
        seen = {node}
        while node != frames.map_frame:
            if node == frames.odom_frame:
                reached_odom = pose
            edge = self._edges.get(node)
            if edge is None:
                return reached_odom
            node, transform = edge
            if node in seen:  # a loop in the tree: not a chain
                return reached_odom
            seen.add(node)
            pose = compose(transform, pose)
        return pose

    def decode(self, msg: Any) -> EgoSample | None:
        """Update the buffer from a ``TFMessage``; a sample if the vehicle frame moved."""
        stamp: int | None = None
        moving = self.moving_frame()
        for tr in msg.transforms:
            child = self._add(tr)
            self._static.discard(child)
            if child == moving:
                stamp = ros_stamp_ns(tr.header.stamp)
        if stamp is None:
            return None
        pose = self.resolve()
        if pose is None:
            return None
        (x, y, z), (qx, qy, qz, qw) = pose
        return EgoSample(stamp, x, y, z, yaw_from_quaternion(qx, qy, qz, qw))
