"""The golden harness: every engine's per-frame records on every sample log, per variant.

``test_goldens.py`` compares; ``python -m tests.goldens.update`` (``make goldens``) rewrites
the files under ``expected/`` and reports what changed. docs/testing.md describes both.
"""
