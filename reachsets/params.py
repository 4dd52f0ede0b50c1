"""Parameters of the reach-set supervisor: frozen dataclasses with units in their names.

Defaults follow the reference's ``supmod_config.ini`` ``[RULE_REACH_SET]`` and its sim/ci
vehicle parameters (see ``docs/reachsets.md``).
"""

from __future__ import annotations

import enum
import functools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from reachsets.errors import ParamsError

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "F1Params",
    "ReachMethod",
    "ReachParams",
    "RoadRuleParams",
    "RoboraceParams",
]


class ReachMethod(enum.StrEnum):
    """How the reachable set of another vehicle is computed."""

    SIMPLE = "simple"
    TURN = "turn"
    BOUND = "bound"


@dataclass(frozen=True, slots=True)
class F1Params:
    """F1 "racing alongside" and "defending off-line" rules.

    Attributes:
        enabled: Evaluate the F1 rules (ignored when a Roborace zone map is given).
        d_overlap: Required longitudinal overlap fraction for "alongside" (0.2 = 20 %).
        len_patch_m: Length of a patch along the track.
        width_extra_bound_m: How far a patch reaches beyond the wall (avoids slivers).
        d_corner_m: "Approaching a corner" distance.
        d_defend_m: Ego within this distance behind the object counts as being defended.
        kappa_thr_inv_m: Curvature above which a centre-line point belongs to a corner.
        veh_width_factor: Defending patch width as a multiple of the ego width.
    """

    enabled: bool = True
    d_overlap: float = 0.2
    len_patch_m: float = 100.0
    width_extra_bound_m: float = 1.0
    d_corner_m: float = 150.0
    d_defend_m: float = 30.0
    kappa_thr_inv_m: float = 0.01
    veh_width_factor: float = 1.1


@dataclass(frozen=True, slots=True)
class RoboraceParams:
    """Roborace Season Alpha rule.

    Attributes:
        t_trigger_s: A chaser triggers its lead when the time gap is below this.
        patch_width_m: Lateral reach of each half-track patch from the centre line.
    """

    t_trigger_s: float = 7.0
    patch_width_m: float = 50.0


@dataclass(frozen=True, slots=True)
class RoadRuleParams:
    """Public-road rules (our design; see ``rules_road``).

    Attributes:
        enabled: Evaluate the road rules when a road layout is given.
        speed_tolerance: Others are assumed to stay below ``limit * (1 + tolerance)``.
        brake_comfort_mps2: Deceleration a yielding vehicle is assumed able to use.
        on_road_margin_m: Footprint may stick out of the road by this much and still count
            as "on the road".
        lane_rules: Evaluate the lane rules (``road.keep_lane``, ``road.no_cut_in``, see
            ``rules_lane``). Off by default (the reference has no lane rules); the workbench
            turns them on for recorded road drives (``--reach-rules public-road``).
        lane_change_v_lat_mps: Lateral velocity towards a side (relative to the lane) from
            which a vehicle counts as changing lanes to that side.
        lane_change_offset_m: Offset of the centre from the lane's centre line towards a side
            from which a vehicle counts as changing lanes to that side.
        lane_margin_m: A footprint sticking out of its lane by more than this is crossing.
        cut_in_gap_s: Time gap (at the ego's current speed) before and behind the ego in
            its lane into which no vehicle may change lanes.
        cut_in_gap_min_m: Smallest such gap.
        corridor_length_m: How far along successor lanes a lane corridor reaches.
        standstill_speed_mps: With the lane rules: an object at or below this speed while
            the ego stands does not start into the ego (``road.standstill``,
            ``rules_standstill``); 0 = off.
    """

    enabled: bool = True
    speed_tolerance: float = 0.1
    brake_comfort_mps2: float = 4.0
    on_road_margin_m: float = 0.1
    lane_rules: bool = False
    lane_change_v_lat_mps: float = 0.5
    lane_change_offset_m: float = 0.6
    lane_margin_m: float = 0.1
    cut_in_gap_s: float = 0.9
    cut_in_gap_min_m: float = 2.0
    corridor_length_m: float = 300.0
    standstill_speed_mps: float = 0.5


@dataclass(frozen=True, slots=True)
class ReachParams:
    """All reach-set parameters.

    Attributes:
        t_max_s: Prediction horizon.
        dt_s: Step of the ego occupancy and reach-set grid.
        method: Reach-set method.
        trim_to_drivable: Intersect every reach set with the track / road polygon.
        a_max_mps2: Acceleration bound of the ``simple`` set (reference: max of localgg ax, ay).
        ax_max_mps2: Longitudinal bound for ``turn``/``bound`` and for braking along arcs.
        ay_max_mps2: Lateral bound of the steering arcs.
        ax_machine_v_mps: Speeds of the machine acceleration limit table.
        ax_machine_mps2: Machine acceleration limits at those speeds (``bound`` only).
        turn_radius_m: Smallest turn radius of the other vehicles.
        arc_points: Points per steering arc.
        arc_step_m: Chord length between arc points.
        arc_max_turn_rad: Arcs stop turning after this heading change (keeps them simple).
        closed_track_gap_m: A track whose centre line ends this close to its start is closed.
        keep_largest_part_only: Reference behaviour: keep only the largest polygon after
            trimming and subtraction. Off by default: dropping parts under-approximates.
        keep_object_body: ``turn``/``bound``: keep the object's own body (and what its sides
            sweep while turning) out of the deletion polygon. Off by default, as in the
            reference, which deletes everything behind the object's front corners; on is
            the sound variant (it flags more steps on the TUM logs).
        full_geometry: Reduce every reachable set (for display). When False, only the
            cells whose unreduced ``simple`` set touches the ego footprint are reduced; the
            verdict is identical (reductions only shrink sets) and much cheaper.
        rules_enabled: Master switch of all rules.
        f1: F1 rule parameters.
        roborace: Roborace rule parameters.
        road: Public-road rule parameters.
    """

    t_max_s: float = 4.0
    dt_s: float = 0.2
    method: ReachMethod = ReachMethod.TURN
    trim_to_drivable: bool = True
    a_max_mps2: float = 13.0
    ax_max_mps2: float = 13.0
    ay_max_mps2: float = 13.0
    ax_machine_v_mps: tuple[float, ...] = (0.0, 36.0, 40.0, 48.0, 60.0, 72.0)
    ax_machine_mps2: tuple[float, ...] = (6.0, 6.0, 5.7, 4.8, 3.9, 2.5)
    turn_radius_m: float = 11.0
    arc_points: int = 15
    arc_step_m: float = 3.0
    arc_max_turn_rad: float = math.pi / 2
    closed_track_gap_m: float = 35.0
    keep_largest_part_only: bool = False
    keep_object_body: bool = False
    full_geometry: bool = True
    rules_enabled: bool = True
    f1: F1Params = field(default_factory=F1Params)
    roborace: RoboraceParams = field(default_factory=RoboraceParams)
    road: RoadRuleParams = field(default_factory=RoadRuleParams)

    def __post_init__(self) -> None:
        """Validate ranges."""
        positive = {
            "t_max_s": self.t_max_s,
            "dt_s": self.dt_s,
            "a_max_mps2": self.a_max_mps2,
            "ax_max_mps2": self.ax_max_mps2,
            "ay_max_mps2": self.ay_max_mps2,
            "turn_radius_m": self.turn_radius_m,
            "arc_step_m": self.arc_step_m,
        }
        for name, value in positive.items():
            if not (math.isfinite(value) and value > 0):
                raise ParamsError(name, value, "a finite value > 0")
        if self.dt_s > self.t_max_s:
            raise ParamsError("dt_s", self.dt_s, f"<= t_max_s ({self.t_max_s})")
        if self.arc_points < 2:  # noqa: PLR2004
            raise ParamsError("arc_points", self.arc_points, ">= 2")
        if len(self.ax_machine_v_mps) != len(self.ax_machine_mps2):
            raise ParamsError("ax_machine_mps2", self.ax_machine_mps2, "one value per speed")
        object.__setattr__(self, "method", ReachMethod(self.method))

    @property
    def n_steps(self) -> int:
        """Number of time stamps ``T`` on the grid ``0, dt, ..., t_max``."""
        return round(self.t_max_s / self.dt_s) + 1

    @property
    def times_s(self) -> tuple[float, ...]:
        """The grid stamps, rounded to 1e-9 s."""
        return tuple(_grid(self.t_max_s, self.dt_s).tolist())

    @property
    def times_array_s(self) -> NDArray[np.float64]:
        """``times_s`` as a read-only ``(T,)`` array (computed once per grid)."""
        return _grid(self.t_max_s, self.dt_s)


@functools.lru_cache(maxsize=16)
def _grid(t_max_s: float, dt_s: float) -> NDArray[np.float64]:
    n = round(t_max_s / dt_s) + 1
    out = np.array([round(k * dt_s, 9) for k in range(n)])
    out.flags.writeable = False
    return out
