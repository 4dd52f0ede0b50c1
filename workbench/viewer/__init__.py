"""Replays into Rerun and where they go (``.rrd`` file, spawned viewer, local server)."""

from workbench.viewer.outputs import LOCALHOST, ReplayError
from workbench.viewer.replay import APPLICATION_ID, ReplaySummary, replay_drive

__all__ = ["APPLICATION_ID", "LOCALHOST", "ReplayError", "ReplaySummary", "replay_drive"]
