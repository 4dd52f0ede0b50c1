"""A drive's objects as tracks: one row per observation, sorted by object then time.

The checks of :mod:`workbench.quality.checks` work on whole tracks, vectorised over every
observation of a drive at once. A structure of arrays in long format (``M`` observations,
not ``frames x objects``) keeps memory proportional to what the log holds, however many
object ids come and go. The ego is the object :data:`EGO_ID` (class car: the log does not
class it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.records import ObjectClass

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import NDArray

    from loaders.records import Frame

__all__ = ["EGO_ID", "TrackCollector", "Tracks", "tracks_from_frames"]

#: Object id of the ego in tracks and findings.
EGO_ID = "ego"


@dataclass(frozen=True, slots=True)
class Tracks:
    """Every observation of every object, sorted by object then time (``M`` rows).

    Attributes:
        ids: ``(K,)`` object ids; ``obj`` indexes them.
        object_class: ``(K,)`` :class:`loaders.records.ObjectClass` of each object (its
            first observation's).
        obj: ``(M,)`` index into ``ids`` of each observation.
        frame: ``(M,)`` frame index (``Frame.index``).
        t_ns: ``(M,)`` frame time.
        x_m: ``(M,)`` centre x in the map frame.
        y_m: ``(M,)`` centre y in the map frame.
        yaw_rad: ``(M,)`` heading (ENU, counter-clockwise from +x).
        speed_mps: ``(M,)`` recorded speed (magnitude; the ego's ``|speed_mps|``).
    """

    ids: NDArray[np.str_]
    object_class: NDArray[np.int8]
    obj: NDArray[np.int64]
    frame: NDArray[np.int64]
    t_ns: NDArray[np.int64]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    speed_mps: NDArray[np.float64]

    def __len__(self) -> int:
        """Number of observations ``M``."""
        return len(self.obj)

    def same_object(self, offset: int) -> NDArray[np.bool_]:
        """``(M,)``: observation ``i + offset`` exists and belongs to the object of ``i``."""
        m = len(self.obj)
        out = np.zeros(m, dtype=np.bool_)
        if offset == 0:
            out[:] = True
        elif 0 < offset < m:
            out[:-offset] = self.obj[offset:] == self.obj[:-offset]
        elif 0 < -offset < m:
            out[-offset:] = self.obj[:offset] == self.obj[-offset:]
        return out


class TrackCollector:
    """Gathers frames (in time order, chunk by chunk) into :class:`Tracks`."""

    def __init__(self) -> None:
        """Start with no observation."""
        self._columns: list[
            tuple[NDArray[np.str_], NDArray[np.int8], int, int, NDArray[np.float64]]
        ]
        self._columns = []

    def add(self, frames: Iterable[Frame]) -> None:
        """Add frames: the ego and every valid actor row."""
        for f in frames:
            a = f.actors
            keep = np.flatnonzero(a.valid)
            ego = f.ego
            values = np.empty((4, keep.size + 1), dtype=np.float64)
            values[:, 0] = (ego.x_m, ego.y_m, ego.yaw_rad, abs(ego.speed_mps))
            values[0, 1:] = a.x_m[keep]
            values[1, 1:] = a.y_m[keep]
            values[2, 1:] = a.yaw_rad[keep]
            values[3, 1:] = np.hypot(a.vx_mps[keep], a.vy_mps[keep])
            ids = np.concatenate((np.array([EGO_ID]), a.ids[keep].astype(np.str_)))
            classes = np.concatenate(
                (np.array([int(ObjectClass.CAR)], dtype=np.int8), a.object_class[keep])
            )
            self._columns.append((ids, classes, f.index, f.t_ns, values))

    def tracks(self) -> Tracks:
        """The observations so far as :class:`Tracks`."""
        if not self._columns:
            e = np.zeros(0, dtype=np.float64)
            i = np.zeros(0, dtype=np.int64)
            return Tracks(np.zeros(0, dtype="<U1"), np.zeros(0, np.int8), i, i, i, e, e, e, e)
        sizes = [len(c[0]) for c in self._columns]
        labels = np.concatenate([c[0] for c in self._columns])
        classes = np.concatenate([c[1] for c in self._columns])
        frame = np.repeat(np.array([c[2] for c in self._columns], dtype=np.int64), sizes)
        t_ns = np.repeat(np.array([c[3] for c in self._columns], dtype=np.int64), sizes)
        values = np.concatenate([c[4] for c in self._columns], axis=1)
        ids, first, obj = np.unique(labels, return_index=True, return_inverse=True)
        order = np.lexsort((t_ns, obj))
        return Tracks(
            ids=ids,
            object_class=classes[first],
            obj=obj.astype(np.int64)[order],
            frame=frame[order],
            t_ns=t_ns[order],
            x_m=values[0, order],
            y_m=values[1, order],
            yaw_rad=values[2, order],
            speed_mps=values[3, order],
        )


def tracks_from_frames(frames: Iterable[Frame]) -> Tracks:
    """Every frame's ego and valid actors as :class:`Tracks`."""
    collector = TrackCollector()
    collector.add(frames)
    return collector.tracks()
