"""The standstill rule of the review profiles: standing vehicles stay, two standing ones are safe.

ad-rss 5.0 assumes every participant may accelerate with ``accel_max`` during its response
time, also from a standstill: two cars standing in a queue 2 m apart are "dangerous" under
the ``adrss-5.0`` dynamics (a standing follower with rho 2 s, 3.5 m/s^2 needs 13.1 m). The
review profiles (docs/rss.md, "Standstill rule") apply, per constellation, before the checks:

* a party whose lane-frame speeds are all within ``standstill_speed_mps`` (longitudinal
  ``speed_lon_max`` and both lateral bounds) is assumed to keep standing during its
  response time: its ``accel_max`` and ``lat_accel_max`` become 0 (CARLA's ``RssCheck`` sets
  ``accel_max = 0`` for standing other vehicles; here for the ego too, and laterally). Its
  safe distances then only hold ``min_longitudinal_safety_distance`` and the lateral
  fluctuation margin;
* a pair in which **both** parties stand is ``NotRelevant`` (ad-rss' own way for a caller to
  leave a pair out, safe with distances "max"): neither can reach the other during its
  response time, the proper response (brake) is met by standing, and starting again makes
  a new situation that the next frame checks. ad-rss' unstructured check answers two
  participants standing within 0.1 m/s with *DriveAway*, not with *Brake*, for the same
  reason.

The rule is off (``standstill_speed_mps = 0``) under ``adrss-5.0`` and ``carla``, so the
conformance reference is unchanged.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.structured.batch import readonly_floats, readonly_ints

if TYPE_CHECKING:
    from rss.arrays import BoolArray
    from rss.structured.batch import ConstellationBatch, DynamicsArrays, ObjectArrays

__all__ = ["apply_standstill", "standing"]


def standing(objects: ObjectArrays, standstill_speed_mps: float) -> BoolArray:
    """``(C,)`` whether each object stands: every lane-frame speed bound within the threshold."""
    out: BoolArray = (
        (objects.speed_lon_max_mps <= standstill_speed_mps)
        & (np.abs(objects.speed_lat_min_mps) <= standstill_speed_mps)
        & (np.abs(objects.speed_lat_max_mps) <= standstill_speed_mps)
    )
    return out


def _kept_still(dynamics: DynamicsArrays, still: BoolArray) -> DynamicsArrays:
    """The dynamics with no acceleration during the response time where ``still``."""
    return dataclasses.replace(
        dynamics,
        accel_max_mps2=readonly_floats(np.where(still, 0.0, dynamics.accel_max_mps2)),
        lat_accel_max_mps2=readonly_floats(np.where(still, 0.0, dynamics.lat_accel_max_mps2)),
    )


def apply_standstill(batch: ConstellationBatch, standstill_speed_mps: float) -> ConstellationBatch:
    """The batch under the standstill rule (the module docstring); unchanged when off (<= 0)."""
    if standstill_speed_mps <= 0.0 or batch.size == 0:
        return batch
    ego_still = standing(batch.ego, standstill_speed_mps)
    other_still = standing(batch.other, standstill_speed_mps)
    if not (ego_still.any() or other_still.any()):
        return batch
    both = ego_still & other_still
    ctype = np.where(both, int(ConstellationType.NotRelevant), batch.constellation_type)
    return dataclasses.replace(
        batch,
        constellation_type=readonly_ints(ctype),
        ego_dynamics=_kept_still(batch.ego_dynamics, ego_still),
        other_dynamics=_kept_still(batch.other_dynamics, other_still),
    )
