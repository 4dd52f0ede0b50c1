"""Ego decoders built per read: stateless message families and the stateful TF / GNSS ones.

| ego type | topics read | state |
|---|---|---|
| ``tf2_msgs/TFMessage`` | ``/tf``; ``/tf_static`` once beforehand | transform buffer |
| ``sensor_msgs/NavSatFix`` | the fix topic and the IMU topic, if any | origin, IMU yaw |
| every other ego type | the ego topic | none |

``/tf_static`` is read in full before the pass (latched transforms are published once at
the start and would be missed by a windowed read).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from loaders.message_logs.decoders.ros_gnss import IMU_TYPE, NAVSATFIX_TYPE, GnssEgo
from loaders.message_logs.decoders.ros_tf import TF_TYPE, TfChain, TfFrames
from loaders.message_logs.registry import family_of, normalize_msgtype

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from loaders.drive import TopicInfo, TopicRoles
    from loaders.maps.model import LaneMap
    from loaders.message_logs.source import MessageSource
    from loaders.profile import Profile

__all__ = [
    "STATIC_TF_TOPIC",
    "EgoSettings",
    "ego_decoders",
    "ego_settings",
    "imu_topic",
    "static_transforms",
]

#: Latched transforms, read once before the pass.
STATIC_TF_TOPIC = "/tf_static"


@dataclass(frozen=True, slots=True)
class EgoSettings:
    """What the stateful ego decoders need.

    Attributes:
        tf: Frame names of the TF chain.
        imu_topic: IMU topic giving the GNSS heading, if any.
        origin_deg: ``(lat, lon)`` origin of the local frame (the map's); None: first fix.
        static: ``/tf_static`` transforms (``TransformStamped``), in log order.
    """

    tf: TfFrames = field(default_factory=TfFrames)
    imu_topic: str | None = None
    origin_deg: tuple[float, float] | None = None
    static: tuple[Any, ...] = ()


def imu_topic(topics: Sequence[TopicInfo], named: str | None) -> str | None:
    """The IMU topic: ``named`` (the profile's) or the first ``sensor_msgs/Imu`` topic by name."""
    if named is not None:
        return named
    imus = sorted(t.topic for t in topics if normalize_msgtype(t.msgtype) == IMU_TYPE and t.count)
    return imus[0] if imus else None


def static_transforms(source: MessageSource) -> tuple[Any, ...]:
    """Every transform on ``/tf_static`` (empty when the log has none)."""
    if not any(t.topic == STATIC_TF_TOPIC for t in source.topics):
        return ()
    out: list[Any] = []
    for _, _, msg in source.messages((STATIC_TF_TOPIC,), None, None):
        out.extend(msg.transforms)
    return tuple(out)


def ego_settings(
    source: MessageSource,
    roles: TopicRoles,
    profile: Profile | None,
    lane_map: LaneMap | None,
) -> EgoSettings:
    """Settings for the ego topic of ``roles``: what its decoder needs besides messages."""
    kind = normalize_msgtype(next(t.msgtype for t in source.topics if t.topic == roles.ego))
    tf = profile.tf if profile is not None else TfFrames()
    if kind == TF_TYPE:
        return EgoSettings(tf=tf, static=static_transforms(source))
    if kind == NAVSATFIX_TYPE:
        return EgoSettings(
            tf=tf,
            imu_topic=imu_topic(source.topics, profile.imu if profile else None),
            origin_deg=None if lane_map is None else lane_map.origin_deg,
        )
    return EgoSettings(tf=tf)


def ego_decoders(
    topic: str, msgtype: str, settings: EgoSettings
) -> dict[str, Callable[[Any], Any]]:
    """Fresh decoders (topic → callable) for the ego topic and its auxiliary topics.

    A decoder returns an ``EgoSample`` or None (the message only updated state).
    """
    kind = normalize_msgtype(msgtype)
    if kind == TF_TYPE:
        chain = TfChain(settings.tf)
        chain.add_static(settings.static)
        return {topic: chain.decode}
    if kind == NAVSATFIX_TYPE:
        gnss = GnssEgo(settings.origin_deg)
        out: dict[str, Callable[[Any], Any]] = {topic: gnss.decode_fix}
        if settings.imu_topic is not None:
            out[settings.imu_topic] = gnss.decode_imu
        return out
    family = family_of(msgtype)
    assert family is not None  # checked by detect_roles
    assert family.decode is not None  # every stateless ego family has a decoder
    return {topic: family.decode}
