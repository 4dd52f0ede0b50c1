"""What the viewer shows of RSS responsibility and proper-response compliance.

Per object a state lane of who must act (``rss/structured/duty/<id>``: ``ego must act``,
``object must act``, ``both must act``, ``no duty``), and per object and party the
longitudinal acceleration its proper response allows next to the one measured on the
recording (``plots/rss/compliance/<id>/<party>_allowed|_measured`` [m/s²], only in frames
where that party must act). Definitions: docs/rss.md, "Responsibility" and "Proper-response
compliance".
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from workbench.engines.rss.verdict import RssVerdict

__all__ = ["DUTY_STATES", "NO_DUTY", "DutyColumns", "layout_duties"]

#: Duty lane values and colours, most demanding first.
DUTY_STATES = {
    "both must act": 0xEF5350FF,
    "ego must act": 0xFFA726FF,
    "object must act": 0x42A5F5FF,
    "no duty": 0x616161FF,
}
NO_DUTY = "no duty"


@dataclass(frozen=True, slots=True)
class DutyColumns:
    """Responsibility and compliance display data for ``N`` frames.

    Attributes:
        duty_states: Per object label that must act in some frame, ``(N,)`` values of
            :data:`DUTY_STATES`.
        compliance: Per ``"<label>/<party>_allowed"`` and ``"<label>/<party>_measured"``,
            ``(rows, values)``: chunk rows with a finite value and the values [m/s²].
    """

    duty_states: dict[str, list[str]]
    compliance: dict[str, tuple[NDArray[np.int64], NDArray[np.float64]]]


def layout_duties(verdicts: Sequence[RssVerdict]) -> DutyColumns:
    """Duty lanes and compliance series of a chunk's RSS verdicts."""
    n = len(verdicts)
    duties: dict[str, list[str]] = {}
    series: dict[str, tuple[list[int], list[float]]] = {}
    for row, verdict in enumerate(verdicts):
        for label, who in verdict.responsibility().items():
            duties.setdefault(label, [NO_DUTY] * n)[row] = f"{who} must act"
        for label, duty in verdict.obligations:
            for kind, value in (
                ("allowed", duty.required_max_mps2),
                ("measured", duty.measured_mps2),
            ):
                if value is not None and np.isfinite(value):
                    key = f"{label}/{duty.party!s}_{kind}"
                    rows, values = series.setdefault(key, ([], []))
                    rows.append(row)
                    values.append(value)
    compliance = {
        key: (np.array(rows, dtype=np.int64), np.array(values, dtype=np.float64))
        for key, (rows, values) in sorted(series.items())
    }
    return DutyColumns(dict(sorted(duties.items())), compliance)
