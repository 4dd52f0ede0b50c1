"""Windowed motion estimates along tracks, vectorised over every observation of a drive.

Every estimate of observation ``i`` uses only observations of the same object, found by
time (not by sample count), so unevenly sampled tracks and different sample rates are
handled alike::

    object k:  o----o----o----o----o----o----o      time ->
                    ^ back     ^ i     ^ ahead      back: last sample >= span before i
                    |<-------->|                    ahead: first sample >= span after i

- :func:`neighbours` finds ``back`` / ``ahead`` (the chord ends);
- :func:`chord_speed` / :func:`chord_heading` are the speed and direction of motion from the
  positions over ``[back, ahead]``;
- :func:`window_slope` is the least-squares slope of a value over a centred time window (a
  first-order Savitzky-Golay derivative for uneven samples).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from workbench.quality.tracks import Tracks

__all__ = ["chord_heading", "chord_speed", "neighbours", "window_slope"]

#: Most samples on one side of a window (a guard against duplicate time stamps).
MAX_SIDE_SAMPLES = 64
_MIN_FIT_SAMPLES = 3


def _keys(tracks: Tracks) -> tuple[NDArray[np.int64], int]:
    """Sortable ``(M,)`` keys ``object << shift | time`` and the time unit [ns] they use."""
    rel = tracks.t_ns - (tracks.t_ns.min() if len(tracks) else 0)
    unit = 1
    span = int(rel.max()) if len(tracks) else 0
    obj_bits = max(1, int(tracks.obj.max() if len(tracks) else 0).bit_length())
    while (span // unit).bit_length() + obj_bits > 62:  # noqa: PLR2004 - int64 headroom
        unit *= 10
    shift = max(1, (span // unit).bit_length())
    return (tracks.obj << shift) | (rel // unit), unit


def neighbours(tracks: Tracks, span_ns: int) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """``back``, ``ahead``: ``(M,)`` nearest observations at least ``span_ns`` away, or ``-1``.

    ``back[i]``: the last observation of the same object at or before ``t_i - span``;
    ``ahead[i]``: the first at or after ``t_i + span``.
    """
    keys, unit = _keys(tracks)
    step = max(1, span_ns // unit)
    m = len(keys)
    back = np.searchsorted(keys, keys - step, side="right") - 1
    ahead = np.searchsorted(keys, keys + step, side="left")
    back = np.where(
        (back >= 0) & (tracks.obj[np.clip(back, 0, max(m - 1, 0))] == tracks.obj), back, -1
    )
    safe = np.clip(ahead, 0, max(m - 1, 0))
    ahead = np.where((ahead < m) & (tracks.obj[safe] == tracks.obj), ahead, -1)
    return back.astype(np.int64), ahead.astype(np.int64)


def chord_speed(
    tracks: Tracks, back: NDArray[np.int64], ahead: NDArray[np.int64]
) -> NDArray[np.float64]:
    """``(M,)`` speed from positions over ``[back, ahead]`` [m/s]; NaN where one end is missing.

    An end that is missing falls back to the observation itself (a one-sided chord).
    """
    lo, hi = _ends(back, ahead)
    dt_s = ns_to_s(tracks.t_ns[hi] - tracks.t_ns[lo])
    dist = np.hypot(tracks.x_m[hi] - tracks.x_m[lo], tracks.y_m[hi] - tracks.y_m[lo])
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(dt_s > 0, dist / np.where(dt_s > 0, dt_s, 1.0), np.nan)


def chord_heading(
    tracks: Tracks, back: NDArray[np.int64], ahead: NDArray[np.int64]
) -> NDArray[np.float64]:
    """``(M,)`` direction of motion over ``[back, ahead]`` [rad, ENU]; NaN without a chord."""
    lo, hi = _ends(back, ahead)
    dx = tracks.x_m[hi] - tracks.x_m[lo]
    dy = tracks.y_m[hi] - tracks.y_m[lo]
    return np.where(hi != lo, np.arctan2(dy, dx), np.nan)


def _ends(
    back: NDArray[np.int64], ahead: NDArray[np.int64]
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    own = np.arange(len(back), dtype=np.int64)
    return np.where(back >= 0, back, own), np.where(ahead >= 0, ahead, own)


def window_slope(tracks: Tracks, values: NDArray[np.float64], half_ns: int) -> NDArray[np.float64]:
    """``(M,)`` least-squares slope of ``values`` over time [unit/s] in ``[t - half, t + half]``.

    Only observations of the same object with a finite value count; NaN with fewer than
    three of them or a window shorter than ``half_ns`` (a track's ends get no estimate).

    Args:
        tracks: The observations.
        values: ``(M,)`` the value per observation.
        half_ns: Half the window [ns].
    """
    m = len(tracks)
    n = np.zeros(m)
    st = np.zeros(m)
    sv = np.zeros(m)
    stt = np.zeros(m)
    stv = np.zeros(m)
    lo_t = np.zeros(m)
    hi_t = np.zeros(m)
    finite = np.isfinite(values)
    idx = np.arange(m)
    for k in range(MAX_SIDE_SAMPLES + 1):
        reached = False
        for d in (k,) if k == 0 else (k, -k):
            same = tracks.same_object(d)
            j = np.clip(idx + d, 0, max(m - 1, 0))
            use = same & (np.abs(tracks.t_ns[j] - tracks.t_ns) <= half_ns)
            reached = reached or bool(use.any())
            use &= finite[j]
            dt_s = np.where(use, ns_to_s(tracks.t_ns[j] - tracks.t_ns), 0.0)
            v = np.where(use, values[j], 0.0)
            n += use
            st += dt_s
            sv += v
            stt += dt_s * dt_s
            stv += v * dt_s
            lo_t = np.minimum(lo_t, dt_s)
            hi_t = np.maximum(hi_t, dt_s)
        if not reached:
            break
    denominator = n * stt - st * st
    ok = (n >= _MIN_FIT_SAMPLES) & (denominator > 0) & (lo_t < 0) & (hi_t > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = (n * stv - st * sv) / np.where(ok, denominator, 1.0)
    return np.where(ok, slope, np.nan)
