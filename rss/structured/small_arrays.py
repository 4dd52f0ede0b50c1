"""Arrays of the small-frame path's results, built when a field is first read.

The row path (:mod:`rss.structured.small`) leaves one frame's rows, proper response and
memory as Python values in a :class:`rss.structured.small_output.Columns`;
``engine.SmallFrameResult`` and ``small_result.SmallMemory`` call these builders on the
first read of a field. Each returns the record :func:`rss.structured.engine.check_frames`
returns for the frame (``(C,)`` arrays; the proper response ``(1,)``), built with a few
array constructions; the records are filled without their frozen ``__init__``
(:func:`_record`).
"""

from __future__ import annotations

import array
from typing import TYPE_CHECKING, Any, Final, TypeVar

import numpy as np

from rss.structured.checks import LateralSide, RawStates
from rss.structured.extraction import Relative
from rss.structured.response import ProperResponses

if TYPE_CHECKING:
    from rss.arrays import BoolArray
    from rss.structured.small_output import Columns

__all__ = ["dangerous", "memory_columns", "raw_states", "relative", "responses"]

# numpy's callables and types as module constants: native names in mypyc, no attribute
# look-ups on the module per call (dtypes passed positionally, no keyword tuple per call)
_ARRAY: Final = np.array
_INT64: Final = np.int64
_FLOAT64: Final = np.float64
_BOOL: Final = np.bool_
_R = TypeVar("_R")


def _matrix(values: list[Any], typecode: str, dtype: type, width: int) -> Any:
    """``values`` (``C`` rows of ``width`` fields one after the other) as ``(width, C)``.

    ``array.array`` converts a flat list in one C loop; numpy wraps its buffer, and the
    transposed copy makes every field's row contiguous.
    """
    flat: Any = np.frombuffer(array.array(typecode, values), dtype=dtype)
    return flat.reshape(-1, width).T.copy()


def _matrices(out: Columns) -> tuple[Any, Any, Any]:
    """``(12, C)`` floats, ``(10, C)`` ints and ``(6, C)`` flags: every row field of ``out``.

    Built once per result (:func:`relative` and :func:`raw_states` share them).
    """
    if out.matrices is not None:
        return out.matrices
    floats: list[float] = []
    ints: list[int] = []
    flags: list[bool] = []
    for r in out.rows:
        floats.extend(
            (
                r.lon_distance_m,
                r.lat_distance_m,
                r.ego_enter_m,
                r.ego_leave_m,
                r.other_enter_m,
                r.other_leave_m,
                r.lon_current_m,
                r.lon_safe_m,
                r.left_current_m,
                r.left_safe_m,
                r.right_current_m,
                r.right_safe_m,
            )
        )
        ints.extend(
            (
                r.lon_position,
                r.lat_position,
                r.lon_response,
                r.lon_evaluator,
                r.intersection_state,
                r.left_response,
                r.left_evaluator,
                r.right_response,
                r.right_evaluator,
                0,
            )
        )
        flags.extend(
            (r.ego_correct, r.other_correct, r.lon_safe, r.dangerous, r.left_safe, r.right_safe)
        )
    out.matrices = (
        _matrix(floats, "d", np.float64, 12),
        _matrix(ints, "q", np.int64, 10),
        _matrix(flags, "b", np.bool_, 6),
    )
    return out.matrices


def _record(cls: type[_R], **fields: Any) -> _R:
    """A frozen dataclass record of ``fields`` (every field), filled without its ``__init__``.

    The generated ``__init__`` of a frozen dataclass sets each field by
    ``object.__setattr__``: at a few rows that costs as much as the arrays it holds.
    """
    record = object.__new__(cls)
    record.__dict__.update(fields)
    return record


def relative(out: Columns) -> Relative:
    """The frame's :class:`Relative` (``(C,)`` arrays)."""
    floats, ints, flags = _matrices(out)
    return _record(
        Relative,
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


def _side(flags: Any, ints: Any, floats: Any, at: tuple[int, int, int, int, int]) -> LateralSide:
    """One :class:`LateralSide` from rows ``at`` of the flag, int, int, float, float matrices."""
    return _record(
        LateralSide,
        is_safe=flags[at[0]],
        response=ints[at[1]],
        evaluator=ints[at[2]],
        current_distance_m=floats[at[3]],
        safe_distance_m=floats[at[4]],
    )


def raw_states(out: Columns) -> RawStates:
    """The frame's memory-adjusted :class:`RawStates` (``(C,)`` arrays)."""
    floats, ints, flags = _matrices(out)
    return _record(
        RawStates,
        lon_is_safe=flags[2],
        lon_response=ints[2],
        lon_evaluator=ints[3],
        lon_current_distance_m=floats[6],
        lon_safe_distance_m=floats[7],
        left=_side(flags, ints, floats, (4, 5, 6, 8, 9)),
        right=_side(flags, ints, floats, (5, 7, 8, 10, 11)),
        intersection_state=ints[4],
    )


def dangerous(out: Columns) -> BoolArray:
    """``(C,)`` dangerous constellations."""
    flags: BoolArray = _ARRAY([r.dangerous for r in out.rows], _BOOL)
    return flags


def responses(out: Columns) -> ProperResponses:
    """The frame's proper response as ``(1,)`` arrays.

    Two array constructions (codes and limits, rows read as views) and one of the flag;
    the record is filled without the frozen dataclass's ``__init__`` (:func:`_record`).
    """
    is_safe, codes, limits = out.response
    code_rows = _ARRAY(codes, _INT64).reshape(3, 1)
    limit_rows = _ARRAY(limits, _FLOAT64).reshape(6, 1)
    return _record(
        ProperResponses,
        is_safe=_ARRAY([is_safe]),
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


def memory_columns(after: dict[tuple[int, int, int], tuple[bool, bool, int]]) -> list[Any]:
    """The six :class:`RssMemory` arrays of the memory ``after`` (by key, sorted, ``M >= 1``)."""
    entries = sorted((*key, *entry) for key, entry in after.items())
    keys = _matrix([v for e in entries for v in (e[0], e[1], e[2], e[5])], "q", np.int64, 4)
    verdicts = _matrix([v for e in entries for v in (e[3], e[4])], "b", np.bool_, 2)
    return [keys[0], keys[1], keys[2], verdicts[0], verdicts[1], keys[3]]
