"""Explicit memory of the unstructured checks (ad-rss keeps it inside its checker).

* ``other_must_brake``: per object, condition 22.1b of the last safe step before the
  danger threshold (carried forward while unsafe; forgotten when the object is absent for
  a step, as ad-rss swaps its map every time step).
* drive-away: per object, the heading range and the other's centre when DriveAway was
  decided; kept while the pair stays unsafe, the other does not move (1 mm) and the ego's
  ``yaw + steering`` stays inside the range.

Pass :meth:`UnstructuredMemory.empty` (or ``None``) to start fresh; store the memory per
frame and a replay can restart at any frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["UnstructuredMemory", "frozen"]


def frozen(values: np.ndarray) -> np.ndarray:
    """``values`` made read-only in place (a fresh array the caller owns)."""
    values.setflags(write=False)
    return values


def _frozen(values: object, dtype: type) -> np.ndarray:
    return frozen(np.array(values, dtype=dtype).reshape(-1))


@dataclass(frozen=True)
class UnstructuredMemory:
    """Memory after one step (read-only arrays).

    Attributes:
        must_brake_ids: ``(K,)`` object ids with a remembered 22.1b value.
        other_must_brake: ``(K,)`` the remembered value.
        drive_away_ids: ``(D,)`` object ids with a stored drive-away state.
        heading_begin_rad: ``(D,)`` allowed heading range begin (signed, may wrap).
        heading_end_rad: ``(D,)`` range end.
        other_x_m: ``(D,)`` the other's centre x when stored.
        other_y_m: ``(D,)`` centre y.
    """

    must_brake_ids: np.ndarray
    other_must_brake: np.ndarray
    drive_away_ids: np.ndarray
    heading_begin_rad: np.ndarray
    heading_end_rad: np.ndarray
    other_x_m: np.ndarray
    other_y_m: np.ndarray

    def __post_init__(self) -> None:
        """Freeze the arrays with their dtypes (a frozen 1-D array owning its data is kept)."""
        for name, dtype in _DTYPES.items():
            value = getattr(self, name)
            if not (
                isinstance(value, np.ndarray)
                and value.dtype == dtype
                and value.ndim == 1
                and value.flags.owndata
                and not value.flags.writeable
            ):
                object.__setattr__(self, name, _frozen(value, dtype))

    @staticmethod
    def of_fresh(*values: np.ndarray) -> UnstructuredMemory:
        """The memory of fresh 1-D arrays of the fields' dtypes (frozen here, not checked)."""
        out = object.__new__(UnstructuredMemory)
        for name, value in zip(_DTYPES, values, strict=True):
            value.setflags(write=False)
            object.__setattr__(out, name, value)
        return out

    @staticmethod
    def empty() -> UnstructuredMemory:
        """No history."""
        none = np.zeros(0)
        return UnstructuredMemory(none, none, none, none, none, none, none)

    def merged(self, other: UnstructuredMemory, object_ids: np.ndarray) -> UnstructuredMemory:
        """This memory plus ``other``'s entries of ``object_ids`` (carried over unchanged)."""
        brake = np.isin(other.must_brake_ids, object_ids)
        drive = np.isin(other.drive_away_ids, object_ids)
        return UnstructuredMemory(
            *(
                np.concatenate((getattr(self, f), getattr(other, f)[brake if i < 2 else drive]))  # noqa: PLR2004  (the two 22.1b fields come first)
                for i, f in enumerate(self.__dataclass_fields__)
            )
        )

    def lookup_must_brake(self, object_id: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(found, value)`` of the remembered 22.1b flag for ``(N,)`` object ids."""
        return _lookup(self.must_brake_ids, object_id, self.other_must_brake)

    def lookup_drive_away(self, object_id: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(found, index into the drive-away arrays)`` for ``(N,)`` object ids."""
        return _lookup(self.drive_away_ids, object_id, np.arange(self.drive_away_ids.shape[0]))


def _lookup(
    keys: np.ndarray, query: np.ndarray, values: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    if keys.shape[0] == 0:
        return np.zeros(query.shape, dtype=bool), np.zeros(query.shape, dtype=values.dtype)
    order = np.argsort(keys, kind="stable")
    pos = np.clip(np.searchsorted(keys[order], query), 0, keys.shape[0] - 1)
    found = keys[order][pos] == query
    return found, np.where(found, values[order][pos], np.zeros(1, dtype=values.dtype))


#: Field dtypes of :class:`UnstructuredMemory`.
_DTYPES: dict[str, type] = {
    name: np.int64 if name.endswith("ids") else bool if name == "other_must_brake" else np.float64
    for name in UnstructuredMemory.__dataclass_fields__
}
