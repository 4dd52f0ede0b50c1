"""Topic role detection from message types, overridable by a profile.

Detection rules (``docs/loaders.md``):

- ego: the best-ranked ego type (``Odometry`` before ``PoseStamped`` before transforms);
  among equals, names containing ``ego``, ``localization`` or ``kinematic_state`` win;
- objects: the single best-ranked object topic (several topics of one log usually carry
  the same objects at different pipeline stages); a profile may list several;
- plan: the best-ranked plan topic, names containing ``planning`` or ``plan`` first.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.drive import TopicInfo, TopicRoles
from loaders.errors import MissingEgoTopicError, ProfileError, UnknownMessageTypeError
from loaders.message_logs.registry import family_of

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from loaders.profile import Profile

__all__ = ["EGO_HINTS", "PLAN_HINTS", "assign_roles", "detect_roles"]

#: Name fragments that make an ego candidate preferable.
EGO_HINTS: tuple[str, ...] = ("ego", "localization", "kinematic_state")
#: Name fragments that make a plan candidate preferable.
PLAN_HINTS: tuple[str, ...] = ("planning", "plan")


def _best(topics: Sequence[TopicInfo], role: str, hints: tuple[str, ...]) -> TopicInfo | None:
    candidates = []
    for info in topics:
        family = family_of(info.msgtype)
        if family is None or family.role != role:
            continue
        hinted = any(h in info.topic.lower() for h in hints)
        candidates.append((info.count == 0, family.rank, not hinted, info.topic, info))
    return min(candidates)[-1] if candidates else None


def _listing(topics: Sequence[TopicInfo]) -> str:
    return "; ".join(f"{t.topic} [{t.msgtype}]" for t in topics) or "no topics"


def _check(path: Path, topics: dict[str, TopicInfo], topic: str, role: str) -> None:
    info = topics.get(topic)
    if info is None:
        raise ProfileError(
            path,
            f"{role} topic {topic} is not in the log (present: {_listing(list(topics.values()))})",
            topic=topic,
        )
    family = family_of(info.msgtype)
    if family is None or family.role != role:
        raise UnknownMessageTypeError(
            path, f"cannot read {info.msgtype} as {role}", topic=topic, value=info.msgtype
        )


def detect_roles(path: Path, topics: Sequence[TopicInfo], profile: Profile | None) -> TopicRoles:
    """Choose the ego, object and plan topics.

    Raises:
        MissingEgoTopicError: No ego topic (listing the topics and types present).
        ProfileError: The profile names a topic the log does not have.
        UnknownMessageTypeError: A profile-named topic has a type we cannot decode.
    """
    by_name = {t.topic: t for t in topics}
    ego_topic = profile.ego if profile else None
    if ego_topic is None:
        best = _best(topics, "ego", EGO_HINTS)
        if best is None:
            raise MissingEgoTopicError(path, f"present: {_listing(topics)}")
        ego_topic = best.topic
    else:
        _check(path, by_name, ego_topic, "ego")
    objects = profile.objects if profile else None
    if objects is None:
        best = _best(topics, "objects", EGO_HINTS)
        objects = () if best is None else (best.topic,)
    else:
        for topic in objects:
            _check(path, by_name, topic, "objects")
    plan_topic = profile.plan if profile else None
    if plan_topic is None:
        best = _best(topics, "plan", PLAN_HINTS)
        plan_topic = None if best is None else best.topic
    else:
        _check(path, by_name, plan_topic, "plan")
    return TopicRoles(ego=ego_topic, objects=tuple(objects), plan=plan_topic)


def assign_roles(topics: Sequence[TopicInfo], roles: TopicRoles) -> tuple[TopicInfo, ...]:
    """Copies of ``topics`` with the ``role`` field filled from ``roles``."""
    role_of = {roles.ego: "ego", **dict.fromkeys(roles.objects, "objects")}
    if roles.plan is not None:
        role_of[roles.plan] = "plan"
    return tuple(TopicInfo(t.topic, t.msgtype, t.count, role_of.get(t.topic)) for t in topics)
