"""``bound`` reachable sets: steering arcs that respect the track walls.

Each edge curve starts at a front corner like the ``turn`` arcs but, before every chord, checks
whether turning further towards its wall would still leave room to straighten out along the
wall; otherwise it turns back towards the wall's direction and then follows the wall::

    wall  ===========================================  (tangent t_w)
             d  ^          .--------------------------  edge follows the wall
                |      .-'   turn back (alpha -> 0)
         corner o---'        turn towards the wall while
                             d - c sin(alpha + dpsi/2) >= r (1 - cos(alpha + dpsi))

``alpha`` is the heading towards the wall relative to the wall tangent, ``d`` the clearance.
A vehicle that would hit the wall is outside the rule-conform behaviour, so the funnel between
the two edge curves is tighter than ``turn``'s where a wall is near. This is our own
wall-following construction in the spirit of the reference's double arc (see docs).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from reachsets import bound_scalar
from reachsets.bound_scalar import continue_curve
from reachsets.reach_turn import arc_profile
from reachsets.walls import (
    SCALAR_SEARCH,
    block_columns,
    track_walls,
    wall_frame,
    wall_frame_reference,
    wall_lists,
)

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams
    from reachsets.track import TrackGeometry
    from reachsets.walls import Walls

__all__ = ["SCALAR_CURVES_MAX", "wall_aware_arcs", "wall_aware_arcs_reference"]

#: Up to this many curves (two per object), they are built one by one with the scalar twin
#: (``bound_scalar``); above it, together in numpy (bit-identical to the curve-by-curve
#: reference; the twin agrees within 1e-9 m). Compiled, the twin is now the faster at every
#: size (random conformance track: 2 curves 0.04 against 0.43 ms, 32: 0.36 against 0.82,
#: 146: 1.60 against 2.05 ms); 32 keeps the larger batches bit-identical for ~3 us a curve.
#: From the sources the twin is about 3.5x slower, and 4 curves is the crossover.
SCALAR_CURVES_MAX = 32 if not bound_scalar.__file__.endswith(".py") else 4
#: Chords of the ``turn`` arcs checked together before the undecided curves check the rest.
FIRST_CHORDS = 4


@dataclass(frozen=True, slots=True)
class _Curves:
    """The object pose and wall of each edge curve (left curves first, then right ones).

    Attributes:
        x: Object x of each curve, ``(R, 1)`` (m).
        y: Object y, ``(R, 1)`` (m).
        yaw: Object heading, ``(R, 1)`` (rad).
        cos: Its cosine, ``(R, 1)``.
        sin: Its sine, ``(R, 1)``.
        side: ``+1.0`` for a left curve, ``-1.0`` for a right one, ``(R, 1)``.
        which: Wall of each curve (0 left, 1 right), ``(R,)``.
    """

    x: NDArray[np.float64]
    y: NDArray[np.float64]
    yaw: NDArray[np.float64]
    cos: NDArray[np.float64]
    sin: NDArray[np.float64]
    side: NDArray[np.float64]
    which: NDArray[np.intp]

    def take(self, rows: NDArray[np.intp] | slice) -> _Curves:
        """The curves ``rows``."""
        return _Curves(
            x=self.x[rows],
            y=self.y[rows],
            yaw=self.yaw[rows],
            cos=self.cos[rows],
            sin=self.sin[rows],
            side=self.side[rows],
            which=self.which[rows],
        )


def _start(
    objects: ObjectStates, params: ReachParams
) -> tuple[_Curves, tuple[NDArray[np.float64], ...]]:
    """Both sides' ``turn`` arcs as rows (left, then right): curves and ``(xi, eta, psi, dmax)``."""
    xi, eta, psi, dmax = arc_profile(objects, params)
    n = len(objects)
    side = np.repeat([1.0, -1.0], n)[:, None]
    xi, eta, psi, dmax = (np.concatenate([v, v]) for v in (xi, eta, psi, dmax))
    x, y, yaw = (
        np.tile(np.asarray(v, dtype=np.float64), 2)[:, None]
        for v in (objects.x_m, objects.y_m, objects.yaw_rad)
    )
    curves = _Curves(x, y, yaw, np.cos(yaw), np.sin(yaw), side, np.repeat([0, 1], n))
    return curves, (xi, side * eta, psi, dmax)


def _advance(
    arcs: tuple[NDArray[np.float64], ...],
    k: int,
    dpsi: NDArray[np.float64],
    side: NDArray[np.float64],
    params: ReachParams,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Point ``k`` ``(xi, eta, psi)`` of every curve of ``arcs`` after turning chord ``k``.

    Args:
        arcs: ``(xi, eta, psi, ...)`` of the curves, each ``(R, P)``.
        k: The point, ``1 <= k < P``.
        dpsi: Turn of chord ``k`` of each curve, ``(R,)`` (rad).
        side: ``+1.0`` for a left curve, ``-1.0`` for a right one, ``(R,)``.
        params: Arc parameters.

    Returns:
        ``(xi, eta, psi)`` at point ``k``, each ``(R,)``.
    """
    xi, eta, psi = (v[:, k - 1] for v in arcs[:3])
    c = params.arc_step_m
    chord = psi + dpsi / 2
    return xi + c * np.cos(chord), eta + side * c * np.sin(chord), psi + dpsi


def _curves_scalar(
    objects: ObjectStates, walls: Walls, params: ReachParams
) -> tuple[tuple[NDArray[np.float64], NDArray[np.float64]], ...]:
    """``wall_aware_arcs`` with the scalar twin, curve by curve (left, then right, per object).

    Each object's two curves start from its ``turn`` arc profile (the right one mirrored),
    exactly the rows ``_start`` builds for the numpy path.
    """
    lists = wall_lists(walls)
    limits = (float(params.arc_step_m), float(params.arc_max_turn_rad))
    xi, eta, psi, dmax = arc_profile(objects, params)
    yaw = np.asarray(objects.yaw_rad, dtype=np.float64)
    pose = np.stack([objects.x_m, objects.y_m, yaw, np.cos(yaw), np.sin(yaw)], axis=1).tolist()
    out = [(xi.copy(), eta.copy()), (xi.copy(), -eta)]
    for r, p in enumerate(pose):
        rows = (xi[r].tolist(), eta[r].tolist(), psi[r].tolist(), dmax[r].tolist())
        for which, (side, (cur_xi, cur_eta)) in enumerate(zip((1.0, -1.0), out, strict=True)):
            arc = (rows[0][:], [side * v for v in rows[1]], rows[2][:], rows[3])
            continue_curve(lists, (p[0], p[1], p[2], p[3], p[4], side), which, arc, limits)
            cur_xi[r], cur_eta[r] = arc[0], arc[1]
    return out[0], out[1]


def wall_aware_arcs(
    objects: ObjectStates,
    params: ReachParams,
    track: TrackGeometry,
    *,
    scalar: bool | None = None,
) -> tuple[tuple[NDArray[np.float64], NDArray[np.float64]], ...]:
    """Body-frame wall-aware edge curves of every object, both sides at once.

    Each curve is the ``turn`` arc until its first chord that may not turn towards its wall:
    every chord's rule is first checked on the ``turn`` arcs at once (all curves, both walls),
    and only the curves that turn back are continued chord by chord from there, together
    (each from its own first turning-back chord on; ``wall_aware_arcs_reference`` is the
    curve-by-curve reference).

    Args:
        objects: The objects (N).
        params: Arc parameters as for ``steering_arcs``.
        track: Track geometry; the left wall bounds the left curve, the right wall the right.
        scalar: Build the curves one by one with the scalar twin (``None``: when there are
            at most ``SCALAR_CURVES_MAX``); the curves agree within 1e-9 m either way.

    Returns:
        ``((xi, eta) left, (xi, eta) right)``, each array ``(N, P)``.
    """
    n = len(objects)
    if n == 0:
        xi, eta, _, _ = arc_profile(objects, params)
        return (xi, eta), (xi, -eta)
    walls = track_walls(track)
    if scalar if scalar is not None else 2 * n <= SCALAR_CURVES_MAX:
        return _curves_scalar(objects, walls, params)
    curves, (xi, eta, psi, dmax) = _start(objects, params)
    start = _first_back(curves, walls, (xi, eta, psi, dmax), params)
    rows = np.flatnonzero(start)
    if len(rows):
        start = start[rows]
        order = np.argsort(start, kind="stable")
        rows, start = rows[order], start[order]
        arcs = tuple(v[rows] for v in (xi, eta, psi, dmax))
        _follow(curves.take(rows), walls, arcs, start, params)
        xi[rows], eta[rows] = arcs[0], arcs[1]
    return (xi[:n], eta[:n]), (xi[n:], eta[n:])


def _first_back(
    curves: _Curves, walls: Walls, arcs: tuple[NDArray[np.float64], ...], params: ReachParams
) -> NDArray[np.intp]:
    """First chord of each curve's ``turn`` arc that may not turn towards the wall (0: none).

    The first ``FIRST_CHORDS`` chords of every curve are checked together, then the rest of
    the curves that all of those may turn (most curves turn back early: fewer positions to
    search than all chords at once).
    """
    xi, eta, psi, dmax = arcs
    start = np.zeros(len(xi), dtype=np.intp)
    live = np.arange(len(xi))
    last = params.arc_points - 1
    for lo, hi in ((0, min(FIRST_CHORDS, last)), (min(FIRST_CHORDS, last), last)):
        if lo >= hi or not len(live):
            break
        sub = curves.take(live) if lo else curves
        chords = tuple(v[live, lo:hi] if lo else v[:, lo:hi] for v in (xi, eta, psi, dmax))
        back = ~_turn(sub, walls, chords, params)[1]
        hit = back.any(axis=1)
        start[live[hit]] = np.argmax(back[hit], axis=1) + lo + 1
        live = live[~hit]
    return start


def _follow(
    curves: _Curves,
    walls: Walls,
    arcs: tuple[NDArray[np.float64], ...],
    start: NDArray[np.intp],
    params: ReachParams,
) -> None:
    """Turn the curves by the wall rule from their first chord turning back on, together.

    The curves are sorted by that chord, so the ones already turned by the rule at chord
    ``k`` are a leading slice (no row gathers or masks per chord); their wall blocks are
    gathered once. Each chord is the same arithmetic as ``_turn`` and ``_advance``.

    Args:
        curves: The curves (R), sorted by ``start``.
        walls: Both walls.
        arcs: Their ``turn`` arcs ``(xi, eta, psi)`` (signed ``eta``), each ``(R, P)``,
            overwritten in place from chord ``start`` on, and ``dmax``, ``(R, P - 1)``.
        start: First chord of each curve that turns back, ascending, ``(R,)``.
        params: Arc parameters.
    """
    xi, eta, psi, dmax = arcs
    cx, cy, co, si, yaw, side = (
        v[:, 0] for v in (curves.x, curves.y, curves.cos, curves.sin, curves.yaw, curves.side)
    )
    side_c = side * params.arc_step_m
    radius = _radius(dmax, params)
    blocks = None if SCALAR_SEARCH else block_columns(walls, curves.which)
    for k in range(int(start[0]), params.arc_points):
        a = int(np.searchsorted(start, k, side="right"))
        j = k - 1
        px, ey, ps = xi[:a, j], eta[:a, j], psi[:a, j]
        x = cx[:a] + co[:a] * px - si[:a] * ey
        y = cy[:a] + si[:a] * px + co[:a] * ey
        frame = wall_frame(walls, x, y, curves.which[:a], blocks and blocks.head(a))
        chord_turn = (ps, dmax[:a, j], radius[:a, j])
        dpsi = _rule(frame, (x, y, yaw[:a], side[:a]), chord_turn, params)[0]
        chord = ps + dpsi / 2
        xi[:a, k] = px + params.arc_step_m * np.cos(chord)
        eta[:a, k] = ey + side_c[:a] * np.sin(chord)
        psi[:a, k] = ps + dpsi


def wall_aware_arcs_reference(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry
) -> tuple[tuple[NDArray[np.float64], NDArray[np.float64]], ...]:
    """Slow reference of ``wall_aware_arcs``: curve by curve, chord by chord.

    Each curve keeps its ``turn`` arc while every chord so far may turn towards the wall;
    from its first chord that may not, every chord is turned by the rule.
    """
    curves, arcs = _start(objects, params)
    walls = track_walls(track)
    for i in range(2 * len(objects)):
        one = curves.take(slice(i, i + 1))
        ruled = False
        for k in range(1, params.arc_points):
            chord = tuple(v[i : i + 1, k - 1 : k] for v in arcs)
            dpsi, towards = _turn(one, walls, chord, params, reference=True)
            ruled = ruled or not bool(towards[0, 0])
            if ruled:
                new = _advance(
                    tuple(v[i : i + 1] for v in arcs), k, dpsi[:, 0], one.side[:, 0], params
                )
                for v, w in zip(arcs[:3], new, strict=True):
                    v[i : i + 1, k] = w
    n = len(objects)
    xi, eta = arcs[0], arcs[1]
    return (xi[:n], eta[:n]), (xi[n:], eta[n:])


def _turn(
    curves: _Curves,
    walls: Walls,
    chords: tuple[NDArray[np.float64], ...],
    params: ReachParams,
    *,
    reference: bool = False,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Turn of the next chord from each point, and whether it may turn towards the wall.

    Args:
        curves: The curves (R).
        walls: Both walls.
        chords: Body-frame start ``(xi, eta)`` of each chord, the heading change so far
            (towards the wall side) and the chord's largest turn, each ``(R, K)``.
        params: Arc parameters.
        reference: Search the walls with the brute-force reference.

    Returns:
        ``dpsi`` and ``towards``, each ``(R, K)``.
    """
    xi, eta, psi, dmax = chords
    x = curves.x + curves.cos * xi - curves.sin * eta
    y = curves.y + curves.sin * xi + curves.cos * eta
    flat = np.repeat(curves.which, x.shape[1]) if x.shape[1] > 1 else curves.which
    search = wall_frame_reference if reference else wall_frame
    frame = tuple(v.reshape(x.shape) for v in search(walls, x.ravel(), y.ravel(), flat))
    pose = (x, y, curves.yaw, curves.side)
    return _rule(frame, pose, (psi, dmax, _radius(dmax, params)), params)


def _radius(dmax: NDArray[np.float64], params: ReachParams) -> NDArray[np.float64]:
    """Radius of the arc turning by ``dmax`` per chord (m), any shape."""
    radius: NDArray[np.float64] = params.arc_step_m / (2 * np.sin(np.maximum(dmax, 1e-12) / 2))
    return radius


def _rule(
    frame: tuple[NDArray[np.float64], ...],
    pose: tuple[NDArray[np.float64], ...],
    chord: tuple[NDArray[np.float64], ...],
    params: ReachParams,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """The wall rule of ``_turn`` from the wall frame of each chord start (shapes broadcast).

    Args:
        frame: Nearest wall point and unit tangent ``(wx, wy, tx, ty)``.
        pose: Chord start ``(x, y)`` (m), the object's heading (rad) and the curve's side.
        chord: Heading change so far, the chord's largest turn (rad) and its ``_radius``.
        params: Arc parameters.

    Returns:
        ``dpsi`` and ``towards``.
    """
    wx, wy, tx, ty = frame
    x, y, yaw0, side = pose
    psi, dmax, radius = chord
    clearance = -side * (tx * (y - wy) - ty * (x - wx))
    heading = yaw0 + side * psi
    rel = np.arctan2(np.sin(heading), np.cos(heading)) - np.arctan2(ty, tx)
    alpha = side * np.arctan2(np.sin(rel), np.cos(rel))
    room = clearance - params.arc_step_m * np.sin(alpha + dmax / 2)
    need = radius * (1 - np.cos(np.minimum(np.maximum(alpha + dmax, 0.0), np.pi)))
    towards = (np.abs(alpha) >= np.pi / 2) | (room >= need)
    back = np.minimum(dmax, np.maximum(alpha, 0.0))
    dpsi = np.minimum(np.where(towards, dmax, -back), params.arc_max_turn_rad - psi)
    return dpsi, towards
