"""Row results of the small-frame path (:mod:`rss.structured.small`) and their arrays.

:class:`Columns` gathers one frame's rows as Python lists, applies the memory for one
frame (``memory.apply_memory_both`` with ``F = 1`` and one row per key: every row is a run
of its own, its remembered state is the memory's entry of its key) and :func:`assemble`
turns the lists into the engine's records with a few array constructions.
"""

from __future__ import annotations

import array
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.structured.checks import LateralSide, RawStates
from rss.structured.codes import (
    EGO_PRIORITY,
    I_ABLE_TO_BRAKE,
    I_SAFE_DISTANCE,
    IN_FRONT,
    OVERLAP_LEFT,
    OVERLAP_RIGHT,
    SAME_DIRECTION,
)
from rss.structured.extraction import Relative
from rss.structured.response import ProperResponses

if TYPE_CHECKING:
    from rss.arrays import BoolArray
    from rss.structured.memory import RssMemory
    from rss.structured.scalar_checks import LateralRow

__all__ = [
    "Columns",
    "dangerous",
    "memory_columns",
    "raw_states",
    "recall",
    "relative",
    "responses",
]


class Columns:
    """One frame's rows as lists (the fields of :class:`Relative` and :class:`RawStates`)."""

    def __init__(self, size: int) -> None:
        """Empty columns for ``size`` rows."""
        self.size = size
        self.lon_position: list[int] = []
        self.lon_distance_m: list[float] = []
        self.lat_position: list[int] = []
        self.lat_distance_m: list[float] = []
        self.ego_correct: list[bool] = []
        self.other_correct: list[bool] = []
        self.enter_leave: list[tuple[float, float, float, float]] = []
        self.lon_safe: list[bool] = []
        self.lon_response: list[int] = []
        self.lon_evaluator: list[int] = []
        self.lon_current_m: list[float] = []
        self.lon_safe_m: list[float] = []
        self.left: list[LateralRow] = []
        self.right: list[LateralRow] = []
        self.left_response: list[int] = []
        self.right_response: list[int] = []
        self.intersection_state: list[int] = []
        self.dangerous: list[bool] = []
        self.memory: dict[tuple[int, int, int], tuple[bool, bool, int]] = {}
        self.response: tuple[bool, tuple[int, int, int], tuple[float, ...]] = (
            True,
            (0, 0, 0),
            (),
        )

    def add_relative(
        self,
        relative: tuple[int, float, int, float, bool],
        other_correct: bool,  # noqa: FBT001
        enter_leave: tuple[float, float, float, float],
    ) -> None:
        """Append one row's relative situation."""
        self.lon_position.append(relative[0])
        self.lon_distance_m.append(relative[1])
        self.lat_position.append(relative[2])
        self.lat_distance_m.append(relative[3])
        self.ego_correct.append(relative[4])
        self.other_correct.append(other_correct)
        self.enter_leave.append(enter_leave)

    def add_states(
        self, states: tuple[bool, int, int, float, float, LateralRow, LateralRow, int]
    ) -> None:
        """Append one row's raw states (``scalar_checks.check_row``)."""
        lon_safe, response, evaluator, current, safe, left, right, state = states
        self.lon_safe.append(lon_safe)
        self.lon_response.append(response)
        self.lon_evaluator.append(evaluator)
        self.lon_current_m.append(current)
        self.lon_safe_m.append(safe)
        self.left.append(left)
        self.right.append(right)
        self.left_response.append(left[1])
        self.right_response.append(right[1])
        self.intersection_state.append(state)
        self.dangerous.append(not lon_safe and not (left[0] and right[0]))

    def apply_memory(
        self,
        ctypes: list[int],
        keys: list[tuple[int, int, int]],
        before: dict[tuple[int, int, int], tuple[bool, bool, int]],
        *,
        unique: bool,
    ) -> None:
        """Clear responses by the remembered safe states; gather the memory after the frame.

        Args:
            ctypes: Constellation type per row.
            keys: ``(ego id, object id, type)`` per row.
            before: The memory before the frame by key (:func:`recall`).
            unique: One row per key (no scan within the frame).
        """
        after = self.memory
        if unique:
            for c, ctype in enumerate(ctypes):
                key = keys[c]
                initial = before.get(key)
                entry = self._remember(c, ctype, initial, initial, seen=False)[0] or initial
                if entry is not None:
                    after[key] = entry
            return
        stored: dict[tuple[int, int, int], tuple[bool, bool, int]] = {}
        events: set[tuple[int, int, int]] = set()
        for c, ctype in enumerate(ctypes):
            key = keys[c]
            initial = before.get(key)
            entry, event = self._remember(
                c, ctype, stored.get(key, initial), initial, seen=key in events
            )
            if entry is not None:
                stored[key] = entry
            if event:
                events.add(key)
        for key in keys:
            last = stored.get(key, before.get(key))
            if last is not None:
                after[key] = last

    def _remember(
        self,
        c: int,
        ctype: int,
        entry: tuple[bool, bool, int] | None,
        initial: tuple[bool, bool, int] | None,
        *,
        seen: bool,
    ) -> tuple[tuple[bool, bool, int] | None, bool]:
        """Row ``c`` of the scan (rows of one key in row order, one run of frame 0).

        Args:
            c: The row.
            ctype: Its constellation type.
            entry: What an earlier row of its key stored, else ``initial``.
            initial: The memory of its key before the frame.
            seen: An earlier row of its key was safe or dangerous non-intersection (no
                synthetic memory after it).

        Returns:
            ``(what the row stores or None, whether it is safe or dangerous
            non-intersection)``.
        """
        intersection = ctype >= EGO_PRIORITY
        dangerous, lon_safe = self.dangerous[c], self.lon_safe[c]
        lat_safe = self.left[c][0] and self.right[c][0]
        base = lon_safe if intersection else not dangerous
        overlap_assumption = (
            ctype == SAME_DIRECTION and OVERLAP_LEFT <= self.lat_position[c] <= OVERLAP_RIGHT
        )
        known = entry is not None
        prev_lon, prev_lat, prev_int = entry if entry is not None else (False, False, 0)
        candidate = dangerous and not intersection
        synthetic = candidate and initial is None and not seen
        store = base or synthetic
        clear_lon = candidate and known and prev_lat and not prev_lon
        clear_lat = candidate and (
            (known and prev_lon and not prev_lat) or (synthetic and overlap_assumption)
        )
        int_none = (
            intersection
            and not lon_safe
            and known
            and (
                (prev_int == I_ABLE_TO_BRAKE and ctype == EGO_PRIORITY)
                or (prev_int == I_SAFE_DISTANCE and self.lon_position[c] == IN_FRONT)
            )
        )
        calm = not intersection and not dangerous
        if clear_lon or int_none or calm:
            self.lon_response[c] = 0
        if clear_lat or calm:
            self.left_response[c] = self.right_response[c] = 0
        if not store:
            return None, base or candidate
        stored_int = self.intersection_state[c] if intersection and base else 0
        stored_lat = not overlap_assumption if synthetic else lat_safe
        return (True if synthetic else lon_safe, stored_lat, stored_int), base or candidate


def _matrix(values: list[Any], typecode: str, dtype: type, rows: int) -> Any:
    """``values`` (``rows`` columns one after the other) as a ``(rows, n)`` array.

    ``array.array`` converts a flat list in one C loop; numpy wraps its buffer.
    """
    return np.frombuffer(array.array(typecode, values), dtype=dtype).reshape(rows, -1)


def _matrices(out: Columns) -> tuple[Any, Any, Any]:
    """``(12, C)`` floats, ``(10, C)`` ints and ``(6, C)`` flags: every row field of ``out``."""
    left, right = out.left, out.right
    lanes = list(zip(*out.enter_leave, strict=True))
    floats = _matrix(
        [
            *out.lon_distance_m,
            *out.lat_distance_m,
            *lanes[0],
            *lanes[1],
            *lanes[2],
            *lanes[3],
            *out.lon_current_m,
            *out.lon_safe_m,
            *[row[3] for row in left],
            *[row[4] for row in left],
            *[row[3] for row in right],
            *[row[4] for row in right],
        ],
        "d",
        np.float64,
        12,
    )
    ints = _matrix(
        [
            *out.lon_position,
            *out.lat_position,
            *out.lon_response,
            *out.lon_evaluator,
            *out.intersection_state,
            *out.left_response,
            *[row[2] for row in left],
            *out.right_response,
            *[row[2] for row in right],
            *[0] * out.size,
        ],
        "q",
        np.int64,
        10,
    )
    flags = _matrix(
        [
            *out.ego_correct,
            *out.other_correct,
            *out.lon_safe,
            *out.dangerous,
            *[row[0] for row in left],
            *[row[0] for row in right],
        ],
        "b",
        np.bool_,
        6,
    )
    return floats, ints, flags


def relative(out: Columns) -> Relative:
    """The frame's :class:`Relative` (``(C,)`` arrays)."""
    floats, ints, flags = _matrices(out)
    return Relative(
        lon_position=ints[0],
        lon_distance_m=floats[0],
        lat_position=ints[1],
        lat_distance_m=floats[1],
        ego_in_correct_lane=flags[0],
        other_in_correct_lane=flags[1],
        ego_dist_to_enter_m=floats[2],
        ego_dist_to_leave_m=floats[3],
        other_dist_to_enter_m=floats[4],
        other_dist_to_leave_m=floats[5],
        invalid=ints[9],
    )


def raw_states(out: Columns) -> RawStates:
    """The frame's memory-adjusted :class:`RawStates` (``(C,)`` arrays)."""
    floats, ints, flags = _matrices(out)
    return RawStates(
        lon_is_safe=flags[2],
        lon_response=ints[2],
        lon_evaluator=ints[3],
        lon_current_distance_m=floats[6],
        lon_safe_distance_m=floats[7],
        left=LateralSide(flags[4], ints[5], ints[6], floats[8], floats[9]),
        right=LateralSide(flags[5], ints[7], ints[8], floats[10], floats[11]),
        intersection_state=ints[4],
    )


def dangerous(out: Columns) -> BoolArray:
    """``(C,)`` dangerous constellations."""
    flags: BoolArray = np.array(out.dangerous, dtype=np.bool_)
    return flags


def responses(out: Columns) -> ProperResponses:
    """The frame's proper response as ``(1,)`` arrays.

    Two array constructions (codes and limits, rows read as views) and one of the flag;
    the record is filled without the frozen dataclass's ``__init__`` (ten
    ``object.__setattr__`` calls, half the cost of the arrays at this size).
    """
    is_safe, codes, limits = out.response
    code_rows = np.array(codes, dtype=np.int64).reshape(3, 1)
    limit_rows = np.array(limits, dtype=np.float64).reshape(6, 1)
    record: ProperResponses = object.__new__(ProperResponses)
    record.__dict__.update(
        is_safe=np.array([is_safe]),
        longitudinal_response=code_rows[0],
        lateral_response_left=code_rows[1],
        lateral_response_right=code_rows[2],
        lon_min_mps2=limit_rows[0],
        lon_max_mps2=limit_rows[1],
        lat_left_min_mps2=limit_rows[2],
        lat_left_max_mps2=limit_rows[3],
        lat_right_min_mps2=limit_rows[4],
        lat_right_max_mps2=limit_rows[5],
    )
    return record


def memory_columns(after: dict[tuple[int, int, int], tuple[bool, bool, int]]) -> list[Any]:
    """The six :class:`RssMemory` arrays of the memory ``after`` (by key, sorted, ``M >= 1``)."""
    entries = sorted((*key, *entry) for key, entry in after.items())
    columns = list(zip(*entries, strict=True))
    keys = _matrix([*columns[0], *columns[1], *columns[2], *columns[5]], "q", np.int64, 4)
    verdicts = _matrix([*columns[3], *columns[4]], "b", np.bool_, 2)
    return [keys[0], keys[1], keys[2], verdicts[0], verdicts[1], keys[3]]


def recall(memory: RssMemory) -> dict[tuple[int, int, int], tuple[bool, bool, int]]:
    """The entries of ``memory`` by key (the last entry of a key wins)."""
    before: dict[tuple[int, int, int], tuple[bool, bool, int]] = {}
    for key_e, key_o, key_t, lon, lat, state in zip(
        memory.ego_id.tolist(),
        memory.object_id.tolist(),
        memory.constellation_type.tolist(),
        memory.lon_safe.tolist(),
        memory.lat_safe.tolist(),
        memory.intersection_state.tolist(),
        strict=True,
    ):
        before[key_e, key_o, key_t] = (lon, lat, state)
    return before
