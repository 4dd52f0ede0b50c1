"""Per-object data quality of a drive: implausible speeds, accelerations, headings and jumps.

Pure checks over a whole drive's tracks (docs/data_quality.md): ``tracks_from_frames`` (or a
:class:`TrackCollector` fed chunk by chunk) then :func:`check_tracks`.
"""

from workbench.quality.bounds import ClassLimits, QualityBounds
from workbench.quality.checks import Finding, Kind, check_tracks
from workbench.quality.tracks import EGO_ID, TrackCollector, Tracks, tracks_from_frames

__all__ = [
    "EGO_ID",
    "ClassLimits",
    "Finding",
    "Kind",
    "QualityBounds",
    "TrackCollector",
    "Tracks",
    "check_tracks",
    "tracks_from_frames",
]
