"""rss-workbench: replay, re-evaluate and review recorded drives in Rerun."""

from rss import compiled

# The one switch of the compiled scene modules (``rss.compiled``): before any workbench
# module imports ``rss`` submodules; without it everything runs from the sources.
compiled.activate()

__all__ = ["__version__"]

__version__ = "0.1.0"
