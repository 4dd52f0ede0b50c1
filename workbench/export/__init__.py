"""Export labeled incident clips: MCAP, OpenLABEL, ``.rrd`` and a thumbnail per incident."""

from workbench.export.plan import ClipPlan, Selection, plan_clips, safe_stem
from workbench.export.run import ExportedClip, ExportSummary, export_clips

__all__ = [
    "ClipPlan",
    "ExportSummary",
    "ExportedClip",
    "Selection",
    "export_clips",
    "plan_clips",
    "safe_stem",
]
