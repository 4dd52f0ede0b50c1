"""Public-road standstill rule: a standing vehicle does not start into the standing ego.

====================  ================================================  =========================
rule                  holds when                                        patch
====================  ================================================  =========================
road.standstill       the object stands (speed ``<=                     the ego's footprints along
                      standstill_speed_mps``) and so does the ego: it   the rated trajectory
                      stands now and its rated trajectory moves it by   (their convex hull, 0.5 m
                      at most ``standstill_speed_mps`` x the horizon    wider), all steps
====================  ================================================  =========================

Why (docs/reachsets.md, "Standstill"): the reference gives a standing car its full reach
(13 m/s^2 from rest, 104 m in 4 s), so at a red light every standing car ahead, beside or
across the junction "reaches" the standing ego and two standing queues are a collision.
Starting from rest into a vehicle standing in plain view is never rule-conform (StVO §1(2):
nobody may be harmed or endangered; Vienna Convention art. 13(1): a driver must be able to
stop within the distance ahead visible to him), and a vehicle that starts is seen moving at
the next frame, where the rule no longer holds and its full reach applies. The patch never
removes the object's current footprint (``patch_grid``), so two standing boxes that already
overlap still collide.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from reachsets.patches import RulePatch

if TYPE_CHECKING:
    from reachsets.patches import RuleContext

__all__ = ["STANDSTILL", "ego_stands", "evaluate_standstill"]

#: Rule name (patches, records).
STANDSTILL = "road.standstill"
#: Margin around the ego's footprints of the patch [m].
_MARGIN_M = 0.5


def ego_stands(ctx: RuleContext, standstill_speed_mps: float) -> bool:
    """Whether the ego stands now and its rated trajectory keeps it (nearly) in place."""
    if ctx.ego_speed_mps > standstill_speed_mps:
        return False
    occ = ctx.occupancy
    travel_m = float(np.max(np.hypot(occ.x_m - occ.x_m[0], occ.y_m - occ.y_m[0]), initial=0.0))
    return travel_m <= standstill_speed_mps * float(ctx.times_s[-1]) + 1e-9


def evaluate_standstill(ctx: RuleContext) -> list[RulePatch]:
    """``road.standstill`` patches of every standing object when the ego stands (see above)."""
    speed = ctx.params.road.standstill_speed_mps
    objs = ctx.objects
    if speed <= 0.0 or not len(objs) or not ego_stands(ctx, speed):
        return []
    standing = np.flatnonzero(objs.speed_mps <= speed)
    if not len(standing):
        return []
    corners = shapely.multipoints(np.asarray(ctx.occupancy.corners_m).reshape(-1, 2))
    ego_area = shapely.buffer(shapely.convex_hull(corners), _MARGIN_M)
    return [RulePatch(int(i), STANDSTILL, ego_area) for i in standing]
