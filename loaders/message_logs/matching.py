"""Object buffers: last message per topic, velocity estimation, matching and extrapolation.

Matching rule (``docs/loaders.md``): a frame at time ``t`` takes, per object topic, the
latest message with stamp ``t_m <= t`` if ``t - t_m <= tolerance``, whatever its place in
the file; newer messages are never used. The pick is made when the ego message arrives
(:func:`pick_messages`) and replaced by any message arriving later that is stamped closer
to ``t`` (:meth:`Pick.offer`) until it is settled (:meth:`Pick.settled`): stamped ``t``
itself, or the topic has a message stamped after ``t``. Rows are extrapolated at constant
velocity to ``t`` and ``match_dt_ns = t - t_m`` is recorded per row::

    object msgs   o---------o---------o
    ego frames        |         |         |
                  <--> match_dt (extrapolated by v * match_dt)

Message types without velocity get one by finite differences per id between consecutive
messages of the topic. An id seen for the first time has no previous position: its
velocity is the forward difference to the topic's next message holding it, filled in when
the topic's next message arrives (the frame waits for it, at most ``MAX_HELD`` frames,
:meth:`FirstDetections.fill`); an id seen once only keeps velocity 0 and is counted.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.records import ActorTable
from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from loaders.message_logs.samples import ObjectColumns

__all__ = [
    "FirstDetections",
    "ObjectBuffer",
    "ObjectMessage",
    "Pick",
    "match_objects",
    "pick_messages",
]


@dataclass(slots=True, eq=False)
class ObjectMessage:
    """One object message of a topic, velocities filled in.

    Attributes:
        t_ns: Its time on the frame clock (log time or header stamp) [ns].
        columns: Its objects.
        first_seen: Its ids without a velocity yet (first detections of a type without
            velocity).
        taken: Whether a frame took it.
    """

    t_ns: int
    columns: ObjectColumns
    first_seen: frozenset[str] = frozenset()
    taken: bool = False


class ObjectBuffer:
    """The last object message of one topic, and what became of the topic's messages."""

    def __init__(self, topic: str) -> None:
        """Start empty for ``topic``."""
        self.topic = topic
        self.message: ObjectMessage | None = None
        #: Messages received and messages a frame took.
        self.received = 0
        self.taken = 0
        #: Forward-difference velocities of first detections, by the stamp of the message
        #: they were first seen in, then id (pruned by :meth:`prune`).
        self.forward: dict[int, dict[str, tuple[float, float]]] = {}

    @property
    def t_ns(self) -> int | None:
        """Time of the last message [ns], None before the first."""
        return None if self.message is None else self.message.t_ns

    def update(self, t_ns: int, cols: ObjectColumns) -> None:
        """Replace the buffer with a newer message (estimating velocities if needed)."""
        first_seen: frozenset[str] = frozenset()
        if not cols.has_velocity:
            vx = np.zeros(len(cols.ids))
            vy = np.zeros(len(cols.ids))
            old = self.message
            first = set(cols.ids)
            if old is not None and t_ns > old.t_ns:
                dt = ns_to_s(t_ns - old.t_ns)
                where = {oid: k for k, oid in enumerate(old.columns.ids)}
                ahead: dict[str, tuple[float, float]] = {}
                for k, oid in enumerate(cols.ids):
                    j = where.get(oid)
                    if j is not None:
                        vx[k] = (cols.x_m[k] - old.columns.x_m[j]) / dt
                        vy[k] = (cols.y_m[k] - old.columns.y_m[j]) / dt
                        first.discard(oid)
                        if oid in old.first_seen:
                            ahead[oid] = (float(vx[k]), float(vy[k]))
                if ahead:
                    self.forward[old.t_ns] = ahead
            first_seen = frozenset(first)
            object.__setattr__(cols, "vx_mps", vx)
            object.__setattr__(cols, "vy_mps", vy)
        self.message = ObjectMessage(t_ns, cols, first_seen)
        self.received += 1

    def take(self, message: ObjectMessage) -> None:
        """Count ``message`` as taken by a frame (once, however many frames take it)."""
        if not message.taken:
            message.taken = True
            self.taken += 1

    @property
    def unused_total(self) -> int:
        """Messages no frame took so far, counting the one buffered now."""
        return self.received - self.taken

    def prune(self, before_ns: int) -> None:
        """Forget forward velocities of messages stamped before ``before_ns``."""
        for t in [t for t in self.forward if t < before_ns]:
            del self.forward[t]


@dataclass(slots=True)
class FirstDetections:
    """Rows of one frame's actor table still without velocity (first detections).

    Attributes:
        rows: ``(row, buffer, message stamp [ns], object id)`` per such row.
    """

    rows: list[tuple[int, ObjectBuffer, int, str]] = field(default_factory=list)

    def settled(self) -> bool:
        """Whether every row's topic has a message newer than the row's (or none wait)."""
        return all(buf.t_ns is not None and buf.t_ns > t for _, buf, t, _ in self.rows)

    def fill(self, actors: ActorTable) -> tuple[ActorTable, int]:
        """``actors`` with the forward velocities known by now; and the rows left at 0.

        A filled row is extrapolated by its velocity over its ``match_dt_ns`` like every
        other row.
        """
        if not self.rows:
            return actors, 0
        vx, vy = actors.vx_mps.copy(), actors.vy_mps.copy()
        x, y = actors.x_m.copy(), actors.y_m.copy()
        left = 0
        for row, buf, t_msg, oid in self.rows:
            v = buf.forward.get(t_msg, {}).get(oid)
            if v is None:
                left += 1
                continue
            dt = ns_to_s(actors.match_dt_ns[row])
            vx[row], vy[row] = v
            x[row] += v[0] * dt
            y[row] += v[1] * dt
        columns = {f: getattr(actors, f) for f in ActorTable.__dataclass_fields__}
        columns.update(vx_mps=vx, vy_mps=vy, x_m=x, y_m=y)  # finite: validity unchanged
        return ActorTable.from_columns(**columns), left


@dataclass(slots=True)
class Pick:
    """The object message one frame takes from one topic, while later ones may replace it.

    Attributes:
        buffer: The topic's buffer (its forward velocities fill first detections).
        message: The message taken, None while the topic has none in tolerance.
    """

    buffer: ObjectBuffer
    message: ObjectMessage | None = None

    def offer(self, frame_ns: int, tolerance_ns: int) -> None:
        """Take the topic's last message if it is a closer match for the frame at ``frame_ns``.

        Closer: stamped ``frame_ns - tolerance <= t_m <= frame_ns`` and after the message
        taken so far (logs that write a stamp's objects after its ego message, or, on the
        header clock, perception stamped at the sensor time and logged after later egos).
        """
        m = self.buffer.message
        if m is None or not 0 <= frame_ns - m.t_ns <= tolerance_ns:
            return
        if self.message is None or m.t_ns > self.message.t_ns:
            self.message = m

    def settled(self, frame_ns: int) -> bool:
        """Whether no later message can be closer: stamped ``frame_ns``, or the topic is past it.

        A topic's stamps increase: once it has a message stamped after the frame, no message
        stamped at or before it follows.
        """
        last = self.buffer.t_ns
        taken = self.message
        return (taken is not None and taken.t_ns == frame_ns) or (
            last is not None and last > frame_ns
        )

    def keep(self) -> None:
        """Count the message taken as used (the frame is final)."""
        if self.message is not None:  # an empty list is used too: no objects of the topic
            self.buffer.take(self.message)


def pick_messages(buffers: list[ObjectBuffer], t_ns: int, tolerance_ns: int) -> list[Pick]:
    """Per buffer, the message a frame at ``t_ns`` takes when its ego message arrives."""
    picks = []
    for buf in buffers:
        pick = Pick(buf)
        pick.offer(t_ns, tolerance_ns)
        picks.append(pick)
    return picks


def match_objects(
    picks: list[Pick],
    t_ns: int,
    exclude_id: str | None = None,
) -> tuple[ActorTable, FirstDetections]:
    """Build the actor table of a frame at ``t_ns`` from its picks (see module docstring).

    Ids are prefixed with ``<topic>:`` when more than one object topic is in use. Also
    returns the rows that are first detections without a velocity yet.
    """
    for pick in picks:
        pick.keep()
    parts = [
        (p.buffer, p.message) for p in picks if p.message is not None and p.message.columns.ids
    ]
    first = FirstDetections()
    if not parts:
        return ActorTable.empty(), first
    prefix = len(picks) > 1
    ids: list[str] = []
    columns: dict[str, list[NDArray[Any]]] = {}
    for buf, message in parts:
        topic, cols, dt_ns = buf.topic, message.columns, t_ns - message.t_ns
        first.rows.extend(
            (len(ids) + k, buf, message.t_ns, oid)
            for k, oid in enumerate(cols.ids)
            if oid in message.first_seen
        )
        ids.extend(f"{topic}:{i}" for i in cols.ids) if prefix else ids.extend(cols.ids)
        dt = ns_to_s(dt_ns)
        values: dict[str, NDArray[Any]] = {
            "object_class": cols.object_class,
            "x_m": cols.x_m + cols.vx_mps * dt,
            "y_m": cols.y_m + cols.vy_mps * dt,
            "z_m": cols.z_m,
            "yaw_rad": cols.yaw_rad,
            "vx_mps": cols.vx_mps,
            "vy_mps": cols.vy_mps,
            "length_m": cols.length_m,
            "width_m": cols.width_m,
            "height_m": cols.height_m,
            "match_dt_ns": np.full(len(cols.ids), dt_ns, dtype=np.int64),
        }
        for name, value in values.items():
            columns.setdefault(name, []).append(value)
    merged = {name: np.concatenate(chunks) for name, chunks in columns.items()}
    if exclude_id is not None:
        keep = np.array([i != exclude_id for i in ids], dtype=bool)
        new_row = np.cumsum(keep) - 1
        first.rows = [(int(new_row[r]), b, t, o) for r, b, t, o in first.rows if keep[r]]
        ids = [i for i in ids if i != exclude_id]
        merged = {name: value[keep] for name, value in merged.items()}
    return ActorTable.from_columns(ids=ids, **merged), first
