"""Whether nothing can collide between the ego and one object, from the scenario's states only.

Independent of every engine of ours: the recorded states of ``loaders.commonroad_scenario``
(positions, headings, speeds, rectangle sizes) and plain geometry. Per time step:

- *both stand*: both speeds at most ``STAND_MPS``;
- *far and opening*: the gap between the two rectangles over ``FAR_M`` and the centre distance
  growing (range rate > 0);
- *laterally clear*: in the ego's frame, every corner of the object at least ``CLEAR_M``
  beyond the ego's side, on one side, and the lateral clearance not shrinking faster than
  ``CONVERGE_MPS`` (speed noise of the recorded traces).

A run of steps is *benign* when every step with both states is one of these.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from loaders.commonroad_scenario import Track

#: At most this speed is standing [m/s].
STAND_MPS = 0.5
#: A gap over this is far [m] (the acceptance criterion of issue 27).
FAR_M = 15.0
#: Laterally clear by at least this [m] (same).
CLEAR_M = 1.5
#: Lateral clearance shrinking slower than this is not converging [m/s].
CONVERGE_MPS = 0.2


@dataclass(frozen=True, slots=True)
class StepFacts:
    """One step of an ego-object pair.

    Attributes:
        step: CommonRoad time step.
        ego_speed_mps: Ego speed.
        object_speed_mps: Object speed.
        gap_m: Distance between the two rectangles (0 when they overlap).
        range_rate_mps: Rate of the centre distance (> 0 opening).
        lateral_clear_m: Lateral clearance in the ego's frame (0 when they overlap laterally).
        lateral_rate_mps: Rate of that clearance (> 0 diverging).
    """

    step: int
    ego_speed_mps: float
    object_speed_mps: float
    gap_m: float
    range_rate_mps: float
    lateral_clear_m: float
    lateral_rate_mps: float

    @property
    def both_stand(self) -> bool:
        """Both speeds at most ``STAND_MPS``."""
        return self.ego_speed_mps <= STAND_MPS and self.object_speed_mps <= STAND_MPS

    @property
    def far_opening(self) -> bool:
        """Gap over ``FAR_M`` and opening."""
        return self.gap_m > FAR_M and self.range_rate_mps > 0

    @property
    def laterally_clear(self) -> bool:
        """Clear by ``CLEAR_M`` sideways and not converging."""
        return self.lateral_clear_m >= CLEAR_M and self.lateral_rate_mps >= -CONVERGE_MPS

    @property
    def benign(self) -> bool:
        """Nothing can collide at this step."""
        return self.both_stand or self.far_opening or self.laterally_clear

    def reason(self) -> str:
        """Which benign condition holds (for messages)."""
        if self.both_stand:
            return "both stand"
        if self.far_opening:
            return f"gap > {FAR_M:.0f} m opening"
        if self.laterally_clear:
            return f"laterally clear >= {CLEAR_M} m"
        return "not benign"


def _corners(track: Track, i: int) -> NDArray[np.float64]:
    c, s = math.cos(track.yaw_rad[i]), math.sin(track.yaw_rad[i])
    hl, hw = track.length_m / 2, track.width_m / 2
    local = np.array([[hl, hw], [hl, -hw], [-hl, -hw], [-hl, hw]])
    rot = np.array([[c, -s], [s, c]])
    return np.asarray(local @ rot.T + [track.x_m[i], track.y_m[i]], dtype=np.float64)


def _segment_distance(
    p: NDArray[np.float64], a: NDArray[np.float64], b: NDArray[np.float64]
) -> float:
    ab = b - a
    t = float(np.clip(np.dot(p - a, ab) / np.dot(ab, ab), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + t * ab)))


def _cross(u: NDArray[np.float64], v: NDArray[np.float64]) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def _inside(p: NDArray[np.float64], box: NDArray[np.float64]) -> bool:
    signs = [_cross(box[(k + 1) % 4] - box[k], p - box[k]) for k in range(4)]
    return all(v >= 0 for v in signs) or all(v <= 0 for v in signs)


def rectangle_gap_m(a: NDArray[np.float64], b: NDArray[np.float64]) -> float:
    """Distance between two convex quadrilaterals given by their 4 corners (0 if they overlap)."""
    if any(_inside(p, b) for p in a) or any(_inside(p, a) for p in b):
        return 0.0
    pairs = [(p, b) for p in a] + [(p, a) for p in b]
    return min(_segment_distance(p, q[k], q[(k + 1) % 4]) for p, q in pairs for k in range(4))


def _lateral_clear(ego: Track, i: int, corners: NDArray[np.float64]) -> float:
    c, s = math.cos(ego.yaw_rad[i]), math.sin(ego.yaw_rad[i])
    lat = -(corners[:, 0] - ego.x_m[i]) * s + (corners[:, 1] - ego.y_m[i]) * c
    half = ego.width_m / 2
    if lat.min() > half:
        return float(lat.min() - half)
    if lat.max() < -half:
        return float(-half - lat.max())
    return 0.0


def pair_facts(ego: Track, other: Track, steps_s: tuple[int, int, float]) -> list[StepFacts]:
    """Facts at every step in ``[first, last]`` at which both have a state.

    ``steps_s``: ``(first step, last step, step length [s])``.

    Rates are central differences over the neighbouring steps both have (one-sided at the ends;
    0 when only one step).
    """
    ego_at = {int(s): i for i, s in enumerate(ego.steps)}
    other_at = {int(s): j for j, s in enumerate(other.steps)}
    first_step, last_step, dt_s = steps_s
    steps = sorted(s for s in ego_at.keys() & other_at.keys())
    raw: dict[int, tuple[float, float, float]] = {}
    for step in steps:
        i, j = ego_at[step], other_at[step]
        corners = _corners(other, j)
        centre = math.hypot(other.x_m[j] - ego.x_m[i], other.y_m[j] - ego.y_m[i])
        raw[step] = (
            rectangle_gap_m(_corners(ego, i), corners),
            centre,
            _lateral_clear(ego, i, corners),
        )
    facts: list[StepFacts] = []
    for k, step in enumerate(steps):
        if not first_step <= step <= last_step:
            continue
        lo, hi = steps[max(k - 1, 0)], steps[min(k + 1, len(steps) - 1)]
        span = ((hi - lo) or 1) * dt_s
        i, j = ego_at[step], other_at[step]
        facts.append(
            StepFacts(
                step=step,
                ego_speed_mps=float(math.hypot(ego.vx_mps[i], ego.vy_mps[i])),
                object_speed_mps=float(math.hypot(other.vx_mps[j], other.vy_mps[j])),
                gap_m=raw[step][0],
                range_rate_mps=(raw[hi][1] - raw[lo][1]) / span,
                lateral_clear_m=raw[step][2],
                lateral_rate_mps=(raw[hi][2] - raw[lo][2]) / span,
            )
        )
    return facts
