"""One integer id space per drive: the drive's actor label table, shared by its engines.

Loaders name actors by strings (a CommonRoad obstacle id, a ROS object id, a track label).
The RSS engines key constellations and their memory by ``int64`` ids. One
:class:`ActorIds` table per drive turns labels into engine ids and back, and every engine
of the drive uses the same table (:func:`workbench.engines.registry.build_runners` makes
one per call), so an object has one id in every engine and every label keeps its own id::

    "7"     ->  7             canonical decimal labels keep their value (NGSIM ids,
    "42"    ->  42            RSS constellation ids and reports agree with the log)
    "007"   ->  2**40         every other label (leading zeros, letters, > 12 digits)
    "car_3" ->  2**40 + 1     gets the next id of its own range, in order of appearance

Canonical decimal labels are below ``10**12 < 2**40``, so the two ranges never meet, and
both stay below the reserved ids of road boundaries (``2**61 + k``) and of the ego
(:data:`EGO_OBJECT_ID`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import NDArray

__all__ = ["EGO_OBJECT_ID", "FIRST_LABEL_ID", "ActorIds"]

#: Id of the ego in constellations (never a published actor id).
EGO_OBJECT_ID = 2**62
#: Engine id of the first non-canonical label (``"007"``, ``"car_3"``) of a drive.
FIRST_LABEL_ID = 2**40
_MAX_DECIMAL_DIGITS = 12


def _canonical_value(label: str) -> int | None:
    """The value of a canonical decimal label (``"7"``; not ``"007"``, ``"+7"``, ``"12.0"``)."""
    if not (label.isascii() and label.isdigit()) or len(label) >= _MAX_DECIMAL_DIGITS:
        return None
    if len(label) > 1 and label[0] == "0":
        return None
    return int(label)


class ActorIds:
    """The drive's label table: actor label <-> engine id, one-to-one."""

    def __init__(self) -> None:
        """Start empty; non-canonical labels get ``2**40``, ``2**40 + 1``, ... as they appear."""
        self._ids: dict[str, int] = {}
        self._labels: dict[int, str] = {}
        self._next = FIRST_LABEL_ID

    def __len__(self) -> int:
        """Number of labels seen so far."""
        return len(self._ids)

    def to_int(self, label: str) -> int:
        """The engine id of ``label`` (the same for the whole drive)."""
        value = self._ids.get(label)
        if value is None:
            canonical = _canonical_value(label)
            value = self._next if canonical is None else canonical
            self._next += canonical is None
            self._ids[label] = value
            self._labels[value] = label
        return value

    def to_ints(self, labels: Iterable[object]) -> NDArray[np.int64]:
        """``(N,)`` engine ids of ``labels`` (each taken as ``str``)."""
        return np.array([self.to_int(str(label)) for label in labels], dtype=np.int64)

    def label(self, value: int) -> str:
        """The actor label of an engine id (``str(value)`` for an id no label had)."""
        return self._labels.get(value, str(value))
