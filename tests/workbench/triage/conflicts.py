"""Independent criticality facts on the NGSIM scenarios: the numpy side and the conflict records.

Everything here is computed from the scenario's recorded states (``loaders.commonroad_scenario``
tracks), never from an engine of ours. Conventions (the criticality-metrics catalogue,
Westhofen et al. 2022, as cited by commonroad-crime):

- a pair-step is *in path* when the other vehicle's centre lies within half the two widths plus
  0.5 m of the ego's heading line (``IN_PATH_MARGIN_M``) and ahead of the ego;
- the gap is the bumper-to-bumper distance along the ego's heading (centre distance minus half
  the two lengths), the closing speed the ego's speed minus the other's along that heading;
- with both accelerations 0, TTC = gap / closing speed and the required deceleration (to match
  the other's speed before touching) = closing² / (2 gap);
- a pair-step is a *real conflict* when it is in path, closing, the gap positive, and TTC ≤
  1.5 s or the required deceleration ≥ 3.4 m/s².

Flagged pair-steps of one object become a conflict per run of consecutive time steps (a gap of
up to ``MERGE_STEPS`` steps is bridged).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from loaders.commonroad_scenario import load_scenario

if TYPE_CHECKING:
    from collections.abc import Iterable
    from pathlib import Path

    from loaders.commonroad_scenario import Scenario, Track

#: TTC at or below this is critical [s] (criticality-metrics catalogue).
TTC_THRESHOLD_S = 1.5
#: Required deceleration at or above this is critical [m/s²] (same catalogue).
DECEL_THRESHOLD_MPS2 = 3.4
#: In-path gate: lateral centre offset at most half the two widths plus this [m].
IN_PATH_MARGIN_M = 0.5
#: Flagged steps of one object at most this many steps apart belong to one conflict.
MERGE_STEPS = 2


@dataclass(frozen=True, slots=True)
class PairStep:
    """One other vehicle at one ego time step, in the ego's frame.

    Attributes:
        object_id: The other vehicle.
        step: CommonRoad time step.
        gap_m: Bumper-to-bumper gap along the heading (``inf``: not ahead).
        lateral_m: Lateral centre offset [m] (signed, left positive).
        closing_mps: Ego speed minus the other's along the heading [m/s].
        ttc_s: Time to collision at constant speeds (``inf``: not closing or not ahead).
        decel_mps2: Required deceleration [m/s²] (0 when not closing).
        in_path: The in-path gate holds.
        lateral_limit_m: The gate's limit for this pair [m].
    """

    object_id: str
    step: int
    gap_m: float
    lateral_m: float
    closing_mps: float
    ttc_s: float
    decel_mps2: float
    in_path: bool
    lateral_limit_m: float

    @property
    def critical(self) -> bool:
        """In path, closing and TTC or required deceleration over its threshold."""
        return is_critical(self.in_path, self.gap_m, self.ttc_s, self.decel_mps2)


def is_critical(in_path: bool, gap_m: float, ttc_s: float, decel_mps2: float) -> bool:
    """The real-conflict rule on one pair-step (closing means a finite TTC)."""
    closing = math.isfinite(ttc_s) and gap_m > 0
    return in_path and closing and (ttc_s <= TTC_THRESHOLD_S or decel_mps2 >= DECEL_THRESHOLD_MPS2)


def in_path_limit_m(ego: Track, other: Track) -> float:
    """Largest lateral centre offset [m] that counts as in the ego's path."""
    return (ego.width_m + other.width_m) / 2 + IN_PATH_MARGIN_M


def default_ego(scenario: Scenario) -> Track:
    """The vehicle the CommonRoad loader promotes by default (longest-lived, then id)."""
    return scenario.candidates()[0]


def numpy_pair_steps(xml: Path) -> tuple[str, list[PairStep]]:
    """Every other dynamic vehicle at every ego step, recomputed with plain numpy.

    Returns:
        The ego id and the pair-steps (other vehicles within 150 m of the ego only).
    """
    scenario = load_scenario(xml)
    ego = default_ego(scenario)
    steps: list[PairStep] = []
    ego_at = {int(s): i for i, s in enumerate(ego.steps)}
    for other in scenario.tracks:
        if not other.dynamic or other.id == ego.id:
            continue
        limit = in_path_limit_m(ego, other)
        for j, step in enumerate(other.steps):
            i = ego_at.get(int(step))
            if i is None:
                continue
            steps.extend(_pair_step(ego, i, other, j, limit))
    return ego.id, steps


def _pair_step(ego: Track, i: int, other: Track, j: int, limit: float) -> list[PairStep]:
    dx, dy = other.x_m[j] - ego.x_m[i], other.y_m[j] - ego.y_m[i]
    if math.hypot(dx, dy) > 150.0:
        return []
    c, s = math.cos(ego.yaw_rad[i]), math.sin(ego.yaw_rad[i])
    lon, lat = dx * c + dy * s, -dx * s + dy * c
    v_ego = ego.vx_mps[i] * c + ego.vy_mps[i] * s
    v_other = other.vx_mps[j] * c + other.vy_mps[j] * s
    closing = float(v_ego - v_other)
    gap = float(lon - (ego.length_m + other.length_m) / 2) if lon > 0 else math.inf
    ttc = gap / closing if closing > 0 and 0 < gap < math.inf else math.inf
    decel = closing**2 / (2 * gap) if closing > 0 and 0 < gap < math.inf else 0.0
    in_path = bool(lon > 0 and abs(lat) <= limit)
    return [
        PairStep(other.id, int(ego.steps[i]), gap, float(lat), closing, ttc, decel, in_path, limit)
    ]


@dataclass(frozen=True, slots=True)
class Conflict:
    """A run of critical pair-steps of one object.

    Attributes:
        object_id: The other vehicle.
        first_step: First critical CommonRoad time step.
        last_step: Last critical time step (inclusive).
        min_ttc_s: Smallest TTC over the run [s].
        max_decel_mps2: Largest required deceleration [m/s²].
        min_gap_m: Smallest gap [m].
        max_closing_mps: Largest closing speed [m/s].
    """

    object_id: str
    first_step: int
    last_step: int
    min_ttc_s: float
    max_decel_mps2: float
    min_gap_m: float
    max_closing_mps: float

    def record(self, ego_first_step: int) -> dict[str, Any]:
        """JSON-ready (all finite: a conflict has a finite TTC); frames count from the ego's
        first step."""
        return {
            "object": self.object_id,
            "frames": [self.first_step - ego_first_step, self.last_step - ego_first_step],
            "steps": [self.first_step, self.last_step],
            "min_ttc_s": round(self.min_ttc_s, 3),
            "max_required_decel_mps2": round(self.max_decel_mps2, 3),
            "min_gap_m": round(self.min_gap_m, 3),
            "max_closing_mps": round(self.max_closing_mps, 3),
        }


def conflicts(pair_steps: Iterable[PairStep]) -> list[Conflict]:
    """Group the critical pair-steps into conflicts, by object then time."""
    by_object: dict[str, list[PairStep]] = {}
    for p in pair_steps:
        if p.critical:
            by_object.setdefault(p.object_id, []).append(p)
    found: list[Conflict] = []
    for object_id, flagged in sorted(by_object.items()):
        flagged.sort(key=lambda p: p.step)
        run = [flagged[0]]
        for p in flagged[1:]:
            if p.step - run[-1].step > MERGE_STEPS + 1:
                found.append(_conflict(object_id, run))
                run = []
            run.append(p)
        found.append(_conflict(object_id, run))
    return found


def _conflict(object_id: str, run: list[PairStep]) -> Conflict:
    return Conflict(
        object_id=object_id,
        first_step=run[0].step,
        last_step=run[-1].step,
        min_ttc_s=min(p.ttc_s for p in run),
        max_decel_mps2=max(p.decel_mps2 for p in run),
        min_gap_m=min(p.gap_m for p in run),
        max_closing_mps=max(p.closing_mps for p in run),
    )


def flag_agreement(ours: Iterable[PairStep], theirs: Iterable[PairStep]) -> dict[str, int | float]:
    """How often two computations flag the same pair-steps (over pair-steps both computed).

    Returns:
        ``compared``, ``both``, ``only_first``, ``only_second``, ``agree`` (share of the
        compared pair-steps with the same flag), ``near_threshold`` (disagreements where
        either side's TTC is within 0.2 s of 1.5 s or its deceleration within 0.4 m/s² of
        3.4 m/s², or its lateral offset within 0.3 m of the gate).
    """
    first = {(p.object_id, p.step): p for p in ours}
    second = {(p.object_id, p.step): p for p in theirs}
    keys = first.keys() & second.keys()
    both = only_first = only_second = near = 0
    for key in keys:
        a, b = first[key].critical, second[key].critical
        both += a and b
        only_first += a and not b
        only_second += b and not a
        if a != b and (_near(first[key]) or _near(second[key])):
            near += 1
    compared = len(keys)
    agree = (compared - only_first - only_second) / compared if compared else 1.0
    return {
        "compared": compared,
        "both": both,
        "only_first": only_first,
        "only_second": only_second,
        "agree": round(agree, 6),
        "near_threshold": near,
    }


def _near(p: PairStep) -> bool:
    return bool(
        abs(p.ttc_s - TTC_THRESHOLD_S) <= 0.2
        or abs(p.decel_mps2 - DECEL_THRESHOLD_MPS2) <= 0.4
        or abs(abs(p.lateral_m) - p.lateral_limit_m) <= 0.3
    )


def near_path(pair_steps: Iterable[PairStep], slack_m: float = 1.0) -> set[tuple[str, int]]:
    """``(object id, step)`` of the pair-steps ahead within the in-path gate plus ``slack_m``.

    The only pair-steps another computation of the same rule could flag, up to its own
    lateral offset differing by less than ``slack_m`` from this one's.
    """
    return {
        (p.object_id, p.step)
        for p in pair_steps
        if p.gap_m < math.inf and abs(p.lateral_m) <= p.lateral_limit_m + slack_m
    }
