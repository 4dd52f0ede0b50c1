"""The frame's proper response and acceleration restrictions of a structured-RSS verdict (pure)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.structured.states import LateralResponse, LongitudinalResponse

if TYPE_CHECKING:
    from workbench.engines.rss.verdict import RssVerdict

__all__ = ["accel_bound", "response_name"]

#: Bounds at or beyond this magnitude mean "unbounded" and are not plotted.
_UNBOUNDED_MPS2 = 999.0


def response_name(verdict: RssVerdict, key: str) -> str:
    """The frame's response name for a ``layout.RESPONSE_LANES`` key (``None`` without one)."""
    if verdict.result is None:
        return "None"
    names = LongitudinalResponse if key == "longitudinal_response" else LateralResponse
    return str(names(int(getattr(verdict.result.responses, key)[0])))


def accel_bound(verdict: RssVerdict, name: str) -> float:
    """One acceleration bound [m/s²]; NaN without constellations or when unbounded."""
    if verdict.result is None:
        return float("nan")
    value = float(getattr(verdict.result.responses, name)[0])
    if not np.isfinite(value) or abs(value) >= _UNBOUNDED_MPS2:
        return float("nan")
    return value
