"""Rule-based reachable-set supervisor (pure: numpy/shapely in, verdicts out)."""

from reachsets.errors import ReachSetError

__all__ = ["ReachSetError"]
