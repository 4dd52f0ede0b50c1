"""``LogDrive``: the ``Drive`` over a ROS or MCAP message source."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any, Self

from loaders.drive import DriveInfo, TopicRoles
from loaders.message_logs.assemble import AssemblyOptions, FrameAssembler
from loaders.message_logs.ego_streams import EgoSettings, ego_decoders
from loaders.message_logs.registry import family_of
from loaders.message_logs.roles import assign_roles

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

    from loaders.maps.model import LaneMap
    from loaders.message_logs.source import MessageSource
    from loaders.records import Frame

__all__ = ["LogDrive"]


def _topics(roles: TopicRoles) -> set[str]:
    return {t for t in (roles.ego, *roles.objects, roles.plan) if t is not None}


class LogDrive:
    """A recorded drive read from a message source (see ``loaders.open.open_drive``)."""

    def __init__(
        self,
        source: MessageSource,
        roles: TopicRoles,
        options: AssemblyOptions,
        lane_map: tuple[str, LaneMap] | None,
        ego: EgoSettings | None = None,
    ) -> None:
        """Wire a source, its roles, the assembly options and the ego decoder settings."""
        self._source = source
        self._roles = roles
        self._options = options
        self._map = lane_map
        self._ego = ego or EgoSettings()
        self._types = {t.topic: t.msgtype for t in source.topics}
        self._decoders: dict[str, Callable[[Any], Any]] = {}
        for topic in (*roles.objects, roles.plan):
            if topic is not None and topic != roles.ego:  # an OSI ego topic decodes both
                family = family_of(self._types[topic])
                assert family is not None  # checked by detect_roles
                assert family.decode is not None  # object and plan families are stateless
                self._decoders[topic] = family.decode
        counts = {t.topic: t.count for t in source.topics}
        self._info = DriveInfo(
            path=source.path,
            source_format=source.source_format,
            start_ns=source.start_ns,
            end_ns=source.end_ns,
            topics=assign_roles(source.topics, roles),
            roles=roles,
            clock=options.clock,
            match_tolerance_ns=options.tolerance_ns,
            frame_count=counts[roles.ego],
            map_source=None if lane_map is None else lane_map[0],
            notes=dict(source.notes),
        )

    @property
    def info(self) -> DriveInfo:
        """What was detected about the drive."""
        return self._info

    @property
    def lane_map(self) -> LaneMap | None:
        """The lane map, if one was found."""
        return None if self._map is None else self._map[1]

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield frames within ``[start_ns, end_ns)`` (intersected with the open window).

        Frame indices count from 0 within the requested window.
        """
        opt = self._options
        if start_ns is not None:
            opt = replace(opt, start_ns=max(start_ns, opt.start_ns or start_ns))
        if end_ns is not None:
            opt = replace(opt, end_ns=min(end_ns, opt.end_ns or end_ns))
        lead = opt.tolerance_ns + 1_000_000_000  # objects and a plan before the first frame
        read_from = None if opt.start_ns is None else opt.start_ns - lead
        read_to = None if opt.end_ns is None else opt.end_ns + 1_000_000_000
        return self._run(self._roles, opt, read_from, read_to)

    def _run(
        self, roles: TopicRoles, opt: AssemblyOptions, read_from: int | None, read_to: int | None
    ) -> Iterator[Frame]:
        ego = ego_decoders(roles.ego, self._types[roles.ego], self._ego)
        others = {t: d for t, d in self._decoders.items() if t in _topics(roles)}
        decoders = {**ego, **others}
        assembler = FrameAssembler(self._source.path, roles, decoders, opt)
        try:
            yield from assembler.run(self._source.messages(tuple(decoders), read_from, read_to))
        finally:
            notes = self._info.notes
            for key, count in (
                ("skipped_invalid_ego", assembler.skipped_invalid),
                ("skipped_out_of_order_ego", assembler.skipped_out_of_order),
                ("unused_object_messages", assembler.unused_objects),
                ("unused_plan_messages", assembler.unused_plans),
                ("ego_messages_without_pose", assembler.ego_without_pose),
                ("ignored_markers", assembler.ignored_markers),
                ("first_detections_at_rest", assembler.first_detections_at_rest),
            ):
                if count:
                    notes[key] = str(count)
                else:
                    notes.pop(key, None)

    def count_frames(self) -> int:
        """Frames ``frames()`` yields over the open window, by a pass without the engines.

        Reads every role topic like ``frames()``, so ``info.notes`` then holds the same loss
        counts ``evaluate`` reports; raises the ``LoaderError`` that ends a damaged log
        (after counting the frames before it).
        """
        return sum(1 for _ in self.frames())

    def close(self) -> None:
        """Close the source."""
        self._source.close()

    def __enter__(self) -> Self:
        """Use as a context manager."""
        return self

    def __exit__(self, *exc: object) -> None:
        """Close on exit."""
        self.close()
