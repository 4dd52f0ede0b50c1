"""Frames on the ego clock from one time-ordered pass over the role topics.

Memory holds the last message per object topic, the last plan, a three-sample ego window
and at most ``MAX_HELD`` frames, whatever the log size. A frame is completed when the next
ego message arrives (or at the end), so finite differences can be central (see
``kinematics``), and held until its object picks are settled (``matching``: a message
stamped at or before the frame may come later in the file) and its first detections have
their forward velocity. Samples without orientation (``heading_from_track``, GNSS without
IMU) take the direction of travel through their neighbours (``prev -> nxt``); below 1 cm
of travel the previous heading is kept.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from loaders.errors import CorruptLogError, InvalidValueError
from loaders.message_logs.kinematics import ego_kinematics
from loaders.message_logs.matching import (
    FirstDetections,
    ObjectBuffer,
    Pick,
    match_objects,
    pick_messages,
)
from loaders.message_logs.samples import EgoSample, EgoWithObjects, ObjectColumns, PlanSample
from loaders.records import ActorTable, EgoState, Frame

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Iterator
    from pathlib import Path

    from loaders.drive import TopicRoles
    from loaders.records import Plan

__all__ = ["MAX_HELD", "AssemblyOptions", "FrameAssembler"]

#: Frames held at most while first detections wait for their topic's next message.
MAX_HELD = 64


@dataclass(frozen=True, slots=True)
class AssemblyOptions:
    """How frames are built.

    Attributes:
        clock: ``log_time`` or ``header``.
        tolerance_ns: Maximum age of a matched object message.
        invalid_ego: ``raise`` or ``skip`` on a non-finite ego pose.
        exclude_id: Object id dropped from the actor tables (the ego itself).
        start_ns: First frame time (inclusive), if bounded.
        end_ns: Frame time bound (exclusive), if bounded.
    """

    clock: str = "log_time"
    tolerance_ns: int = 150_000_000
    invalid_ego: str = "raise"
    exclude_id: str | None = None
    start_ns: int | None = None
    end_ns: int | None = None


@dataclass(frozen=True, slots=True)
class _Pending:
    t_ns: int
    sample: EgoSample
    picks: list[Pick]
    plan: Plan | None


@dataclass(slots=True)
class _Held:
    """A completed frame waiting for its object picks and first detections to settle."""

    frame: Frame  # its actors are set once the picks are settled
    picks: list[Pick]
    first: FirstDetections | None = None


class FrameAssembler:
    """Turns ``(topic, log_time_ns, decoded message)`` tuples into frames."""

    def __init__(
        self,
        path: Path,
        roles: TopicRoles,
        decoders: dict[str, Callable[[Any], Any]],
        options: AssemblyOptions,
    ) -> None:
        """Prepare buffers for ``roles``; ``decoders`` maps topic → message decoder.

        A decoder may return None: the message only updated its state (``/tf`` moving other
        frames, an IMU message).
        """
        self._path = path
        self._roles = roles
        self._decoders = decoders
        self._opt = options
        self._buffers = [ObjectBuffer(t) for t in roles.objects]
        self._by_topic = {b.topic: k for k, b in enumerate(self._buffers)}
        self._plan: tuple[int, Plan] | None = None
        self._plan_used = False
        self._plans_unused = 0
        self._prev: _Pending | None = None
        self._cur: _Pending | None = None
        self._index = 0
        self._held: deque[_Held] = deque()
        self._last_yaw = 0.0
        self.skipped_invalid = 0
        self.skipped_out_of_order = 0
        #: Ego-topic messages that made no ego sample (``/tf`` moving other frames only, or
        #: without a chain to the map; GNSS without a fix).
        self.ego_without_pose = 0
        #: Entries of object messages that are not objects (``MarkerArray`` non-box markers).
        self.ignored_markers = 0
        #: Frame rows of first detections (types without velocity) whose velocity stayed 0:
        #: the object's next message came after the frame was emitted, or never.
        self.first_detections_at_rest = 0

    @property
    def unused_objects(self) -> int:
        """Object messages no frame took (replaced before the next ego message, or too old)."""
        return sum(b.unused_total for b in self._buffers)

    @property
    def unused_plans(self) -> int:
        """Plan messages no frame took (replaced before the next ego message, or last)."""
        return self._plans_unused + int(self._plan is not None and not self._plan_used)

    def _time(self, log_ns: int, stamp_ns: int | None) -> int:
        return stamp_ns if self._opt.clock == "header" and stamp_ns is not None else log_ns

    def _in_window(self, t_ns: int) -> bool:
        start, end = self._opt.start_ns, self._opt.end_ns
        return (start is None or t_ns >= start) and (end is None or t_ns < end)

    def _track(self, pending: _Pending, a: _Pending | None, b: _Pending | None) -> _Pending:
        """``pending`` with the heading of the track from ``a`` to ``b`` (GNSS without IMU)."""
        if not pending.sample.heading_from_track:
            return pending
        a, b = a or pending, b or pending
        dx, dy = b.sample.x_m - a.sample.x_m, b.sample.y_m - a.sample.y_m
        yaw = math.atan2(dy, dx) if math.hypot(dx, dy) >= 0.01 else self._last_yaw  # noqa: PLR2004 - 1 cm
        return replace(pending, sample=replace(pending.sample, yaw_rad=yaw))

    def _emit(self, nxt: _Pending | None) -> None:
        """Complete the current frame (its kinematics need ``nxt``) and hold it."""
        cur = self._cur
        if cur is None:
            self._cur = nxt
            return
        prev = self._prev
        cur = self._track(cur, prev, nxt)
        self._last_yaw = cur.sample.yaw_rad
        ahead = None if nxt is None else self._track(nxt, cur, None)
        speed, accel, yaw_rate = ego_kinematics(
            (prev.t_ns, prev.sample) if prev else None,
            (cur.t_ns, cur.sample),
            (ahead.t_ns, ahead.sample) if ahead else None,
        )
        s = cur.sample
        ego = EgoState(s.x_m, s.y_m, s.z_m, s.yaw_rad, speed, accel, yaw_rate, *(s.size_m or ()))
        self._prev, self._cur = cur, nxt
        if not self._in_window(cur.t_ns):
            for pick in cur.picks:
                pick.keep()
            return
        frame = Frame(self._index, cur.t_ns, ego, ActorTable.empty(), cur.plan)
        self._held.append(_Held(frame, cur.picks))
        self._index += 1

    def _release(self, *, final: bool) -> Iterator[Frame]:
        """Yield the held frames whose objects are settled, in order.

        A frame waits until each object topic has given it its closest message (see
        ``matching``), then until every object topic with a first detection in it has a
        newer message (the forward difference is then known, or the object is gone); at
        most ``MAX_HELD`` frames wait, ``final`` releases all.
        """
        held = self._held
        while held:
            entry = held[0]
            force = final or len(held) > MAX_HELD
            t_ns = entry.frame.t_ns
            if entry.first is None:
                if not force and not all(p.settled(t_ns) for p in entry.picks):
                    return
                actors, entry.first = match_objects(entry.picks, t_ns, self._opt.exclude_id)
                entry.frame = replace(entry.frame, actors=actors)
            if not force and not entry.first.settled():
                return
            held.popleft()
            actors, left = entry.first.fill(entry.frame.actors)
            self.first_detections_at_rest += left
            for buf in self._buffers:
                buf.prune(t_ns - self._opt.tolerance_ns)
            yield (
                replace(entry.frame, actors=actors)
                if actors is not entry.frame.actors
                else entry.frame
            )

    def _on_ego(self, topic: str, log_ns: int, sample: EgoSample) -> None:
        t_ns = self._time(log_ns, sample.stamp_ns)
        if self._cur is not None and t_ns <= self._cur.t_ns:
            self.skipped_out_of_order += 1
            return
        pose = (sample.x_m, sample.y_m, 0.0 if sample.heading_from_track else sample.yaw_rad)
        if not all(math.isfinite(v) for v in pose):
            if self._opt.invalid_ego == "skip":
                self.skipped_invalid += 1
                return
            raise InvalidValueError(
                self._path, "non-finite ego pose (x, y, yaw)", topic=topic, t_ns=t_ns, value=pose
            )
        picks = pick_messages(self._buffers, t_ns, self._opt.tolerance_ns)
        plan = self._plan[1] if self._plan is not None and self._plan[0] <= t_ns else None
        self._plan_used = self._plan_used or plan is not None
        self._emit(_Pending(t_ns, sample, picks, plan))

    def _decode(self, topic: str, log_ns: int, msg: Any) -> Any:
        try:
            return self._decoders[topic](msg)
        except (AttributeError, KeyError, TypeError, ValueError) as err:
            raise CorruptLogError(
                self._path, f"cannot decode message: {err!r}", topic=topic, t_ns=log_ns
            ) from err

    def _on_objects(self, topic: str, t_ns: int, objects: ObjectColumns) -> None:
        """Buffer an object message and offer it to the frames still open for it."""
        k = self._by_topic[topic]
        tolerance_ns = self._opt.tolerance_ns
        self._buffers[k].update(t_ns, objects)
        if self._cur is not None:  # the frame whose next ego message has not come yet
            self._cur.picks[k].offer(self._cur.t_ns, tolerance_ns)
        for entry in self._held:
            if entry.first is None:
                entry.picks[k].offer(entry.frame.t_ns, tolerance_ns)

    def _on_message(self, topic: str, log_ns: int, decoded: Any) -> None:
        """File one decoded message (completing the frame before it, for an ego message)."""
        if isinstance(decoded, EgoWithObjects):  # OSI: the objects first, then the ego
            if topic in self._by_topic:
                self._on_objects(topic, self._time(log_ns, decoded.ego.stamp_ns), decoded.objects)
            decoded = decoded.ego
        if isinstance(decoded, EgoSample):
            self._on_ego(topic, log_ns, decoded)
        elif isinstance(decoded, ObjectColumns):
            self.ignored_markers += decoded.ignored
            self._on_objects(topic, self._time(log_ns, decoded.stamp_ns), decoded)
        elif isinstance(decoded, PlanSample):
            self._plans_unused += int(self._plan is not None and not self._plan_used)
            self._plan = (self._time(log_ns, decoded.stamp_ns), decoded.plan)
            self._plan_used = False

    def run(self, messages: Iterable[tuple[str, int, Any]]) -> Iterator[Frame]:
        """Yield frames from the message stream.

        A ``CorruptLogError`` or ``InvalidValueError`` is re-raised after the frame still
        pending was yielded.
        """
        try:
            for topic, log_ns, msg in messages:
                decoded = self._decode(topic, log_ns, msg)
                if decoded is None:  # the message only updated decoder state (TF, IMU)
                    self.ego_without_pose += int(topic == self._roles.ego)
                    continue
                self._on_message(topic, log_ns, decoded)
                yield from self._release(final=False)
        except (CorruptLogError, InvalidValueError):
            self._emit(None)
            yield from self._release(final=True)
            raise
        self._emit(None)
        yield from self._release(final=True)
