"""Structured RSS results of a chunk of frames as columnar arrays (pure: no Rerun import).

Per frame the viewer shows one line from the ego to every object it forms a constellation
with, coloured by constellation type (red and thicker when dangerous) and labelled with the
longitudinal / lateral distance against the safe distance of the object's most critical
constellation (and how many more it has); the road area of that constellation as an
outline; a red box around every dangerous object; the frame's proper
response and acceleration restrictions; and one state lane per object::

    state per object = worst over its constellations of
        dangerous  >  lon unsafe  >  lat unsafe  >  safe        ("not relevant" without one)

Distances are those of the object's most critical constellation (dangerous first, then the
smallest longitudinal margin ``current - safe``). Intersection constellations are judged on
the distances of both vehicles to enter the intersection (ad-rss' intersection check), so
those are shown for them instead of lon/lat distances.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.physics import DISTANCE_MAX_M
from workbench.engines.rss.responses import accel_bound, response_name
from workbench.replay.layout import pad_polylines, yaw_to_quaternion
from workbench.replay.short_labels import ShortLabels

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from workbench.engines.rss.verdict import RssVerdict

__all__ = [
    "ACCEL_SERIES",
    "FRAME_STATES",
    "OBJECT_STATES",
    "RESPONSE_LANES",
    "TYPE_COLORS",
    "RssColumns",
    "layout_rss",
]

#: Frame state lane values and colours.
FRAME_STATES = {"safe": 0x4CAF50FF, "dangerous": 0xEF5350FF, "no constellation": 0x757575FF}
#: Per-object state lane values and colours, most severe first.
OBJECT_STATES = {
    "dangerous": 0xEF5350FF,
    "lon unsafe": 0xFFA726FF,
    "lat unsafe": 0xFFEE58FF,
    "safe": 0x4CAF50FF,
    "not relevant": 0x616161FF,
}
#: Line colour per constellation type (dangerous lines are red whatever their type).
TYPE_COLORS = {
    ConstellationType.NotRelevant: 0x9E9E9EC0,
    ConstellationType.SameDirection: 0x42A5F5E0,
    ConstellationType.OppositeDirection: 0xFFA726E0,
    ConstellationType.IntersectionEgoHasPriority: 0xAB47BCE0,
    ConstellationType.IntersectionObjectHasPriority: 0xAB47BCE0,
    ConstellationType.IntersectionSamePriority: 0xAB47BCE0,
    ConstellationType.Unstructured: 0x26A69AE0,
}
DANGEROUS_COLOR = 0xEF5350FF
#: Road-area outline colour (dangerous constellations use ``DANGEROUS_COLOR``).
ROAD_AREA_COLOR = 0x80DEEA70
#: Response state lanes: record key -> (lane name, values in severity order).
RESPONSE_LANES = {
    "longitudinal_response": ("longitudinal", ("None", "BrakeMinCorrect", "BrakeMin")),
    "lateral_response_left": ("lateral_left", ("None", "BrakeMin")),
    "lateral_response_right": ("lateral_right", ("None", "BrakeMin")),
}
#: Acceleration-restriction series: name -> (record key, 0 = lower / 1 = upper bound).
ACCEL_SERIES = {
    "lon_min_mps2": ("longitudinal", 0),
    "lon_max_mps2": ("longitudinal", 1),
    "lat_left_min_mps2": ("lateral_left", 0),
    "lat_left_max_mps2": ("lateral_left", 1),
    "lat_right_min_mps2": ("lateral_right", 0),
    "lat_right_max_mps2": ("lateral_right", 1),
}
#: Constellation lines and danger boxes float above the road and the boxes' base.
Z_LINK_M = 1.0
Z_AREA_M = 0.08
#: Danger boxes are this much larger than the object, per side.
DANGER_MARGIN_M = 0.35
_INTERSECTION = {
    ConstellationType.IntersectionEgoHasPriority,
    ConstellationType.IntersectionObjectHasPriority,
    ConstellationType.IntersectionSamePriority,
}
_SEVERITY = {name: k for k, name in enumerate(OBJECT_STATES)}
_TYPE_SHORT = {
    ConstellationType.NotRelevant: "not relevant",
    ConstellationType.SameDirection: "same dir",
    ConstellationType.OppositeDirection: "opposite",
    ConstellationType.IntersectionEgoHasPriority: "intersection, ego prio",
    ConstellationType.IntersectionObjectHasPriority: "intersection, object prio",
    ConstellationType.IntersectionSamePriority: "intersection, same prio",
    ConstellationType.Unstructured: "unstructured",
}


@dataclass(frozen=True, slots=True)
class RssColumns:
    """Everything the sink sends for the structured RSS engine, for ``N`` frames.

    Attributes:
        frame_state: ``(N,)`` values of :data:`FRAME_STATES`.
        link_strips_m: ``(L, 2, 3)`` ego-to-object lines of all frames.
        link_counts: ``(N,)`` lines per frame.
        link_colors: ``(L,)`` packed RGBA.
        link_radii_m: ``(L,)``.
        link_labels: ``(L,)`` "<short label>: <type> lon d/safe m, lat d/safe m" (``#1``:
            the drive's short label of the object).
        link_object_ids: ``(L,)`` the full object id of each line.
        area_strips_m: ``(A, V, 3)`` road-area outlines; ``area_counts`` ``(N,)``;
            ``area_colors`` ``(A,)``.
        danger_centre_m: ``(D, 3)`` boxes around dangerous objects; ``danger_half_m``
            ``(D, 3)``, ``danger_quat_xyzw`` ``(D, 4)``, ``danger_counts`` ``(N,)``.
        object_states: Per object id, ``(N,)`` values of :data:`OBJECT_STATES`.
        distances: Per ``"<id>/<series>"`` (``lon_m``, ``lon_safe_m``, ``lat_m``,
            ``lat_safe_m``; for intersection constellations ``ego_to_enter_m`` and
            ``other_to_enter_m``), ``(rows, values)``: chunk rows where the object has a finite
            value, and the values.
        responses: Per :data:`RESPONSE_LANES` lane name, ``(N,)`` response names.
        accel: Per :data:`ACCEL_SERIES` name, ``(N,)`` bounds [m/s²], NaN = none.
    """

    frame_state: list[str]
    link_strips_m: NDArray[np.float32]
    link_counts: NDArray[np.int64]
    link_colors: NDArray[np.uint32]
    link_radii_m: NDArray[np.float32]
    link_labels: list[str]
    link_object_ids: list[str]
    area_strips_m: NDArray[np.float32]
    area_counts: NDArray[np.int64]
    area_colors: NDArray[np.uint32]
    danger_centre_m: NDArray[np.float32]
    danger_half_m: NDArray[np.float32]
    danger_quat_xyzw: NDArray[np.float32]
    danger_counts: NDArray[np.int64]
    object_states: dict[str, list[str]]
    distances: dict[str, tuple[NDArray[np.int64], NDArray[np.float64]]]
    responses: dict[str, list[str]]
    accel: dict[str, NDArray[np.float64]]


@dataclass(frozen=True, slots=True)
class _Row:
    """One constellation, reduced to what is drawn."""

    index: int
    label: str
    ctype: ConstellationType
    state: str
    lon_m: float
    lon_safe_m: float
    lat_m: float
    lat_safe_m: float
    ego_to_enter_m: float = float("nan")
    other_to_enter_m: float = float("nan")

    @property
    def is_intersection(self) -> bool:
        """Intersection constellations are judged by the distances to enter, not lon/lat."""
        return self.ctype in _INTERSECTION

    def series(self) -> dict[str, float]:
        """The plotted distances of this row [m]."""
        if self.is_intersection:
            return {
                "ego_to_enter_m": self.ego_to_enter_m,
                "other_to_enter_m": self.other_to_enter_m,
            }
        return {
            "lon_m": self.lon_m,
            "lon_safe_m": self.lon_safe_m,
            "lat_m": self.lat_m,
            "lat_safe_m": self.lat_safe_m,
        }

    @property
    def margin_m(self) -> float:
        """Longitudinal margin, ``-inf`` first for dangerous rows (most critical first)."""
        if self.state == "dangerous":
            return -np.inf
        return self.lon_m - self.lon_safe_m if np.isfinite(self.lon_m) else np.inf

    def text(self, short: str) -> str:
        """The line label, naming the object by its ``short`` label."""
        if self.is_intersection:
            return (
                f"{short}: {_TYPE_SHORT[self.ctype]}  to enter: "
                f"ego {_fmt(self.ego_to_enter_m)} m, object {_fmt(self.other_to_enter_m)} m"
            )
        return (
            f"{short}: {_TYPE_SHORT[self.ctype]}  "
            f"lon {_fmt(self.lon_m)}/{_fmt(self.lon_safe_m)} m  "
            f"lat {_fmt(self.lat_m)}/{_fmt(self.lat_safe_m)} m"
        )


def _fmt(value: float) -> str:
    return f"{value:.1f}" if np.isfinite(value) else "-"


def _finite(value: float) -> float:
    return value if abs(value) < DISTANCE_MAX_M / 2 else float("nan")


def _rows(detail: RssVerdict) -> list[_Row]:
    res = detail.result
    if res is None or detail.constellation_type is None:
        return []
    st = res.states
    rows = []
    for c, label in enumerate(detail.labels):
        left_cur = float(st.left.current_distance_m[c])
        right_cur = float(st.right.current_distance_m[c])
        side = st.left if left_cur <= right_cur else st.right
        lon_safe = bool(st.lon_is_safe[c])
        lat_safe = bool(st.left.is_safe[c] and st.right.is_safe[c])
        if bool(res.dangerous[c]):
            state = "dangerous"
        elif not lon_safe:
            state = "lon unsafe"
        elif not lat_safe:
            state = "lat unsafe"
        else:
            state = "safe"
        rows.append(
            _Row(
                index=c,
                label=label,
                ctype=ConstellationType(int(detail.constellation_type[c])),
                state=state,
                lon_m=_finite(float(st.lon_current_distance_m[c])),
                lon_safe_m=_finite(float(st.lon_safe_distance_m[c])),
                lat_m=_finite(float(side.current_distance_m[c])),
                lat_safe_m=_finite(float(side.safe_distance_m[c])),
                ego_to_enter_m=_finite(float(res.relative.ego_dist_to_enter_m[c])),
                other_to_enter_m=_finite(float(res.relative.other_dist_to_enter_m[c])),
            )
        )
    return rows


def _most_critical(rows: list[_Row]) -> dict[str, _Row]:
    """Per object, its most severe row (then the smallest longitudinal margin)."""
    best: dict[str, _Row] = {}
    for row in rows:
        seen = best.get(row.label)
        key = (_SEVERITY[row.state], row.margin_m)
        if seen is None or key < (_SEVERITY[seen.state], seen.margin_m):
            best[row.label] = row
    return best


@dataclass
class _Builder:
    """Accumulates the columns frame by frame."""

    n: int
    short: ShortLabels
    links: list[NDArray[np.float64]] = field(default_factory=list)
    link_colors: list[int] = field(default_factory=list)
    link_radii: list[float] = field(default_factory=list)
    link_labels: list[str] = field(default_factory=list)
    link_ids: list[str] = field(default_factory=list)
    areas: list[NDArray[np.float64]] = field(default_factory=list)
    area_colors: list[int] = field(default_factory=list)
    danger: list[tuple[float, ...]] = field(default_factory=list)
    states: dict[str, list[str]] = field(default_factory=dict)
    dist: dict[str, tuple[list[int], list[float]]] = field(default_factory=dict)

    def add_frame(self, i: int, frame: Frame, detail: RssVerdict) -> tuple[int, int, int]:
        """Add frame ``i``'s constellations; returns its numbers of lines, areas, boxes."""
        rows = _rows(detail)
        actors = frame.actors
        where = {str(a): k for k, a in enumerate(actors.ids)}
        ego = np.array([frame.ego.x_m, frame.ego.y_m, Z_LINK_M])
        n_links = n_areas = n_boxes = 0
        best = _most_critical(rows)
        for row in best.values():
            rings = detail.road_areas[row.index] if detail.road_areas else ()
            for ring in rings:
                self.areas.append(np.asarray(ring, dtype=np.float64))
                danger = row.state == "dangerous"
                self.area_colors.append(DANGEROUS_COLOR if danger else ROAD_AREA_COLOR)
                n_areas += 1
        per_object = Counter(row.label for row in rows)
        for label, row in best.items():
            k = where.get(label)
            if k is None:
                continue
            danger = row.state == "dangerous"
            other = np.array([actors.x_m[k], actors.y_m[k], Z_LINK_M])
            self.links.append(np.stack([ego, other]))
            self.link_colors.append(DANGEROUS_COLOR if danger else TYPE_COLORS[row.ctype])
            self.link_radii.append(0.12 if danger else 0.06)
            more = per_object[label] - 1
            text = row.text(self.short.label(label))
            self.link_labels.append(text + (f"  (+{more} more)" if more else ""))
            self.link_ids.append(label)
            n_links += 1
        for label, row in best.items():
            self.states.setdefault(label, ["not relevant"] * self.n)[i] = row.state
            for name, value in row.series().items():
                if np.isfinite(value):
                    rows_vals = self.dist.setdefault(f"{label}/{name}", ([], []))
                    rows_vals[0].append(i)
                    rows_vals[1].append(value)
            k = where.get(label)
            if row.state == "dangerous" and k is not None:
                self.danger.append(
                    (
                        float(actors.x_m[k]),
                        float(actors.y_m[k]),
                        float(actors.z_m[k]),
                        float(actors.length_m[k]) / 2 + DANGER_MARGIN_M,
                        float(actors.width_m[k]) / 2 + DANGER_MARGIN_M,
                        float(actors.height_m[k]) / 2 + DANGER_MARGIN_M,
                        float(actors.yaw_rad[k]),
                    )
                )
                n_boxes += 1
        return n_links, n_areas, n_boxes


def layout_rss(
    frames: Sequence[Frame], verdicts: Sequence[RssVerdict], labels: ShortLabels | None = None
) -> RssColumns:
    """Columnar structured-RSS display data for a chunk of frames and their verdicts.

    Args:
        frames: ``N`` frames.
        verdicts: The ``rss`` verdict of each frame.
        labels: The drive's short labels (objects not in it yet are numbered next); a fresh
            table by default.
    """
    n = len(frames)
    b = _Builder(n, labels if labels is not None else ShortLabels())
    counts = np.zeros((3, n), dtype=np.int64)
    frame_state = []
    for i, (frame, verdict) in enumerate(zip(frames, verdicts, strict=True)):
        if verdict.result is None:
            frame_state.append("no constellation")
            continue
        frame_state.append("safe" if verdict.is_safe else "dangerous")
        counts[:, i] = b.add_frame(i, frame, verdict)
    box = np.array(b.danger, dtype=np.float64).reshape(-1, 7)
    responses = {
        lane: [response_name(v, key) for v in verdicts] for key, (lane, _) in RESPONSE_LANES.items()
    }
    return RssColumns(
        frame_state=frame_state,
        link_strips_m=np.array(b.links, dtype=np.float32).reshape(-1, 2, 3),
        link_counts=counts[0],
        link_colors=np.array(b.link_colors, dtype=np.uint32),
        link_radii_m=np.array(b.link_radii, dtype=np.float32),
        link_labels=b.link_labels,
        link_object_ids=b.link_ids,
        area_strips_m=pad_polylines(b.areas, z_m=Z_AREA_M),
        area_counts=counts[1],
        area_colors=np.array(b.area_colors, dtype=np.uint32),
        danger_centre_m=box[:, :3].astype(np.float32),
        danger_half_m=box[:, 3:6].astype(np.float32),
        danger_quat_xyzw=yaw_to_quaternion(box[:, 6]),
        danger_counts=counts[2],
        object_states=b.states,
        distances={
            key: (np.array(r, dtype=np.int64), np.array(v, dtype=np.float64))
            for key, (r, v) in sorted(b.dist.items())
        },
        responses=responses,
        accel={
            name: np.array([accel_bound(v, name) for v in verdicts], dtype=np.float64)
            for name in ACCEL_SERIES
        },
    )
