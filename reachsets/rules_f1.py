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
from reachsets.patches import RulePatch

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray

    from reachsets.batch import FrameBatch
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
    batch: FrameBatch, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    """Evaluate both F1 rules for every object over consecutive frames and build their patches.

    Args:
        batch: The frames' objects and egos; needs ``batch.track``.
        memory: LTL memory from the frame before the first one.

    Returns:
        The patches (``object_index`` = batch row) and the memory after the last frame.
    """
    track = batch.track
    if track is None:
        return [], {}
    p = batch.params.f1
    objs = batch.objects
    ids = [str(i) for i in objs.ids]
    f = batch.frame
    gap = track.ahead_m(batch.s_ego_m[f], batch.s_obj_m)
    approach, first, direction = _next_corner(track, batch.s_obj_m, p.d_corner_m, p.kappa_thr_inv_m)
    lat_obj = batch.lat_obj_m
    atoms = {
        "overlap": (gap >= 0) & (gap < (1 - p.d_overlap) * batch.ego_length_m[f]),
        "approach": approach,
        "defense": (gap >= 0) & (gap <= p.d_defend_m),
        "off_line": np.where(direction > 0, lat_obj < 0, lat_obj > 0),
    }
    n = batch.n_frames
    alongside, mem = step(ALONGSIDE, atoms, ids, memory, "f1.alongside", frame=f, n_frames=n)
    atoms["active"] = approach & first & ~alongside
    defending, mem_d = step(DEFENDING, atoms, ids, memory, "f1.defending", frame=f, n_frames=n)
    mem.update(mem_d)
    patches: list[RulePatch] = []
    for i in np.flatnonzero(alongside | defending):
        k = int(f[i])
        idx = track.span_indices(float(batch.s_ego_m[k]), p.len_patch_m)
        if alongside[i]:
            lat_ego = float(track.lateral_m([batch.ego_x_m[k]], [batch.ego_y_m[k]])[0])
            strip = _alongside_strip(batch, int(i), idx, lat_ego)
            patches.append(RulePatch(int(i), "f1.alongside", strip))
            continue
        width = p.veh_width_factor * float(batch.ego_width_m[k])
        tw_l = track.tw_left_m[idx]
        tw_r = track.tw_right_m[idx]
        if direction[i] < 0:  # right corner: keep the left (outside) edge free
            geom = track.strip(idx, -(tw_l + p.width_extra_bound_m), -(tw_l - width))
        else:
            geom = track.strip(idx, tw_r + p.width_extra_bound_m, tw_r - width)
        patches.append(RulePatch(int(i), "f1.defending", geom))
    return patches, mem


def _alongside_strip(batch: FrameBatch, i: int, idx: NDArray[np.intp], lat_ego: float) -> object:
    """The alongside patch of row ``i`` over centre points ``idx``."""
    track = batch.track
    assert track is not None
    p = batch.params.f1
    j = int(track.index_at(batch.s_obj_m[i]))
    lat_obj = float(batch.lat_obj_m[i])
    w_obj = float(batch.objects.width_m[i])
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
    d_k = np.minimum(
        np.maximum(w * frac, min(d, float(batch.ego_width_m[batch.frame[i]]))), w - w_obj
    )
    d_k = np.maximum(d_k, 0.0)
    if right:
        tw = track.tw_right_m[idx]
        return track.strip(idx, tw + p.width_extra_bound_m, tw - d_k)
    tw = track.tw_left_m[idx]
    return track.strip(idx, -(tw + p.width_extra_bound_m), -(tw - d_k))
