"""Consumers of the driver's chunks: per-frame JSON lines, violation intervals, Rerun."""
