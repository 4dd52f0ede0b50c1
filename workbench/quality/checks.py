"""Per-object data-quality checks over a whole drive (docs/data_quality.md).

Pure and vectorised over every observation at once (:class:`~workbench.quality.tracks.Tracks`);
each check yields, per observation, a measured value and its bound; flagged observations of
one object that follow each other become one :class:`Finding` (its worst value). Kinds:

- ``speed_mismatch``: recorded speed outside the speeds the positions give just before and
  just after (chords of ``chord_span``), by more than ``speed_abs + speed_rel * speed``;
- ``accel``: the least-squares slope of the recorded speed over ``2 * window_half`` beyond
  the class's acceleration or braking limit;
- ``jerk``: the same slope of that acceleration beyond the class's jerk limit;
- ``heading``: heading more than the class's slip angle off the direction of motion (either
  way along the axis: reversing is motion), when moving at ``moving`` or more;
- ``teleport``: a step between consecutive frames longer than the recorded speeds and the
  class's acceleration allow, plus ``position_tol``;
- ``id_jump``: the same across frames in which the id was absent (it reappears too far away).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.timebase import ns_to_s
from workbench.quality.bounds import QualityBounds
from workbench.quality.kinematics import chord_heading, chord_speed, neighbours, window_slope

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from workbench.quality.tracks import Tracks

__all__ = ["Finding", "Kind", "check_tracks"]


class Kind(enum.StrEnum):
    """What a finding says is implausible."""

    SPEED_MISMATCH = "speed_mismatch"
    ACCEL = "accel"
    JERK = "jerk"
    HEADING = "heading"
    TELEPORT = "teleport"
    ID_JUMP = "id_jump"


_TINY = 1e-9
#: Unit of each kind's value and bound.
UNITS = {
    Kind.SPEED_MISMATCH: "m/s",
    Kind.ACCEL: "m/s²",
    Kind.JERK: "m/s³",
    Kind.HEADING: "deg",
    Kind.TELEPORT: "m",
    Kind.ID_JUMP: "m",
}


@dataclass(frozen=True, slots=True)
class Finding:
    """A run of implausible data of one object and kind.

    Attributes:
        object_id: The object (``"ego"`` for the ego).
        kind: What is implausible.
        start_frame: First frame affected.
        end_frame: Last frame affected (inclusive).
        start_ns: Time of ``start_frame``.
        end_ns: Time of ``end_frame``.
        frames: Observations flagged in the run.
        value: The worst measured value (its unit: :data:`UNITS`; accelerations signed).
        bound: The bound it broke at that observation (same unit and sign).
    """

    object_id: str
    kind: Kind
    start_frame: int
    end_frame: int
    start_ns: int
    end_ns: int
    frames: int
    value: float
    bound: float

    @property
    def excess(self) -> float:
        """How far beyond its bound the worst value is: ``|value| / |bound|`` (> 1)."""
        return abs(self.value) / max(abs(self.bound), _TINY)

    @property
    def unit(self) -> str:
        """Unit of ``value`` and ``bound``."""
        return UNITS[self.kind]

    def reason(self) -> str:
        """One line: ``"ego speed_mismatch 1.83 > 1.69 m/s (frames 22-22)"``."""
        return (
            f"{self.object_id} {self.kind} {self.value:.2f} beyond {self.bound:.2f} {self.unit}"
            f" (frames {self.start_frame}-{self.end_frame})"
        )

    def record(self) -> dict[str, object]:
        """JSON-ready (finite numbers only)."""
        return {
            "object_id": self.object_id,
            "kind": str(self.kind),
            "start_frame": self.start_frame,
            "end_frame": self.end_frame,
            "start_ns": self.start_ns,
            "end_ns": self.end_ns,
            "frames": self.frames,
            "value": round(self.value, 6),
            "bound": round(self.bound, 6),
            "unit": self.unit,
        }


def check_tracks(tracks: Tracks, bounds: QualityBounds | None = None) -> tuple[Finding, ...]:
    """Every finding of a drive, by object, then kind, then time.

    Args:
        tracks: The drive's observations.
        bounds: Thresholds (default :class:`QualityBounds`).
    """
    b = bounds or QualityBounds()
    if len(tracks) == 0:
        return ()
    codes = tracks.object_class[tracks.obj]
    classes = np.unique(codes)
    lim = {c: b.of(int(c)) for c in classes.tolist()}

    def per_obs(attr: str) -> NDArray[np.float64]:
        out = np.full(len(tracks), np.nan)
        for c, limits in lim.items():
            value = getattr(limits, attr)
            out[codes == c] = np.nan if value is None else value
        return out

    flags: list[tuple[Kind, NDArray[np.bool_], NDArray[np.float64], NDArray[np.float64]]] = []
    flags.append((Kind.SPEED_MISMATCH, *_speed(tracks, b)))
    back, ahead = neighbours(tracks, b.chord_span_ns)
    accel, jerk = _worse(
        _derivatives(tracks, tracks.speed_mps, b),
        _derivatives(tracks, chord_speed(tracks, back, ahead), b),
    )
    top = np.where(accel >= 0, per_obs("accel_mps2"), -per_obs("brake_mps2"))
    flags.append((Kind.ACCEL, np.abs(accel) > np.abs(top), accel, top))
    jerk_top = per_obs("jerk_mps3")
    flags.append((Kind.JERK, np.abs(jerk) > jerk_top, np.abs(jerk), jerk_top))
    flags.append((Kind.HEADING, *_heading(tracks, b, np.degrees(per_obs("slip_rad")))))
    step, step_top, gap = _steps(
        tracks, b, np.maximum(per_obs("accel_mps2"), per_obs("brake_mps2"))
    )
    flags.append((Kind.TELEPORT, (step > step_top) & ~gap, step, step_top))
    flags.append((Kind.ID_JUMP, (step > step_top) & gap, step, step_top))
    found = [f for kind, hit, value, bound in flags for f in _runs(tracks, kind, hit, value, bound)]
    order = {k: n for n, k in enumerate(Kind)}
    return tuple(sorted(found, key=lambda f: (f.object_id, order[f.kind], f.start_frame)))


def _derivatives(
    tracks: Tracks, speed_mps: NDArray[np.float64], b: QualityBounds
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Acceleration and jerk of a speed series: window slopes, ``(M,)`` each (NaN: none)."""
    accel = window_slope(tracks, speed_mps, b.window_half_ns)
    return accel, window_slope(tracks, accel, b.window_half_ns)


def _worse(
    recorded: tuple[NDArray[np.float64], NDArray[np.float64]],
    positions: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per observation the larger magnitude of the recorded speed's and the positions'."""
    out = []
    for a, p in zip(recorded, positions, strict=True):
        pick = np.isnan(a) | (np.abs(np.nan_to_num(p)) > np.abs(a))
        out.append(np.where(pick, p, a))
    return out[0], out[1]


def _speed(
    tracks: Tracks, b: QualityBounds
) -> tuple[NDArray[np.bool_], NDArray[np.float64], NDArray[np.float64]]:
    """Recorded speed against the chords just before and after (``(M,)`` each)."""
    back, ahead = neighbours(tracks, b.chord_span_ns)
    own = np.arange(len(tracks), dtype=np.int64)
    before = chord_speed(tracks, back, own)
    after = chord_speed(tracks, own, ahead)
    centre = chord_speed(tracks, back, ahead)
    v = tracks.speed_mps
    off = np.maximum(v - np.fmax(before, after), np.fmin(before, after) - v)
    dense = (
        tracks.t_ns[np.where(ahead >= 0, ahead, own)] - tracks.t_ns[np.where(back >= 0, back, own)]
    ) <= b.max_gap_ns
    checked = (back >= 0) & (ahead >= 0) & dense & np.isfinite(off)
    bound = b.speed_abs_mps + b.speed_rel * np.where(np.isfinite(centre), centre, 0.0)
    off = np.where(checked, np.maximum(off, 0.0), 0.0)
    return checked & (off > bound), off, bound


def _heading(
    tracks: Tracks, b: QualityBounds, slip_deg: NDArray[np.float64]
) -> tuple[NDArray[np.bool_], NDArray[np.float64], NDArray[np.float64]]:
    """Angle between the heading axis and the direction of motion [deg] (``(M,)`` each)."""
    back, ahead = neighbours(tracks, b.chord_span_ns)
    moving = chord_speed(tracks, back, ahead) >= b.moving_mps
    motion = chord_heading(tracks, back, ahead)
    off = np.abs(np.angle(np.exp(1j * (tracks.yaw_rad - motion))))
    axis = np.degrees(np.minimum(off, np.pi - off))
    checked = moving & (back >= 0) & (ahead >= 0) & np.isfinite(slip_deg) & np.isfinite(axis)
    return checked & (axis > slip_deg), np.where(checked, axis, 0.0), slip_deg


def _steps(
    tracks: Tracks, b: QualityBounds, accel_mps2: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Per observation: the step from the object's previous one [m], its bound, frames missing.

    ``(M,)`` each; a track's first observation has step 0, bound ``inf``, no gap.
    """
    m = len(tracks)
    prev = tracks.same_object(-1)
    j = np.clip(np.arange(m) - 1, 0, None)
    dt_s = np.where(prev, ns_to_s(tracks.t_ns - tracks.t_ns[j]), 0.0)
    step = np.where(prev, np.hypot(tracks.x_m - tracks.x_m[j], tracks.y_m - tracks.y_m[j]), 0.0)
    v = np.maximum(tracks.speed_mps, tracks.speed_mps[j])
    top = v * dt_s + 0.5 * accel_mps2 * dt_s * dt_s + b.position_tol_m
    gap = prev & (tracks.frame - tracks.frame[j] > 1)
    return np.where(prev, step, 0.0), np.where(prev, top, np.inf), gap


def _runs(
    tracks: Tracks,
    kind: Kind,
    hit: NDArray[np.bool_],
    value: NDArray[np.float64],
    bound: NDArray[np.float64],
) -> list[Finding]:
    """Consecutive flagged observations of one object as findings."""
    rows = np.flatnonzero(hit)
    if rows.size == 0:
        return []
    new = np.ones(rows.size, dtype=np.bool_)
    new[1:] = (np.diff(rows) != 1) | (tracks.obj[rows[1:]] != tracks.obj[rows[:-1]])
    starts = np.flatnonzero(new)
    ends = np.append(starts[1:], rows.size)
    score = np.abs(value[rows]) / np.maximum(np.abs(bound[rows]), _TINY)
    out = []
    for s, e in zip(starts.tolist(), ends.tolist(), strict=True):
        run = rows[s:e]
        worst = int(run[np.argmax(score[s:e])])
        first = int(run[0])
        if kind in {Kind.TELEPORT, Kind.ID_JUMP}:
            first -= 1  # the step starts at the previous observation
        last = int(run[-1])
        out.append(
            Finding(
                object_id=str(tracks.ids[tracks.obj[last]]),
                kind=kind,
                start_frame=int(tracks.frame[first]),
                end_frame=int(tracks.frame[last]),
                start_ns=int(tracks.t_ns[first]),
                end_ns=int(tracks.t_ns[last]),
                frames=int(e - s),
                value=float(value[worst]),
                bound=float(bound[worst]),
            )
        )
    return out
