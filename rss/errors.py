"""Typed errors of the RSS engine."""

from __future__ import annotations

__all__ = ["RssError"]


class RssError(Exception):
    """Root of every error the RSS engine raises (bad parameters, bad constellations)."""
