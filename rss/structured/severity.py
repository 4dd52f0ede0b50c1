"""Severity facts of every constellation: distance ratio, time to collision, deceleration.

Computed from the checks' distances and the lane-frame speeds, ``(C,)`` arrays:

* ``distance_ratio`` = current / safe distance of the dimension that is *closer to safe*:
  ``max(lon ratio, lat ratio)`` (a constellation is dangerous only while both are below 1,
  so the larger one says how far it is from being safe again); the lateral ratio is the
  smaller of the evaluated sides; 0 for a dimension whose safe distance is 0 but unsafe
  (overlap, intersections' lateral state). ``inf`` when nothing was evaluated.
* ``ttc_s``: longitudinal time to collision at constant speeds, gap / closing speed, in the
  lane frame (mid of each speed interval): same direction ``v_rear - v_front``, opposite
  direction ``v_ego + v_other`` while the other is ahead; ``inf`` when not closing,
  overlapping longitudinally or at intersections.
* ``required_decel_mps2``: the deceleration that removes the closing speed within the gap
  (DRAC, closing² / 2 gap; the front vehicle keeping its speed), positive; 0 when not
  closing, ``inf`` when closing with no gap.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.physics import DISTANCE_MAX_M
from rss.structured.states import LongitudinalPosition

if TYPE_CHECKING:
    from rss.arrays import FloatArray
    from rss.structured.batch import ConstellationBatch
    from rss.structured.checks import LateralSide, RawStates
    from rss.structured.extraction import Relative

__all__ = ["Severity", "severity"]


@dataclass(frozen=True)
class Severity:
    """Severity facts of ``C`` constellations (see the module docstring).

    Attributes:
        distance_ratio: ``(C,)`` current / safe distance of the dimension closer to safe.
        ttc_s: ``(C,)`` longitudinal time to collision [s] (``inf``: none).
        required_decel_mps2: ``(C,)`` deceleration removing the closing speed [m/s²].
    """

    distance_ratio: FloatArray
    ttc_s: FloatArray
    required_decel_mps2: FloatArray


def _ratio(current: FloatArray, safe: FloatArray) -> FloatArray:
    evaluated = safe < DISTANCE_MAX_M
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(safe > 0.0, current / np.where(safe > 0.0, safe, 1.0), 0.0)
    return np.where(evaluated, ratio, np.inf)


def _lateral_ratio(left: LateralSide, right: LateralSide) -> FloatArray:
    left_r = _ratio(left.current_distance_m, left.safe_distance_m)
    right_r = _ratio(right.current_distance_m, right.safe_distance_m)
    return np.minimum(left_r, right_r)


def severity(batch: ConstellationBatch, rel: Relative, states: RawStates) -> Severity:
    """Severity facts of every constellation.

    Args:
        batch: ``C`` constellations (merged, as checked).
        rel: Their relative situation.
        states: Their (memory-adjusted) states.

    Returns:
        ``(C,)`` facts.
    """
    lon = _ratio(states.lon_current_distance_m, states.lon_safe_distance_m)
    lat = _lateral_ratio(states.left, states.right)
    ratio = np.maximum(np.where(np.isfinite(lon), lon, 0.0), np.where(np.isfinite(lat), lat, 0.0))
    ratio = np.where(np.isfinite(lon) | np.isfinite(lat), ratio, np.inf)

    ego_v = 0.5 * (batch.ego.speed_lon_min_mps + batch.ego.speed_lon_max_mps)
    other_v = 0.5 * (batch.other.speed_lon_min_mps + batch.other.speed_lon_max_mps)
    ctype = batch.constellation_type
    ego_behind = rel.lon_position == LongitudinalPosition.AtBack
    ego_ahead = rel.lon_position == LongitudinalPosition.InFront
    same = ctype == ConstellationType.SameDirection
    opposite = ctype == ConstellationType.OppositeDirection
    closing = np.where(
        same & ego_behind,
        ego_v - other_v,
        np.where(
            same & ego_ahead, other_v - ego_v, np.where(opposite & ego_behind, ego_v + other_v, 0.0)
        ),
    )
    gap = rel.lon_distance_m
    approaching = closing > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        ttc = np.where(approaching, gap / np.where(approaching, closing, 1.0), np.inf)
        decel = np.where(
            approaching,
            np.where(gap > 0.0, closing**2 / (2.0 * np.where(gap > 0.0, gap, 1.0)), np.inf),
            0.0,
        )
    return Severity(
        distance_ratio=np.asarray(ratio, dtype=np.float64),
        ttc_s=np.asarray(ttc, dtype=np.float64),
        required_decel_mps2=np.asarray(decel, dtype=np.float64),
    )
