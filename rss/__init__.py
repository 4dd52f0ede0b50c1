"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out)."""

from rss.errors import RssError

__all__ = ["RssError"]
