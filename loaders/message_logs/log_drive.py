"""``LogDrive``: the ``Drive`` over a ROS or MCAP message source."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any, Self

from loaders.drive import DriveInfo
from loaders.message_logs.assemble import AssemblyOptions, FrameAssembler
from loaders.message_logs.ego_streams import EgoSettings, ego_decoders
from loaders.message_logs.registry import family_of
from loaders.message_logs.roles import assign_roles

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

    from loaders.drive import TopicRoles
    from loaders.maps.model import LaneMap
    from loaders.message_logs.source import MessageSource
    from loaders.records import Frame

__all__ = ["LogDrive"]


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
            if topic is not None:
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
            notes={},
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
        ego = ego_decoders(self._roles.ego, self._types[self._roles.ego], self._ego)
        decoders = {**ego, **self._decoders}
        assembler = FrameAssembler(self._source.path, self._roles, decoders, opt)
        try:
            yield from assembler.run(self._source.messages(tuple(decoders), read_from, read_to))
        finally:
            if assembler.skipped_invalid:
                self._info.notes["skipped_invalid_ego"] = str(assembler.skipped_invalid)
            if assembler.skipped_out_of_order:
                self._info.notes["skipped_out_of_order_ego"] = str(assembler.skipped_out_of_order)

    def close(self) -> None:
        """Close the source."""
        self._source.close()

    def __enter__(self) -> Self:
        """Use as a context manager."""
        return self

    def __exit__(self, *exc: object) -> None:
        """Close on exit."""
        self.close()
