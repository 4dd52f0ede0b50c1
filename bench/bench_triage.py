"""Cost of triage per frame beside the RSS path it sits on (issue 27's target: <= 1.3x).

For each drive (the 11 NGSIM scenarios of ``../shared/external`` where present, else the
sample logs) the RSS engine's chunks are produced once and timed (the RSS path: loader, scene
creation, structured RSS, object side, compliance), then the same chunks go through the
incident detector, which holds every triage addition: each incident's own-object physical
facts (gap, time to collision along the path, required deceleration, closing speed), the
per-object data-quality checks, the flags of suspect incidents, the one severity order and the
grouping into events. Both are wall-clock times of one process, one after the other.
"""

from __future__ import annotations

import time
from pathlib import Path

from workbench.driver import DriveRun
from workbench.incidents import IncidentDetector, IncidentRequest, group_events

_ROOT = Path(__file__).resolve().parent.parent
_NGSIM = _ROOT.parent / "shared" / "external" / "commonroad_ngsim"
_REPEATS = 3


def _drives(quick: bool) -> list[Path]:  # noqa: FBT001
    found = sorted(_NGSIM.glob("*.xml")) if _NGSIM.is_dir() else []
    if not found:
        found = sorted((_ROOT / "sample_logs").glob("*.mcap"))
    return found[:3] if quick else found


def _measure(log: Path) -> tuple[int, float, float, float]:
    """``(frames, rss_ms, detector_ms, quality_ms)`` per drive, best of ``_REPEATS``."""
    request = IncidentRequest(log, engines=("rss",))
    best_rss = best_det = best_q = float("inf")
    frames = 0
    for _ in range(_REPEATS):
        drive = request.open_drive()
        try:
            runners, ego = request.engines_for(drive)
            t0 = time.perf_counter()
            chunks = list(DriveRun(drive, runners, ego_size=ego))
            t_rss = time.perf_counter() - t0
        finally:
            drive.close()
        t0 = time.perf_counter()
        detector = IncidentDetector("bench", request.settings)
        for chunk in chunks:
            detector.add_chunk(chunk)
        t1 = time.perf_counter()
        findings = detector.findings()
        t_q = time.perf_counter() - t1
        group_events(detector.incidents(findings))
        t_det = time.perf_counter() - t0
        frames = sum(len(c.frames) for c in chunks)
        best_rss, best_det, best_q = min(best_rss, t_rss), min(best_det, t_det), min(best_q, t_q)
    return frames, best_rss * 1e3, best_det * 1e3, best_q * 1e3


def run(quick: bool) -> str:  # noqa: FBT001 - the harness calls run(quick=...)
    """Measure and return the Markdown section."""
    lines = [
        "## Triage cost per frame (issue 27)",
        "",
        "RSS path = loader + scene creation + structured RSS (both sides) + compliance, the",
        "engine's chunks of a whole drive; triage = the incident detector on those chunks",
        "(own-object facts, data-quality checks, suspect flags, severity order, events), of",
        "which data quality alone is a column. Best of 3, one process, `--engines rss`,",
        "defaults (`auto` profile).",
        "",
        (
            "| drive | frames | RSS path ms/frame | triage ms/frame | of which data quality |"
            " (RSS + triage) / RSS |"
        ),
        "|---|---:|---:|---:|---:|---:|",
    ]
    total_rss = total_det = 0.0
    for log in _drives(quick):
        frames, rss_ms, det_ms, q_ms = _measure(log)
        if frames == 0:
            continue
        total_rss, total_det = total_rss + rss_ms, total_det + det_ms
        lines.append(
            f"| `{log.stem}` | {frames} | {rss_ms / frames:.2f} | {det_ms / frames:.3f} "
            f"| {q_ms / frames:.3f} | {(rss_ms + det_ms) / rss_ms:.3f}x |"
        )
    if total_rss > 0:
        lines.append(f"| all | | | | | **{(total_rss + total_det) / total_rss:.3f}x** |")
    return "\n".join(lines)
