"""Benchmarks (``python -m bench.run``): they run the compiled scene modules when fresh.

As the workbench does at its start, the compiled build is switched on here, before any
benchmark imports ``rss`` submodules (``rss.compiled.activate``).
"""

from rss import compiled

compiled.activate()
