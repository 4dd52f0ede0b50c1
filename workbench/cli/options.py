"""Option types and help texts shared by the command modules (parsing only)."""

from __future__ import annotations

import enum

__all__ = ["EGO_TOPIC_HELP", "ReachMethodOption"]

#: Help of ``--ego-topic`` (info, evaluate, replay).
EGO_TOPIC_HELP = "Ego topic of a ROS/MCAP log (over the profile and the detected one)."


class ReachMethodOption(enum.StrEnum):
    """``--reach-method`` values."""

    simple = "simple"
    turn = "turn"
    bound = "bound"
