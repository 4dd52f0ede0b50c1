"""The objects of each incident, highlighted and labelled over the incident's frames (pure).

::

    world/incidents/<engine>/<incident id>   Boxes3D: the incident's objects at each of its
                                             frames, labelled with their short label (#1)

The replay keeps the boxes of every culprit of an unsafe frame while it runs (small: only
unsafe frames' culprits), and lays them out per incident once the incidents are known. The
review blueprint shows only the incident under review's entity, with the other actors dimmed
and unlabelled (:func:`workbench.replay.blueprint.replay_blueprint`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from workbench.replay.layout import yaw_to_quaternion

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    from numpy.typing import NDArray

    from workbench.driver.run import Chunk
    from workbench.incidents import Incident

__all__ = ["HIGHLIGHT_ORIGIN", "CulpritBoxes", "Highlight", "highlight_path", "worst_frame"]

#: Origin of the incidents' highlighted objects (under ``world``, so the scene shows them).
HIGHLIGHT_ORIGIN = "world/incidents"


def highlight_path(incident: Incident, escape: Callable[[str], str] = str) -> str:
    """The entity of an incident's highlighted objects."""
    return f"{HIGHLIGHT_ORIGIN}/{incident.engine}/{escape(incident.id)}"


def worst_frame(incident: Incident) -> int:
    """The frame a viewer or a thumbnail shows for ``incident``: its worst, else its first."""
    worst = incident.worst_frame
    inside = worst is not None and incident.start_frame <= worst <= incident.end_frame
    return worst if inside and worst is not None else incident.start_frame


@dataclass(frozen=True, slots=True)
class Highlight:
    """One incident's objects: ``R`` box rows over ``T`` frames (``counts`` per frame).

    The last frame may have no row (``counts`` 0): it clears the boxes after the incident.
    """

    path: str
    frames: NDArray[np.int64]
    t_ns: NDArray[np.int64]
    counts: NDArray[np.int64]
    centre_m: NDArray[np.float32]
    half_size_m: NDArray[np.float32]
    quaternion_xyzw: NDArray[np.float32]
    labels: NDArray[np.str_]


class CulpritBoxes:
    """Collects the boxes of the culprits of every unsafe frame, chunk by chunk."""

    def __init__(self) -> None:
        """Start empty."""
        # (frame, t_ns, object id, cx, cy, cz, half l, half w, half h, yaw)
        self._rows: list[tuple[int, int, str, float, float, float, float, float, float, float]]
        self._rows = []
        #: Ego position ``(x, y)`` [m] at every unsafe frame (any engine).
        self.ego_m: dict[int, tuple[float, float]] = {}
        self._by_frame: dict[int, dict[str, tuple[float, ...]]] | None = None

    def add_chunk(self, chunk: Chunk) -> None:
        """Keep the boxes of the objects any engine named as culprit of an unsafe frame."""
        self._by_frame = None
        for k, frame in enumerate(chunk.frames):
            unsafe = [v[k] for v in chunk.verdicts.values() if not v[k].is_safe]
            if not unsafe:
                continue
            self.ego_m[frame.index] = (frame.ego.x_m, frame.ego.y_m)
            culprits = {c for verdict in unsafe for c in verdict.culprits}
            actors = frame.actors
            for j, oid in enumerate(actors.ids.tolist()):
                if oid in culprits and bool(actors.valid[j]):
                    self._rows.append(
                        (
                            frame.index,
                            frame.t_ns,
                            str(oid),
                            float(actors.x_m[j]),
                            float(actors.y_m[j]),
                            float(actors.z_m[j]),
                            0.5 * float(actors.length_m[j]),
                            0.5 * float(actors.width_m[j]),
                            0.5 * float(actors.height_m[j]),
                            float(actors.yaw_rad[j]),
                        )
                    )

    def at(
        self, frame: int, objects: Sequence[str]
    ) -> tuple[tuple[float, float] | None, list[tuple[float, float]]]:
        """The ego's and ``objects``' positions ``(x, y)`` [m] at an unsafe ``frame``.

        ``(None, [])`` for a frame no engine rated unsafe; an object that was no culprit
        there is left out.
        """
        boxes = self.boxes_at(frame, objects)
        return self.ego_m.get(frame), [(float(b[0]), float(b[1])) for b in boxes]

    def boxes_at(self, frame: int, objects: Sequence[str]) -> NDArray[np.float64]:
        """``(N, 7)`` boxes of ``objects`` at an unsafe ``frame``, in the order given.

        Columns: centre x, y, z [m], half length, half width, half height [m], yaw [rad].
        An object that was no culprit there is left out.
        """
        if self._by_frame is None:
            self._by_frame = {}
            for row in self._rows:
                self._by_frame.setdefault(row[0], {})[row[2]] = row[3:]
        there = self._by_frame.get(frame, {})
        return np.array([there[o] for o in objects if o in there], dtype=np.float64).reshape(-1, 7)

    def layout(
        self,
        incidents: Sequence[Incident],
        labels: Mapping[str, str],
        frame_times: Sequence[tuple[int, int]],
        escape: Callable[[str], str] = str,
    ) -> list[Highlight]:
        """Per incident, its objects' boxes at its frames, then an empty frame after it.

        Args:
            incidents: The drive's incidents.
            labels: Short label per object id (``#1``): the drive's table
                (:mod:`workbench.replay.short_labels`).
            frame_times: ``(frame, t_ns)`` of every frame, in order.
            escape: Escapes an id as one entity path part.
        """
        order = [f for f, _ in frame_times]
        position = {f: k for k, f in enumerate(order)}
        out = []
        for incident in incidents:
            wanted = set(incident.objects)
            rows = [
                r
                for r in self._rows
                if r[2] in wanted and incident.start_frame <= r[0] <= incident.end_frame
            ]
            if not rows:
                continue
            frames = sorted({r[0] for r in rows})
            t_of = {r[0]: r[1] for r in rows}
            counts = [sum(r[0] == f for r in rows) for f in frames]
            after = position.get(incident.end_frame, len(order)) + 1
            if after < len(order):
                frames.append(order[after])
                t_of[order[after]] = frame_times[after][1]
                counts.append(0)
            rows.sort(key=lambda r: (r[0], r[2]))
            data = np.array([r[3:] for r in rows], dtype=np.float64).reshape(-1, 7)
            out.append(
                Highlight(
                    path=highlight_path(incident, escape),
                    frames=np.array(frames, dtype=np.int64),
                    t_ns=np.array([t_of[f] for f in frames], dtype=np.int64),
                    counts=np.array(counts, dtype=np.int64),
                    centre_m=data[:, 0:3].astype(np.float32),
                    half_size_m=data[:, 3:6].astype(np.float32),
                    quaternion_xyzw=yaw_to_quaternion(data[:, 6]),
                    labels=np.array([labels.get(r[2], r[2]) for r in rows], dtype=str),
                )
            )
        return out
