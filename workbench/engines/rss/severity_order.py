"""The documented severity order of RSS incidents (docs/rss.md, "Severity"), as a sort key."""

from __future__ import annotations

import math

__all__ = ["severity_key"]


def severity_key(
    *,
    shortfall_mps2: float | None,
    distance_ratio: float,
    ttc_s: float | None,
    required_decel_mps2: float | None,
    duration_s: float,
) -> tuple[float, float, float, float, float]:
    """Sort key, most severe first (``sorted(incidents, key=...)``).

    Args:
        shortfall_mps2: Worst compliance shortfall of a party after its response was due
            (``None`` or 0: every due response was proper).
        distance_ratio: Worst (smallest) current / safe distance ratio.
        ttc_s: Smallest time to collision (``None``: never closing).
        required_decel_mps2: Largest deceleration the situation demanded (``None``: 0).
        duration_s: Duration of the incident.

    Returns:
        ``(-shortfall, ratio, ttc, -deceleration, -duration)``.
    """
    return (
        -(shortfall_mps2 or 0.0),
        distance_ratio,
        math.inf if ttc_s is None else ttc_s,
        -(required_decel_mps2 or 0.0),
        -duration_s,
    )
