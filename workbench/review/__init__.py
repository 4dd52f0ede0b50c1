"""The review loop: a session over a drive's incidents, its terminal UI and the viewer link."""

from workbench.review.session import ReviewSession

__all__ = ["ReviewSession"]
