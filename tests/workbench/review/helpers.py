"""A small incident report for review tests (no engine run)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from workbench.incidents import Incident, IncidentReport, Severity

if TYPE_CHECKING:
    from workbench.incidents.model import Fact

T0 = 1_700_000_000_000_000_000


def incident(
    n: int, margin: float, *, drive: str = "abc", facts: dict[str, Fact] | None = None
) -> Incident:
    """Incident ``n`` of object ``n`` (frames 10n..10n+4) with this margin and facts."""
    return Incident(
        id=f"rss-{n:06d}-{drive}",
        engine="rss",
        objects=(str(n),),
        cause="RSS BrakeMin",
        start_frame=10 * n,
        end_frame=10 * n + 4,
        start_ns=T0 + n * 10**9,
        end_ns=T0 + n * 10**9 + 4 * 10**8,
        severity=Severity(margin, 5, 0.4, facts=facts or {}),
    )


def report(count: int = 3) -> IncidentReport:
    """``count`` incidents, worst first."""
    found = tuple(incident(n, float(n)) for n in range(1, count + 1))
    return IncidentReport(
        log=Path("drive.mcap"),
        drive_hash="d" * 64,
        settings={"engines": ["rss"], "merge_gap_s": 0.0},
        incidents=found,
        frame_times=tuple((f, T0 + f * 10**8) for f in range(10 * count + 10)),
        start_ns=T0,
    )
