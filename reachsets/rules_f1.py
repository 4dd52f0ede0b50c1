"""F1 rules: racing alongside and defending off-line, with their deletion patches.

Atoms per object (s along the centre line, ``L`` ego length)::

    overlap   0 <= s_obj - s_ego < (1 - d_overlap) L      at least 20 % side by side
    approach  the next corner point (|kappa| > kappa_thr) lies within d_corner ahead
    first     the corner point before that one is not within d_corner before it, i.e. the
              object is ahead of the first corner of a combination (false inside a corner)
    defense   0 <= s_obj - s_ego <= d_defend              the ego attacks from behind
    off_line  the object is on the inside half of the track for that corner

Formulas::

    alongside = overlap S (overlap and not approach)
    active    = approach and first and not alongside
    defending = active and Y (active S (active and defense and off_line))

Patches (all steps, ``len_patch`` from the ego's s, ``width_extra_bound`` beyond the wall):

* alongside: a strip along the wall on the ego's side, ``d`` wide, where ``d`` is the midpoint
  of the ego's and the object's wall distances (at most the object's wall distance minus
  half its width), kept as a fraction of the local width, never narrower than ``min(d, W)``
  and never wider than ``w - W_obj``: the object leaves the ego room on its side.
* defending: a strip of ``veh_width_factor * W`` along the outside wall of the corner.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from reachsets.ltl import And, Atom, LtlMemory, Not, Previously, Since, step
from reachsets.patches import RuleContext, RulePatch

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray

    from reachsets.track import TrackGeometry

__all__ = ["ALONGSIDE", "DEFENDING", "corner_points", "evaluate_f1"]

ALONGSIDE = Since(Atom("overlap"), And((Atom("overlap"), Not(Atom("approach")))))
DEFENDING = And(
    (
        Atom("active"),
        Previously(Since(Atom("active"), And((Atom("active"), Atom("defense"), Atom("off_line"))))),
    )
)


def corner_points(
    track: TrackGeometry, kappa_thr: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Corners as the centre points with ``|kappa| > kappa_thr`` (reference semantics).

    Returns:
        ``(s, direction)``, each ``(R,)``; direction +1 left, -1 right.
    """
    mask = np.abs(track.kappa_inv_m) > kappa_thr
    return track.s_m[mask], np.where(track.kappa_inv_m[mask] > 0, 1.0, -1.0)


def _next_corner(
    track: TrackGeometry, s_obj: NDArray[np.float64], d_corner: float, kappa_thr: float
) -> tuple[NDArray[np.bool_], NDArray[np.bool_], NDArray[np.float64]]:
    """``approach``, ``first`` and corner direction per object.

    The next corner is the first corner *point* at or ahead of the object (the first one of
    the track when none is ahead); ``approach``: it lies at most ``d_corner`` ahead;
    ``first``: the corner point before it (cyclically) is not within ``d_corner`` before it.
    Inside a corner the next point is a metre ahead and its predecessor a metre behind it,
    so the object approaches but not the first corner of a combination.
    """
    s_c, direction = corner_points(track, kappa_thr)
    n = len(s_obj)
    if len(s_c) == 0:
        return np.zeros(n, bool), np.zeros(n, bool), np.zeros(n)
    ahead = s_c[None, :] >= s_obj[:, None]
    k = np.where(ahead.any(axis=1), np.argmax(ahead, axis=1), 0)
    to_next = track.ahead_m(s_obj, s_c[k])
    prev_gap = track.ahead_m(s_c[k - 1], s_c[k])
    approach = (to_next >= 0) & (to_next <= d_corner)
    first = ~((prev_gap >= 0) & (prev_gap <= d_corner))
    return approach, first, direction[k]


def evaluate_f1(
    ctx: RuleContext, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    """Evaluate both F1 rules for every object and build their patches.

    Args:
        ctx: Rule context; needs ``ctx.track``.
        memory: LTL memory from the previous frame.

    Returns:
        The patches and the new memory.
    """
    track = ctx.track
    if track is None or len(ctx.objects) == 0:
        return [], {}
    p = ctx.params.f1
    objs = ctx.objects
    ids = [str(i) for i in objs.ids]
    gap = track.ahead_m(ctx.s_ego_m, ctx.s_obj_m)
    approach, first, direction = _next_corner(track, ctx.s_obj_m, p.d_corner_m, p.kappa_thr_inv_m)
    lat_obj = ctx.lat_obj_m
    atoms = {
        "overlap": (gap >= 0) & (gap < (1 - p.d_overlap) * ctx.ego_length_m),
        "approach": approach,
        "defense": (gap >= 0) & (gap <= p.d_defend_m),
        "off_line": np.where(direction > 0, lat_obj < 0, lat_obj > 0),
    }
    alongside, mem = step(ALONGSIDE, atoms, ids, memory, prefix="f1.alongside")
    atoms["active"] = approach & first & ~alongside
    defending, mem_d = step(DEFENDING, atoms, ids, memory, prefix="f1.defending")
    mem.update(mem_d)
    patches: list[RulePatch] = []
    if not (alongside.any() or defending.any()):
        return patches, mem
    idx = track.span_indices(ctx.s_ego_m, p.len_patch_m)
    tw_l = track.tw_left_m[idx]
    tw_r = track.tw_right_m[idx]
    lat_ego = float(track.lateral_m([ctx.ego_x_m], [ctx.ego_y_m])[0])
    patches.extend(
        RulePatch(int(i), "f1.alongside", _alongside_strip(ctx, int(i), idx, lat_ego))
        for i in np.flatnonzero(alongside)
    )
    for i in np.flatnonzero(defending & ~alongside):
        width = p.veh_width_factor * ctx.ego_width_m
        if direction[i] < 0:  # right corner: keep the left (outside) edge free
            geom = track.strip(idx, -(tw_l + p.width_extra_bound_m), -(tw_l - width))
        else:
            geom = track.strip(idx, tw_r + p.width_extra_bound_m, tw_r - width)
        patches.append(RulePatch(int(i), "f1.defending", geom))
    return patches, mem


def _alongside_strip(ctx: RuleContext, i: int, idx: NDArray[np.intp], lat_ego: float) -> object:
    """The alongside patch of object ``i`` over centre points ``idx``."""
    track = ctx.track
    assert track is not None
    p = ctx.params.f1
    j = int(track.index_at(ctx.s_obj_m[i]))
    lat_obj = float(ctx.lat_obj_m[i])
    w_obj = float(ctx.objects.width_m[i])
    right = lat_ego > lat_obj
    if right:
        d_ego = track.tw_right_m[j] - lat_ego
        d_obj = track.tw_right_m[j] - lat_obj
    else:
        d_ego = track.tw_left_m[j] + lat_ego
        d_obj = track.tw_left_m[j] + lat_obj
    width_here = track.tw_left_m[j] + track.tw_right_m[j]
    d = min((d_ego + d_obj) / 2, d_obj - w_obj / 2)
    frac = d / width_here
    w = track.tw_left_m[idx] + track.tw_right_m[idx]
    d_k = np.minimum(np.maximum(w * frac, min(d, ctx.ego_width_m)), w - w_obj)
    d_k = np.maximum(d_k, 0.0)
    if right:
        tw = track.tw_right_m[idx]
        return track.strip(idx, tw + p.width_extra_bound_m, tw - d_k)
    tw = track.tw_left_m[idx]
    return track.strip(idx, -(tw + p.width_extra_bound_m), -(tw - d_k))
