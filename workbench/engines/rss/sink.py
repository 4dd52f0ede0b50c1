"""Sends structured RSS results (``rss_layout``) to Rerun; thin, like ``sink``.

Entity paths::

    world/rss/constellations          LineStrips3D ego -> object, coloured by type, red when
                                      dangerous, labelled with the object's short label
                                      (``#1``) and distances vs safe distances; the full
                                      id per line in its ``object_id`` component
    world/rss/road_areas              LineStrips3D, road-area outline per constellation
    world/rss/dangerous               Boxes3D, red boxes around dangerous objects
    rss/structured/state              StateChange safe / dangerous / no constellation
    rss/structured/objects/<id>       StateChange per object (dangerous, lon unsafe, ...)
    rss/structured/response/<lane>    StateChange proper response (longitudinal,
                                      lateral_left, lateral_right)
    plots/rss/acceleration/<bound>    Scalars, acceleration restrictions [m/s²]
    plots/rss/distances/<id>/<kind>   Scalars, lon/lat distance and safe distance [m]
    rss/structured/duty/<id>          StateChange who must act (``duties``)
    plots/rss/compliance/<id>/<party>_allowed|_measured
                                      Scalars, longitudinal acceleration the proper response
                                      allows vs the measured one [m/s²] (``duties``)

Per-object lanes carry only changes; an object that leaves every constellation gets one
"not relevant" entry ("no duty" on its duty lane), also across chunk boundaries. Per-object
entities keep the full id in their path; the plots' series are named by the short label.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import rerun as rr

from workbench.engines.rss.duties import DUTY_STATES, NO_DUTY, layout_duties
from workbench.engines.rss.layout import FRAME_STATES, OBJECT_STATES, RESPONSE_LANES, layout_rss
from workbench.replay.short_labels import ShortLabels
from workbench.replay.sink import object_id_columns, send_strips, state_configuration, time_index
from workbench.replay.strips import StripColumns

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from workbench.engines.rss.duties import DutyColumns
    from workbench.engines.rss.layout import RssColumns
    from workbench.engines.rss.verdict import RssVerdict
    from workbench.replay.layout import ChunkLayout

__all__ = ["RssSink", "object_path"]

STATE_PATH = "rss/structured/state"
_AREA_RADIUS_M = 0.06
_NOT_RELEVANT = "not relevant"
_RESPONSE_COLORS = {"None": 0x4CAF50FF, "BrakeMinCorrect": 0xFFA726FF, "BrakeMin": 0xEF5350FF}


def object_path(object_id: str) -> str:
    """Entity path of an object's state lane (the id escaped as one path part)."""
    return f"rss/structured/objects/{rr.escape_entity_path_part(object_id)}"


def duty_path(object_id: str) -> str:
    """Entity path of an object's duty lane (who must act)."""
    return f"rss/structured/duty/{rr.escape_entity_path_part(object_id)}"


class _Lanes:
    """Per-object state lanes that carry only changes, with an idle value on leaving."""

    def __init__(self, path: Callable[[str], str], states: dict[str, int], idle: str) -> None:
        self.path, self.idle = path, idle
        self.config = state_configuration(states)
        self.last: dict[str, str] = {}


class RssSink:
    """Sends structured RSS columns on the ``frame`` and ``log_time`` timelines."""

    def __init__(self, recording: rr.RecordingStream, labels: ShortLabels | None = None) -> None:
        """Remember the stream and send the static state configurations.

        Args:
            recording: The stream.
            labels: The drive's short labels (``#1``) every object label uses; a fresh
                table by default.
        """
        self.recording = recording
        self.labels = labels if labels is not None else ShortLabels()
        self._named: set[str] = set()
        recording.log(STATE_PATH, state_configuration(FRAME_STATES), static=True)
        for lane, values in RESPONSE_LANES.values():
            colors = {v: _RESPONSE_COLORS[v] for v in values}
            path = f"rss/structured/response/{lane}"
            recording.log(path, state_configuration(colors), static=True)
        self._objects = _Lanes(object_path, OBJECT_STATES, _NOT_RELEVANT)
        self._duties = _Lanes(duty_path, DUTY_STATES, NO_DUTY)
        self._profile_sent = False

    def _states(
        self, path: str, frame: NDArray[np.int64], t_ns: NDArray[np.int64], states: list[str]
    ) -> None:
        self.recording.send_columns(
            path,
            indexes=time_index(frame, t_ns),
            columns=rr.StateChange.columns(state=np.array(states, dtype=str)),
        )

    def _object_lanes(
        self,
        frame: NDArray[np.int64],
        t_ns: NDArray[np.int64],
        lanes: dict[str, list[str]],
        kind: _Lanes,
    ) -> None:
        last, idle = kind.last, kind.idle
        for object_id in sorted(set(last) - set(lanes)):
            if last[object_id] != idle:
                self._states(kind.path(object_id), frame[:1], t_ns[:1], [idle])
                last[object_id] = idle
        for object_id, states in sorted(lanes.items()):
            if object_id not in last:
                self.recording.log(kind.path(object_id), kind.config, static=True)
            prev = [last.get(object_id, idle), *states[:-1]]
            change = np.flatnonzero([s != p for s, p in zip(states, prev, strict=True)])
            if len(change):
                picked = [states[k] for k in change]
                self._states(kind.path(object_id), frame[change], t_ns[change], picked)
            last[object_id] = states[-1]

    def _series(
        self,
        prefix: str,
        frame: NDArray[np.int64],
        t_ns: NDArray[np.int64],
        series: dict[str, tuple[NDArray[np.int64], NDArray[np.float64]]],
    ) -> None:
        """Scalars per ``"<object id>/<name>"`` at their chunk rows."""
        for key, (rows, values) in series.items():
            object_id, kind = key.rsplit("/", 1)
            path = f"{prefix}/{rr.escape_entity_path_part(object_id)}/{kind}"
            if path not in self._named:
                name = f"{self.labels.label(object_id)} {kind}"
                self.recording.log(path, rr.SeriesLines(names=[name]), static=True)
                self._named.add(path)
            self.recording.send_columns(
                path,
                indexes=time_index(frame[rows], t_ns[rows]),
                columns=rr.Scalars.columns(scalars=values),
            )

    def send_columns(
        self, frame: NDArray[np.int64], t_ns: NDArray[np.int64], cols: RssColumns
    ) -> None:
        """Send one chunk of structured RSS results."""
        rec = self.recording
        index = time_index(frame, t_ns)
        rec.send_columns(
            "world/rss/constellations",
            indexes=index,
            columns=[
                *rr.LineStrips3D.columns(
                    strips=cols.link_strips_m,
                    colors=cols.link_colors,
                    radii=cols.link_radii_m,
                    labels=cols.link_labels,
                ).partition(cols.link_counts),
                *object_id_columns(cols.link_object_ids, cols.link_counts),
            ],
        )
        areas = StripColumns(cols.area_strips_m, cols.area_counts, cols.area_colors)
        send_strips(rec, "world/rss/road_areas", index, areas, _AREA_RADIUS_M)
        n_boxes = len(cols.danger_centre_m)
        rec.send_columns(
            "world/rss/dangerous",
            indexes=index,
            columns=rr.Boxes3D.columns(
                centers=cols.danger_centre_m,
                half_sizes=cols.danger_half_m,
                quaternions=cols.danger_quat_xyzw,
                colors=np.full(n_boxes, FRAME_STATES["dangerous"], dtype=np.uint32),
            ).partition(cols.danger_counts),
        )
        self._states(STATE_PATH, frame, t_ns, cols.frame_state)
        for lane, names in cols.responses.items():
            self._states(f"rss/structured/response/{lane}", frame, t_ns, names)
        self._object_lanes(frame, t_ns, cols.object_states, self._objects)
        for name, values in cols.accel.items():
            keep = np.isfinite(values)
            if keep.any():
                rec.send_columns(
                    f"plots/rss/acceleration/{name}",
                    indexes=time_index(frame[keep], t_ns[keep]),
                    columns=rr.Scalars.columns(scalars=values[keep]),
                )
        self._series("plots/rss/distances", frame, t_ns, cols.distances)

    def send_duties(
        self, frame: NDArray[np.int64], t_ns: NDArray[np.int64], cols: DutyColumns
    ) -> None:
        """Send one chunk's duty lanes and compliance series."""
        self._object_lanes(frame, t_ns, cols.duty_states, self._duties)
        self._series("plots/rss/compliance", frame, t_ns, cols.compliance)

    def send_chunk(
        self, frames: Sequence[Frame], layout: ChunkLayout, verdicts: Sequence[RssVerdict]
    ) -> None:
        """Lay out and send the verdicts of a chunk of frames.

        The first chunk also sends the recording property ``rss`` (``profile``: the RSS
        parameter profile of the run).
        """
        if verdicts and not self._profile_sent:
            values = rr.AnyValues()
            values.with_component_from_data("profile", verdicts[0].profile)
            self.recording.send_property("rss", values)
            self._profile_sent = True
        self.send_columns(layout.frame, layout.t_ns, layout_rss(frames, verdicts, self.labels))
        self.send_duties(layout.frame, layout.t_ns, layout_duties(verdicts))
