"""Roborace Season Alpha: trigger zones decide who attacks, overtaking zones fix the side.

Every vehicle (the ego included) is ranked by s. ``lead`` is the closest vehicle ahead,
``follow`` the closest behind; ``chaser`` triggers ``lead`` iff
``(s_lead - s_chaser) / v_chaser < t_trigger`` (never when ``v_chaser = 0``). Atoms::

    in_trigger   the vehicle is inside a trigger zone
    trig_lead    it triggers its lead
    trig_follow  its follower triggers it

Formulas (the status only changes inside a trigger zone and is held outside)::

    offence = (not in_trigger) S (in_trigger and trig_lead)
    defence = (not in_trigger) S (in_trigger and not trig_lead and trig_follow)

Patches (all steps): per overtaking zone the half-tracks ``L`` (centre line to 50 m left)
and ``R`` (to 50 m right) over the zone's s-range. In an overtake-left zone an offence
vehicle loses ``R`` and a defence vehicle loses ``L``; in an overtake-right zone they swap.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.errors import ZoneFileError
from reachsets.inputs import Zone, ZoneKind, ZoneMap
from reachsets.ltl import And, Atom, LtlMemory, Not, Since, step
from reachsets.patches import RuleContext, RulePatch

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray

__all__ = ["DEFENCE", "EGO_ID", "OFFENCE", "evaluate_roborace", "zones_from_json"]

EGO_ID = "__ego__"
OFFENCE = Since(Not(Atom("in_trigger")), And((Atom("in_trigger"), Atom("trig_lead"))))
DEFENCE = Since(
    Not(Atom("in_trigger")),
    And((Atom("in_trigger"), Not(Atom("trig_lead")), Atom("trig_follow"))),
)


def zones_from_json(data: Mapping[str, Any]) -> ZoneMap:
    """Build a zone map from a parsed Roborace JSON map (``Centre`` and ``Zone`` keys).

    Raises:
        ZoneFileError: If keys are missing or indices fall outside the centre line.
    """
    try:
        centre = np.asarray(data["Centre"], dtype=np.float64)[:, :2]
        raw = data["Zone"]
    except (KeyError, TypeError, ValueError, IndexError) as err:
        raise ZoneFileError(f"needs 'Centre' points and a 'Zone' list ({err})") from err
    zones = []
    for entry in raw:
        try:
            zone = Zone(
                int(entry["Type"]), str(entry["ID"]), int(entry["Start"]), int(entry["End"])
            )
        except (KeyError, TypeError, ValueError) as err:
            raise ZoneFileError(f"zone entry {entry!r} lacks Type/ID/Start/End") from err
        if not (0 <= zone.start_index < len(centre) and 0 <= zone.end_index < len(centre)):
            raise ZoneFileError(f"zone {zone.zone_id} indexes outside the {len(centre)} points")
        zones.append(zone)
    return ZoneMap(centre, tuple(zones))


def _neighbour_gaps(s: NDArray[np.float64], length_m: float, closed: bool) -> NDArray[np.float64]:  # noqa: FBT001
    """``(M, M)`` distance along the track from vehicle i forward to vehicle j (inf if behind)."""
    d = s[None, :] - s[:, None]
    if closed:
        d = d % length_m
    d = np.where(d > 0, d, np.inf)
    np.fill_diagonal(d, np.inf)
    return d


def evaluate_roborace(
    ctx: RuleContext, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    """Evaluate the Roborace rule for every vehicle and build the objects' patches."""
    track, zones = ctx.track, ctx.zones
    if track is None or zones is None or len(ctx.objects) == 0:
        return [], {}
    p = ctx.params.roborace
    ids = [EGO_ID, *(str(i) for i in ctx.objects.ids)]
    s = np.concatenate([[ctx.s_ego_m], ctx.s_obj_m])
    v = np.concatenate([[ctx.ego_speed_mps], ctx.objects.speed_mps])
    zs = track.project(zones.centre_m[:, 0], zones.centre_m[:, 1])
    gaps = _neighbour_gaps(s, track.length_m, track.closed)
    lead_gap = gaps.min(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        trig_lead = np.where(v > 0, lead_gap / np.where(v > 0, v, 1.0), np.inf) < p.t_trigger_s
    follower = np.argmin(gaps, axis=0)
    has_follower = np.isfinite(gaps.min(axis=0))
    trig_follow = has_follower & trig_lead[follower]
    in_trigger = np.zeros(len(s), dtype=bool)
    for z in zones.zones:
        if z.kind == ZoneKind.TRIGGER:
            in_trigger |= _in_zone(track.ahead_m, s, zs[z.start_index], zs[z.end_index])
    atoms = {"in_trigger": in_trigger, "trig_lead": trig_lead, "trig_follow": trig_follow}
    offence, mem = step(OFFENCE, atoms, ids, memory, prefix="roborace.offence")
    defence, mem_d = step(DEFENCE, atoms, ids, memory, prefix="roborace.defence")
    mem.update(mem_d)
    patches: list[RulePatch] = []
    for z in zones.zones:
        if z.kind not in (ZoneKind.OVERTAKE_LEFT, ZoneKind.OVERTAKE_RIGHT):
            continue
        s0, s1 = float(zs[z.start_index]), float(zs[z.end_index])
        idx = track.span_indices(s0, float(track.ahead_m(s0, s1)) % max(track.length_m, 1e-9))
        if len(idx) < 2:  # noqa: PLR2004
            continue
        left = track.strip(idx, 0.0, -p.patch_width_m)
        right = track.strip(idx, 0.0, p.patch_width_m)
        for i in range(len(ctx.objects)):
            if offence[i + 1]:
                geom = right if z.kind == ZoneKind.OVERTAKE_LEFT else left
                patches.append(RulePatch(i, "roborace.offence", geom))
            elif defence[i + 1]:
                geom = left if z.kind == ZoneKind.OVERTAKE_LEFT else right
                patches.append(RulePatch(i, "roborace.defence", geom))
    return patches, mem


def _in_zone(ahead: Any, s: NDArray[np.float64], s0: float, s1: float) -> NDArray[np.bool_]:
    """Whether each s lies between zone start ``s0`` and end ``s1`` (driving direction)."""
    into = np.asarray(ahead(s0, s), dtype=float)
    span = float(np.asarray(ahead(s0, s1)))
    return np.asarray((into >= 0) & (into <= span), dtype=bool)
