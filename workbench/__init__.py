"""rss-workbench: replay, re-evaluate and review recorded drives in Rerun."""

__all__ = ["__version__"]

__version__ = "0.1.0"
