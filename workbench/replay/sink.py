"""A thin Rerun sink: sends what ``layout`` and ``properties`` decided, nothing more.

Entity paths (they mirror the scene; see ``docs/replay.md``)::

    world                      ViewCoordinates RIGHT_HAND_Z_UP, AnnotationContext (static)
    world/map/borders/<type>   LineStrips3D lane borders by line type (static)
    world/map/centre/<kind>    LineStrips3D centre lines by lane kind, dim (static)
    world/map/boundaries       LineStrips3D road/track boundaries (static)
    world/ego                  Boxes3D, one box per frame
    world/ego/trail            Points3D, one point per frame (the blueprint shows the recent ones)
    world/ego/view             Points3D, two invisible corners around the ego per frame: what
                               the live viewer's tracking camera frames (see ``blueprint``)
    world/ego/plan             LineStrips3D, the plan valid at the frame
    world/actors               Boxes3D with class ids, labelled with the drive's short label
                               (``#1``), the full id in the ``object_id`` component
    world/actors/velocity      Arrows3D, one second of travel, coloured by class
    plots/ego/speed_mps        Scalars
    plots/ego/accel_mps2       Scalars
    plots/actors/count         Scalars
    plots/actors/min_distance_m  Scalars (frames with at least one actor)

Every temporal entity gets one ``send_columns`` call per chunk on the timelines ``frame``
(sequence) and ``log_time`` (the drive's timestamps; the SDK's own wall-clock ``log_time`` is
switched off so the name means drive time).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import rerun as rr

from loaders.records import ObjectClass
from workbench.replay import style
from workbench.replay.short_labels import ShortLabels

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from numpy.typing import NDArray

    from workbench.replay.layout import ChunkLayout, MapLayout
    from workbench.replay.strips import StripColumns

__all__ = [
    "FRAME_TIMELINE",
    "OBJECT_ID",
    "TIME_TIMELINE",
    "RerunSink",
    "object_id_columns",
    "send_strips",
    "state_configuration",
    "time_index",
]

#: Component beside an engine's short object labels (``#1``) holding each instance's full id.
OBJECT_ID = "object_id"
FRAME_TIMELINE = "frame"
TIME_TIMELINE = "log_time"

_SERIES: dict[str, tuple[str, int]] = {
    "plots/ego/speed_mps": ("ego speed [m/s]", 0x00E676FF),
    "plots/ego/accel_mps2": ("ego acceleration [m/s²]", 0x29B6F6FF),
    "plots/actors/count": ("actors", 0xFFA726FF),
    "plots/actors/min_distance_m": ("nearest actor [m]", 0xEF5350FF),
}


def time_index(frame: NDArray[np.int64], t_ns: NDArray[np.int64]) -> list[rr.TimeColumn]:
    """The two index columns of every temporal entity: ``frame`` and ``log_time`` (drive time)."""
    return [
        rr.TimeColumn(FRAME_TIMELINE, sequence=frame),
        rr.TimeColumn(TIME_TIMELINE, timestamp=t_ns.astype("datetime64[ns]")),
    ]


def state_configuration(colors: Mapping[str, int]) -> rr.StateConfiguration:
    """The static configuration of a state lane: its values in order, packed RGBA each."""
    return rr.StateConfiguration(
        values=list(colors), colors=np.array(list(colors.values()), dtype=np.uint32)
    )


def object_id_columns(
    object_ids: Sequence[str], counts: NDArray[np.int64]
) -> rr.ComponentColumnList:
    """The full id of each labelled instance (:data:`OBJECT_ID`), partitioned like its batch.

    Args:
        object_ids: ``(I,)`` full object ids, one per instance of all frames.
        counts: ``(N,)`` instances per frame.
    """
    ids = np.array(object_ids, dtype=str)
    return rr.AnyValues.columns(object_id=ids).partition(counts)  # OBJECT_ID


def send_strips(
    recording: rr.RecordingStream,
    path: str,
    index: list[rr.TimeColumn],
    cols: StripColumns,
    radius_m: float,
) -> None:
    """Send per-frame outlines (``StripColumns``) as one columnar ``LineStrips3D`` call."""
    strips = cols.strips if cols.strips.shape[0] else np.zeros((0, 2, 3), dtype=np.float32)
    recording.send_columns(
        path,
        indexes=index,
        columns=rr.LineStrips3D.columns(
            strips=strips,
            colors=cols.colors,
            radii=np.full(len(strips), radius_m, dtype=np.float32),
        ).partition(cols.counts),
    )


def _u32(colors: list[int] | int, n: int = 1) -> NDArray[np.uint32]:
    """Packed RGBA as a ``uint32`` array (a bare list of three ints is ambiguous to Rerun)."""
    if isinstance(colors, int):
        return np.full(n, colors, dtype=np.uint32)
    return np.asarray(colors, dtype=np.uint32)


class RerunSink:
    """Sends a drive to one explicit ``rr.RecordingStream`` (never the global one)."""

    def __init__(self, recording: rr.RecordingStream, labels: ShortLabels | None = None) -> None:
        """Wrap ``recording`` and switch off its wall-clock ``log_time`` timeline.

        Args:
            recording: The stream to log to; its sinks (file, viewer, server) are set by the
                caller.
            labels: The drive's short labels the actors are labelled with (new actors are
                numbered as they first appear); a fresh table by default.
        """
        self.recording = recording
        self.labels = labels if labels is not None else ShortLabels()
        recording.set_log_time_enabled(False)
        self._plan_seen = False

    def send_static(
        self,
        *,
        name: str,
        start_ns: int,
        properties: Mapping[str, Mapping[str, str | int | float]],
        map_layout: MapLayout | None,
    ) -> None:
        """Send recording properties, coordinates, class annotations, series styles and the map.

        Args:
            name: Recording name shown in the viewer.
            start_ns: Drive start, used as the recording start time.
            properties: Property name to fields (see ``workbench.replay.properties``).
            map_layout: Static map geometry, if the drive has a map.
        """
        rec = self.recording
        rec.send_recording_name(name)
        rec.send_recording_start_time_nanos(start_ns)
        for prop, fields in properties.items():
            values = rr.AnyValues()
            for key, value in fields.items():
                values.with_component_from_data(key, value)
            rec.send_property(prop, values)
        rec.log("world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
        infos = [
            rr.AnnotationInfo(id=int(cls), label=cls.label, color=int(style.CLASS_COLORS[cls]))
            for cls in ObjectClass
        ]
        rec.log("world", rr.AnnotationContext(infos), static=True)
        for path, (label, color) in _SERIES.items():
            rec.log(path, rr.SeriesLines(names=[label], colors=_u32([color])), static=True)
        if map_layout is not None:
            self._send_map(map_layout)

    def _send_map(self, layout: MapLayout) -> None:
        rec = self.recording
        for line_type, strips in layout.borders.items():
            color = style.BORDER_COLORS.get(line_type, style.BORDER_COLORS["unknown"])
            rec.log(
                f"world/map/borders/{line_type}",
                rr.LineStrips3D(strips, radii=style.BORDER_RADIUS_M, colors=_u32(color)),
                static=True,
            )
        for kind, strips in layout.centres.items():
            rec.log(
                f"world/map/centre/{kind}",
                rr.LineStrips3D(
                    strips, radii=style.CENTRE_RADIUS_M, colors=_u32(style.CENTRE_COLOR)
                ),
                static=True,
            )
        if len(layout.boundaries):
            rec.log(
                "world/map/boundaries",
                rr.LineStrips3D(
                    layout.boundaries,
                    radii=style.BOUNDARY_RADIUS_M,
                    colors=_u32(style.BOUNDARY_COLOR),
                ),
                static=True,
            )

    def send_chunk(self, layout: ChunkLayout) -> None:
        """Send one chunk of frames: one columnar call per entity.

        Args:
            layout: The chunk's columns from ``layout_chunk``.
        """
        rec = self.recording
        n = len(layout)
        index = time_index(layout.frame, layout.t_ns)
        ego = layout.ego
        rec.send_columns(
            "world/ego",
            indexes=index,
            columns=rr.Boxes3D.columns(
                centers=ego.centre_m,
                half_sizes=ego.half_size_m,
                quaternions=ego.quaternion_xyzw,
                colors=_u32(style.EGO_COLOR, n),
                labels=np.full(n, "ego"),
            ),
        )
        corners = np.repeat(ego.centre_m, 2, axis=0)
        corners[0::2, :2] -= style.VIEW_HALF_SIZE_M
        corners[1::2, :2] += style.VIEW_HALF_SIZE_M
        rec.send_columns(
            "world/ego/view",
            indexes=index,
            columns=rr.Points3D.columns(
                positions=corners,
                radii=np.full(2 * n, 0.01, dtype=np.float32),
                colors=_u32(0x00000000, 2 * n),
            ).partition(np.full(n, 2, dtype=np.int64)),
        )
        trail = ego.centre_m.copy()
        trail[:, 2] = style.EGO_TRAIL_RADIUS_M
        rec.send_columns(
            "world/ego/trail",
            indexes=index,
            columns=rr.Points3D.columns(
                positions=trail,
                radii=np.full(n, style.EGO_TRAIL_RADIUS_M, dtype=np.float32),
                colors=_u32(style.EGO_COLOR, n),
            ),
        )
        self._send_actors(index, layout)
        self._send_plan(index, layout)
        self._send_scalars(index, layout)

    def _send_actors(self, index: list[rr.TimeColumn], layout: ChunkLayout) -> None:
        actors = layout.actors
        self.recording.send_columns(
            "world/actors",
            indexes=index,
            columns=[
                *rr.Boxes3D.columns(
                    centers=actors.centre_m,
                    half_sizes=actors.half_size_m,
                    quaternions=actors.quaternion_xyzw,
                    class_ids=actors.class_ids,
                    labels=[self.labels.label(i) for i in actors.labels.tolist()],
                ).partition(actors.counts),
                *object_id_columns(actors.labels.tolist(), actors.counts),
            ],
        )
        self.recording.send_columns(
            "world/actors/velocity",
            indexes=index,
            columns=rr.Arrows3D.columns(
                origins=actors.centre_m,
                vectors=actors.velocity_mps,
                class_ids=actors.class_ids,
            ).partition(actors.counts),
        )

    def _send_plan(self, index: list[rr.TimeColumn], layout: ChunkLayout) -> None:
        plan = layout.plan
        if not self._plan_seen and not plan.counts.any():
            return
        self._plan_seen = True
        self.recording.send_columns(
            "world/ego/plan",
            indexes=index,
            columns=rr.LineStrips3D.columns(
                strips=plan.strips_m,
                radii=np.full(len(plan.strips_m), style.PLAN_RADIUS_M, dtype=np.float32),
                colors=_u32(style.PLAN_COLOR, len(plan.strips_m)),
            ).partition(plan.counts),
        )

    def _send_scalars(self, index: list[rr.TimeColumn], layout: ChunkLayout) -> None:
        rec = self.recording
        series = {
            "plots/ego/speed_mps": layout.ego.speed_mps,
            "plots/ego/accel_mps2": layout.ego.accel_mps2,
            "plots/actors/count": layout.actors.counts.astype(np.float64),
        }
        for path, values in series.items():
            rec.send_columns(path, indexes=index, columns=rr.Scalars.columns(scalars=values))
        dist = layout.actors.min_distance_m
        keep = np.isfinite(dist)
        if keep.any():
            rec.send_columns(
                "plots/actors/min_distance_m",
                indexes=time_index(layout.frame[keep], layout.t_ns[keep]),
                columns=rr.Scalars.columns(scalars=dist[keep]),
            )

    def flush(self) -> None:
        """Block until everything sent so far has reached the sinks."""
        self.recording.flush()
