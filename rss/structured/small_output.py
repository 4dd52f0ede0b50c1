"""Row results of the small-frame path (:mod:`rss.structured.small`).

:class:`Columns` gathers one frame's rows (:class:`Row`, a compiled record whose fields
are plain C values, one allocation per row), applies the memory for one frame
(``memory.apply_memory_both`` with ``F = 1``: a key's rows in order, the memory's entry of
its key remembered before the first) and keeps the memory after the frame by key; the
builders of :mod:`rss.structured.small_arrays` turn them into the engine's records when a
field is first read.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rss.structured.codes import (
    EGO_PRIORITY,
    I_ABLE_TO_BRAKE,
    I_SAFE_DISTANCE,
    IN_FRONT,
    OVERLAP_LEFT,
    OVERLAP_RIGHT,
    SAME_DIRECTION,
)

if TYPE_CHECKING:
    from rss.structured.memory import RssMemory
    from rss.structured.scalar_checks import LateralRow

__all__ = ["Columns", "Row", "recall"]


class Row:
    """One row's extracted situation and raw states (a compiled record: unboxed fields).

    The fields of one row of :class:`Relative` (positions, distances, lanes, distances to
    enter / leave the intersection) and of :class:`RawStates` (longitudinal and per side
    lateral verdicts, responses, evaluators, distances [m], intersection state); the
    responses are those after the memory (:meth:`Columns.apply_memory`).
    """

    def __init__(
        self,
        relative: tuple[int, float, int, float, bool],
        other_correct: bool,  # noqa: FBT001
        enter_leave: tuple[float, float, float, float],
    ) -> None:
        """The row's relative situation; its states are set by :meth:`add_states`."""
        self.lon_position, self.lon_distance_m = relative[0], relative[1]
        self.lat_position, self.lat_distance_m = relative[2], relative[3]
        self.ego_correct = relative[4]
        self.other_correct = other_correct
        self.ego_enter_m, self.ego_leave_m = enter_leave[0], enter_leave[1]
        self.other_enter_m, self.other_leave_m = enter_leave[2], enter_leave[3]
        self.lon_safe = self.dangerous = False
        self.lon_response = self.lon_evaluator = self.intersection_state = 0
        self.lon_current_m = self.lon_safe_m = 0.0
        self.left_safe = self.right_safe = False
        self.left_response = self.left_evaluator = 0
        self.right_response = self.right_evaluator = 0
        self.left_current_m = self.left_safe_m = self.right_current_m = self.right_safe_m = 0.0

    def relative(self) -> tuple[int, float, int, float, bool]:
        """``(lon position, lon distance, lat position, lat distance, ego in correct lane)``."""
        return (
            self.lon_position,
            self.lon_distance_m,
            self.lat_position,
            self.lat_distance_m,
            self.ego_correct,
        )

    def enter_leave(self) -> tuple[float, float, float, float]:
        """Distances to enter / leave the intersection (ego, then other) [m]."""
        return self.ego_enter_m, self.ego_leave_m, self.other_enter_m, self.other_leave_m

    def add_states(
        self, states: tuple[bool, int, int, float, float, LateralRow, LateralRow, int]
    ) -> None:
        """The row's raw states (``scalar_checks.check_row``)."""
        lon_safe, response, evaluator, current, safe, left, right, state = states
        self.lon_safe, self.lon_response, self.lon_evaluator = lon_safe, response, evaluator
        self.lon_current_m, self.lon_safe_m = current, safe
        self.left_safe, self.left_response, self.left_evaluator = left[0], left[1], left[2]
        self.left_current_m, self.left_safe_m = left[3], left[4]
        self.right_safe, self.right_response, self.right_evaluator = right[0], right[1], right[2]
        self.right_current_m, self.right_safe_m = right[3], right[4]
        self.intersection_state = state
        self.dangerous = not lon_safe and not (left[0] and right[0])


class Columns:
    """One frame's rows (:class:`Row`), memory after the frame and proper response."""

    def __init__(self, size: int) -> None:
        """No rows yet of ``size``."""
        self.size = size
        self.rows: list[Row] = []
        self.memory: dict[tuple[int, int, int], tuple[bool, bool, int]] = {}
        self.response: tuple[bool, tuple[int, int, int], tuple[float, ...]] = (
            True,
            (0, 0, 0),
            (),
        )
        self.matrices: tuple[Any, Any, Any] | None = None

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
        row = self.rows[c]
        intersection = ctype >= EGO_PRIORITY
        dangerous, lon_safe = row.dangerous, row.lon_safe
        lat_safe = row.left_safe and row.right_safe
        base = lon_safe if intersection else not dangerous
        overlap_assumption = (
            ctype == SAME_DIRECTION and OVERLAP_LEFT <= row.lat_position <= OVERLAP_RIGHT
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
                or (prev_int == I_SAFE_DISTANCE and row.lon_position == IN_FRONT)
            )
        )
        calm = not intersection and not dangerous
        if clear_lon or int_none or calm:
            row.lon_response = 0
        if clear_lat or calm:
            row.left_response = row.right_response = 0
        if not store:
            return None, base or candidate
        stored_int = row.intersection_state if intersection and base else 0
        stored_lat = not overlap_assumption if synthetic else lat_safe
        return (True if synthetic else lon_safe, stored_lat, stored_int), base or candidate


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
