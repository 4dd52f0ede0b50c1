"""Typed errors of the reach-set supervisor."""

from __future__ import annotations

__all__ = ["ReachSetError"]


class ReachSetError(Exception):
    """Root of every error the reach-set engine raises."""
