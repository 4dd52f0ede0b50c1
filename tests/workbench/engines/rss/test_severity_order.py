"""The severity order of RSS incidents: shortfall, then ratio, TTC, deceleration, duration."""

from __future__ import annotations

from workbench.engines.rss.severity_order import severity_key


def _incident(
    name: str,
    *,
    shortfall: float | None = None,
    ratio: float = 0.5,
    ttc: float | None = None,
    decel: float | None = None,
    duration: float = 1.0,
) -> tuple[str, tuple[float, ...]]:
    key = severity_key(
        shortfall_mps2=shortfall,
        distance_ratio=ratio,
        ttc_s=ttc,
        required_decel_mps2=decel,
        duration_s=duration,
    )
    return name, key


def test_order_follows_the_documented_criteria():
    incidents = [
        _incident("calm", ratio=0.9),
        _incident("long", ratio=0.9, duration=5.0),
        _incident("close", ratio=0.1),
        _incident("late brake", shortfall=2.0, ratio=0.95),
        _incident("later brake", shortfall=4.0, ratio=0.95),
        _incident("imminent", ratio=0.1, ttc=0.8),
        _incident("hard", ratio=0.1, ttc=0.8, decel=6.0),
    ]
    ranked = [name for name, key in sorted(incidents, key=lambda item: item[1])]
    assert ranked == ["later brake", "late brake", "hard", "imminent", "close", "long", "calm"]
