"""Option types and help texts shared by the command modules (parsing only)."""

from __future__ import annotations

import enum

__all__ = ["ReachMethodOption"]


class ReachMethodOption(enum.StrEnum):
    """``--reach-method`` values."""

    simple = "simple"
    turn = "turn"
    bound = "bound"
