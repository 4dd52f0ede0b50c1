"""Who must act: the same constellations checked from the other object's side, vectorised.

RSS is symmetric: each participant of a pair has its own proper response. ad-rss computes
only the ego's. Here every constellation is also checked with the roles swapped — the other
object as "ego", the ego as "other" — in the same road area, by the same kernels
(:func:`rss.structured.checks.check_all`) on swapped arrays, and adjusted by the same
memory of the pair (:func:`rss.structured.memory.apply_memory_both`)::

    ego side      ego    other   rel.lon_position p   lat q   ego_in_correct   EgoHasPriority
    object side   other  ego     4 - p                4 - q   other_in_correct ObjectHasPriority

A participant *must act* when the constellation is dangerous from its own side and its
proper response restricts it (longitudinal or a lateral response other than ``None``): in a
same-direction pair the rear one (longitudinally), in opposite direction both (BrakeMin /
BrakeMinCorrect), laterally both, at intersections as the priority and the remembered safe
state decide.

The danger itself is symmetric in the RSS paper, but ad-rss' checks are written from the
ego's side and are not exactly symmetric: in opposite direction the ego's
``is_in_correct_lane`` alone picks who brakes with ``brake_min_correct`` (so two vehicles
both in their correct lanes get different safe distances from each side), and the
intersection checks try the ego's stop first. Each side is therefore judged by its own
check (measured on 600 random ad-rss cases: the two sides disagree on danger in about 1 %,
all opposite-direction or intersection pairs; same-direction pairs always agree).
"""

from __future__ import annotations

import dataclasses
import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.structured.memory import is_dangerous

if TYPE_CHECKING:
    from rss.arrays import BoolArray, IntArray
    from rss.structured.batch import ConstellationBatch
    from rss.structured.checks import RawStates
    from rss.structured.extraction import Relative

__all__ = ["Responsibility", "Responsible", "must_act", "responsibility", "swap_roles"]

_MIRROR = 4  # LongitudinalPosition / LateralPosition codes 0..4 mirror as 4 - code


class Responsible(enum.IntEnum):
    """Who must act in a constellation (codes of :attr:`Responsibility.responsible`)."""

    NONE = 0
    EGO = 1
    OBJECT = 2
    BOTH = 3

    def __str__(self) -> str:
        """Record spelling: ``none``, ``ego``, ``object``, ``both``."""
        return self.name.lower()


@dataclass(frozen=True)
class Responsibility:
    """Both sides of ``C`` constellations.

    Attributes:
        object_states: Memory-adjusted states from the other object's side (its own lateral
            left / right; longitudinal response codes of :class:`LongitudinalResponse`).
        object_dangerous: ``(C,)`` dangerous (and valid) from the object's side.
        ego_must_act: ``(C,)`` dangerous and the ego's proper response restricts it.
        object_must_act: ``(C,)`` dangerous from its side and the object's proper response
            restricts it.
        responsible: ``(C,)`` :class:`Responsible` codes.
    """

    object_states: RawStates
    object_dangerous: BoolArray
    ego_must_act: BoolArray
    object_must_act: BoolArray
    responsible: IntArray


def swap_roles(batch: ConstellationBatch, rel: Relative) -> tuple[ConstellationBatch, Relative]:
    """The constellations with ego and other exchanged (same road areas, mirrored positions).

    Args:
        batch: ``C`` constellations.
        rel: Their relative situation (ego w.r.t. other).

    Returns:
        ``(batch, rel)`` from the other's side (``(C,)`` arrays, no copies of the road areas).
    """
    ctype = batch.constellation_type
    ego_prio = int(ConstellationType.IntersectionEgoHasPriority)
    other_prio = int(ConstellationType.IntersectionObjectHasPriority)
    swapped_type = np.where(
        ctype == ego_prio, other_prio, np.where(ctype == other_prio, ego_prio, ctype)
    ).astype(np.int64)
    swapped = dataclasses.replace(
        batch,
        constellation_type=swapped_type,
        ego=batch.other,
        other=batch.ego,
        ego_dynamics=batch.other_dynamics,
        other_dynamics=batch.ego_dynamics,
    )
    mirrored = dataclasses.replace(
        rel,
        lon_position=(_MIRROR - rel.lon_position).astype(np.int64),
        lat_position=(_MIRROR - rel.lat_position).astype(np.int64),
        ego_in_correct_lane=rel.other_in_correct_lane,
        other_in_correct_lane=rel.ego_in_correct_lane,
        ego_dist_to_enter_m=rel.other_dist_to_enter_m,
        ego_dist_to_leave_m=rel.other_dist_to_leave_m,
        other_dist_to_enter_m=rel.ego_dist_to_enter_m,
        other_dist_to_leave_m=rel.ego_dist_to_leave_m,
    )
    return swapped, mirrored


def must_act(states: RawStates, dangerous: BoolArray) -> BoolArray:
    """``(C,)`` dangerous constellations whose proper response restricts that side."""
    restricted = (states.lon_response != 0) | (states.left.response != 0)
    restricted |= states.right.response != 0
    return np.asarray(dangerous & restricted, dtype=np.bool_)


def responsibility(
    ego_states: RawStates, object_states: RawStates, dangerous: BoolArray, valid: BoolArray
) -> Responsibility:
    """Combine both sides' memory-adjusted states of ``C`` constellations.

    Args:
        ego_states: The ego side's states (the engine's result).
        object_states: The object side's states.
        dangerous: ``(C,)`` dangerous and valid constellations (the ego's side).
        valid: ``(C,)`` evaluated constellations.

    Returns:
        Who must act per constellation.
    """
    object_dangerous = np.asarray(is_dangerous(object_states) & valid, dtype=np.bool_)
    ego = must_act(ego_states, dangerous)
    other = must_act(object_states, object_dangerous)
    code = ego.astype(np.int64) * int(Responsible.EGO) + other.astype(np.int64) * int(
        Responsible.OBJECT
    )
    return Responsibility(object_states, object_dangerous, ego, other, code)
