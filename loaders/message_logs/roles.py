"""Topic role detection from message types, overridable by a profile.

Detection rules (``docs/loaders.md``):

- ego: ``--ego-topic`` / the profile if given; else topics named like ground truth
  (``groundtruth``, ``ground_truth``, ``gt``) before every other (estimates: ORB-SLAM,
  odometry), then the best-ranked ego type (``Odometry`` before
  ``PoseStamped`` before transforms before GNSS), then names containing ``ego``,
  ``localization`` or ``kinematic_state``, then the name order (``/tf_static`` never);
- objects: the single best-ranked object topic (several topics of one log usually carry
  the same objects at different pipeline stages); a profile may list several;
- plan: the best-ranked plan topic, names containing ``planning`` or ``plan`` first.
"""

from __future__ import annotations

import re
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
#: Topic names that read as ground truth (whole words: ``/gt/pose``, ``/groundtruth``).
_GROUND_TRUTH = re.compile(r"ground[_-]?truth|(^|[^a-z])gt([^a-z]|$)")
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


def _truth_rank(topic: str) -> int:
    return 0 if _GROUND_TRUTH.search(topic.lower()) else 1


def _ego_candidates(topics: Sequence[TopicInfo]) -> tuple[list[str], str]:
    """Ego candidates best first and the rule that put the first one first."""
    keys = []
    for info in topics:
        family = family_of(info.msgtype)
        if family is None or family.role != "ego" or info.topic == "/tf_static":
            continue
        hinted = any(h in info.topic.lower() for h in EGO_HINTS)
        keys.append((info.count == 0, _truth_rank(info.topic), family.rank, not hinted, info.topic))
    keys.sort()
    if len(keys) < 2:  # noqa: PLR2004 - one candidate needs no rule
        return [k[-1] for k in keys], "only candidate"
    rules = (
        "has messages",
        "ground truth before estimates",
        "message type rank",
        "name hint (ego, localization, kinematic_state)",
        "name order",
    )
    first, second = keys[0], keys[1]
    rule = next(r for r, a, b in zip(rules, first, second, strict=True) if a != b)
    return [k[-1] for k in keys], rule


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


def detect_roles(
    path: Path,
    topics: Sequence[TopicInfo],
    profile: Profile | None,
    ego_topic: str | None = None,
) -> TopicRoles:
    """Choose the ego, object and plan topics.

    ``ego_topic`` (``--ego-topic``) overrides the profile's and the detected ego topic.

    Raises:
        MissingEgoTopicError: No ego topic (listing the topics and types present).
        ProfileError: The profile names a topic the log does not have.
        UnknownMessageTypeError: A profile-named topic has a type we cannot decode.
    """
    by_name = {t.topic: t for t in topics}
    candidates, rule = _ego_candidates(topics)
    if ego_topic is not None:
        rule = "--ego-topic"
    elif profile is not None and profile.ego is not None:
        ego_topic, rule = profile.ego, f"profile {profile.source or ''}".strip()
    if ego_topic is None:
        if not candidates:
            raise MissingEgoTopicError(path, f"present: {_listing(topics)}")
        ego_topic = candidates[0]
    else:
        _check(path, by_name, ego_topic, "ego")
    objects = profile.objects if profile else None
    ego_family = family_of(by_name[ego_topic].msgtype)
    if objects is None and ego_family is not None and ego_family.carries_objects:
        objects = (ego_topic,)  # ASAM OSI: the ground truth holds the objects too
    if objects is None:
        best = _best(topics, "objects", EGO_HINTS)
        objects = () if best is None else (best.topic,)
    else:
        for topic in objects:
            if topic != ego_topic or ego_family is None or not ego_family.carries_objects:
                _check(path, by_name, topic, "objects")
    plan_topic = profile.plan if profile else None
    if plan_topic is None:
        best = _best(topics, "plan", PLAN_HINTS)
        plan_topic = None if best is None else best.topic
    else:
        _check(path, by_name, plan_topic, "plan")
    return TopicRoles(
        ego=ego_topic,
        objects=tuple(objects),
        plan=plan_topic,
        ego_candidates=tuple(candidates),
        ego_rule=rule,
    )


def assign_roles(topics: Sequence[TopicInfo], roles: TopicRoles) -> tuple[TopicInfo, ...]:
    """Copies of ``topics`` with the ``role`` field filled from ``roles``."""
    role_of = dict.fromkeys(roles.objects, "objects")
    role_of[roles.ego] = "ego+objects" if roles.ego in role_of else "ego"  # OSI ground truth
    if roles.plan is not None:
        role_of[roles.plan] = "plan"
    return tuple(TopicInfo(t.topic, t.msgtype, t.count, role_of.get(t.topic)) for t in topics)
