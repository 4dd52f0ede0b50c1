"""The default viewer layout of a replay, built in one function.

::

    +-------------------------------------+------------------------+
    |                                     | ego speed, accel       |
    |  world: 3-D scene, camera follows   +------------------------+
    |  the ego from above and behind      | actors: count, nearest |
    |                                     +------------------------+
    |                                     | engine state lanes     |
    +-------------------------------------+------------------------+
    | time panel on the ``frame`` timeline                         |
    +--------------------------------------------------------------+

Each registered engine adds its own plots (``EngineSpec.views``) while it runs and one tab of
state lanes (``EngineSpec.state_origin``), empty until the engine logs its results there.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import rerun as rr
import rerun.blueprint as rrb

from workbench.engines.registry import engine, names
from workbench.replay import style
from workbench.replay.highlight import HIGHLIGHT_ORIGIN, highlight_path
from workbench.replay.incidents import INCIDENT_LOG, LANES_ORIGIN
from workbench.replay.sink import FRAME_TIMELINE, TIME_TIMELINE

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rerun.blueprint.api import VisualizerLike
    from rerun.datatypes import EntityPathLike

    from workbench.incidents import Incident

__all__ = [
    "TRAIL_FRAMES",
    "TRAIL_SECONDS",
    "incident_eye",
    "replay_blueprint",
    "thumbnail_blueprint",
]

#: The ego trail shows this many past frames on the ``frame`` timeline ...
TRAIL_FRAMES = 100
#: ... or this many seconds on the ``log_time`` timeline.
TRAIL_SECONDS = 10.0

#: Camera offset from the ego: behind (-x), above (+z); metres, map frame.
_EYE_OFFSET_M = (-25.0, 0.0, 60.0)
#: Ground radius [m] the default eye shows around its target, and the margin kept around the
#: actors of an incident when the eye is pulled back to show them all.
_FRAME_RADIUS_M = 30.0
_FRAME_MARGIN_M = 10.0


def _trail_ranges() -> rrb.VisibleTimeRanges:
    return rrb.VisibleTimeRanges(
        [
            rrb.VisibleTimeRange(
                FRAME_TIMELINE,
                start=rrb.TimeRangeBoundary.cursor_relative(seq=-TRAIL_FRAMES),
                end=rrb.TimeRangeBoundary.cursor_relative(),
            ),
            rrb.VisibleTimeRange(
                TIME_TIMELINE,
                start=rrb.TimeRangeBoundary.cursor_relative(seconds=-TRAIL_SECONDS),
                end=rrb.TimeRangeBoundary.cursor_relative(),
            ),
        ]
    )


def _time_panel(selection: tuple[int, int] | None) -> rrb.TimePanel:
    if selection is None:
        return rrb.TimePanel(timeline=FRAME_TIMELINE, play_state="paused", state="collapsed")
    first, last = selection
    return rrb.TimePanel(
        timeline=FRAME_TIMELINE,
        play_state="paused",
        state="expanded",
        loop_mode="selection",
        time_selection=rrb.components.AbsoluteTimeRange(min=first, max=last),
    )


def incident_eye(
    ego_m: tuple[float, float], actors_m: Sequence[tuple[float, float]] = ()
) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """Eye ``position`` and ``look_target`` [m] that frame the ego and the actors involved.

    The target is the centroid of the ego and the actors; the eye keeps the replay's offset
    (behind and above), scaled up when the actors are far apart so all of them stay in view.
    """
    points = [ego_m, *actors_m]
    cx = sum(p[0] for p in points) / len(points)
    cy = sum(p[1] for p in points) / len(points)
    spread = max(math.hypot(p[0] - cx, p[1] - cy) for p in points)
    dx, dy, dz = _EYE_OFFSET_M
    scale = max(1.0, (spread + _FRAME_MARGIN_M) / _FRAME_RADIUS_M)
    return (cx + dx * scale, cy + dy * scale, dz * scale), (cx, cy, 0.0)


def _scene_contents(incident: Incident | None) -> list[str]:
    if incident is None:
        return ["+ /world/**"]
    own = highlight_path(incident, rr.escape_entity_path_part)
    return ["+ /world/**", f"- /{HIGHLIGHT_ORIGIN}/**", f"+ /{own}/**"]


def _scene_overrides(incident: Incident | None) -> dict[EntityPathLike, VisualizerLike]:
    overrides: dict[EntityPathLike, VisualizerLike] = {"world/ego/trail": _trail_ranges()}
    if incident is not None:
        overrides["world/actors"] = rr.Boxes3D.from_fields(
            colors=[style.INCIDENT_DIM_COLOR], show_labels=False
        )
        overrides["world/actors/velocity"] = rr.Arrows3D.from_fields(
            colors=[style.INCIDENT_DIM_COLOR]
        )
        for name in names():  # an override of an entity a recording lacks is a no-op
            spec = engine(name)
            if spec.incident_overrides is not None:
                overrides.update(spec.incident_overrides())
    return overrides


def _scene(
    eye: tuple[tuple[float, float, float], tuple[float, float, float]],
    incident: Incident | None,
    *,
    tracking: bool,
) -> rrb.Spatial3DView:
    """The 3-D scene of ``/world`` seen from ``eye`` (``(position, look_target)`` [m])."""
    position, target = eye
    return rrb.Spatial3DView(
        name="scene",
        origin="/world",
        line_grid=rrb.LineGrid3D(visible=False),
        eye_controls=rrb.EyeControls3D(
            kind=rrb.Eye3DKind.Orbital,
            position=position,
            look_target=target,
            eye_up=(0.0, 0.0, 1.0),
            tracking_entity="/world/ego/view" if tracking else None,
        ),
        contents=_scene_contents(incident),
        overrides=_scene_overrides(incident),
    )


def thumbnail_blueprint(
    incident: Incident | None,
    eye: tuple[tuple[float, float, float], tuple[float, float, float]],
) -> rrb.Blueprint:
    """A clip thumbnail's blueprint: the scene view alone, no plot and no panel.

    Args:
        incident: The clip's incident: its objects highlighted and labelled, the other
            actors dimmed (as in the review); ``None`` for a window without incident.
        eye: Camera ``(position, look_target)`` [m], e.g. :func:`incident_eye` of the ego
            and the incident's objects at its worst frame.
    """
    return rrb.Blueprint(
        _scene(eye, incident, tracking=False),
        rrb.TimePanel(timeline=FRAME_TIMELINE, play_state="paused", state="hidden"),
        rrb.SelectionPanel(state="hidden"),
        rrb.BlueprintPanel(state="hidden"),
        rrb.TopPanel(state="hidden"),
        collapse_panels=True,
    )


def replay_blueprint(
    ego_start_m: tuple[float, float] | None = None,
    engines: Sequence[str] = (),
    *,
    selection: tuple[int, int] | None = None,
    focus_m: Sequence[tuple[float, float]] = (),
    incident: Incident | None = None,
) -> rrb.Blueprint:
    """The default blueprint: scene, plots, engine result views, time panel on ``frame``.

    With engines, an "incidents" tab holds the incident lanes and an "incident log" tab
    their markers (:mod:`workbench.replay.incidents`).

    Args:
        ego_start_m: Ego position at the first frame ``(x, y)``; the camera starts there and
            then tracks ``world/ego``.
        engines: Names of the engines whose results are logged (registered engines); the
            first one's state lanes are the active tab.
        selection: ``(first, last)`` frame of an incident under review: the time panel
            selects and loops over it, the incidents tab is active and the camera stays put
            at ``ego_start_m`` (pass the ego's position at the incident's start).
        focus_m: With ``selection``: the positions of the actors involved at the incident's
            start; the camera frames them with the ego (:func:`incident_eye`).
        incident: The incident under review: the scene shows its objects highlighted and
            labelled (:mod:`workbench.replay.highlight`), the other actors dimmed and
            unlabelled, and no other incident's highlight.
    """
    x0, y0 = ego_start_m or (0.0, 0.0)
    # A live viewer pulls a tracking eye in to the ego's box (about 4 m): for one incident
    # the camera stays where the incident is instead.
    scene = _scene(
        incident_eye((x0, y0), focus_m if selection is not None else ()),
        incident,
        tracking=selection is None,
    )
    views: list[rrb.View | rrb.Container] = [
        rrb.TimeSeriesView(name="ego", origin="/plots/ego"),
        rrb.TimeSeriesView(name="actors", origin="/plots/actors"),
    ]
    for name in engines:
        views.extend(engine(name).views())
    specs = [engine(name) for name in names()]
    tabs: list[rrb.View] = [
        rrb.StateTimelineView(name=spec.title, origin=spec.state_origin) for spec in specs
    ]
    active = engine(engines[0]).title if engines else specs[0].title
    if engines:
        tabs.append(rrb.StateTimelineView(name="incidents", origin=f"/{LANES_ORIGIN}"))
        tabs.append(rrb.TextLogView(name="incident log", origin=f"/{INCIDENT_LOG}"))
        if selection is not None:
            active = "incidents"
    views.append(rrb.Tabs(*tabs, active_tab=active))
    side = rrb.Vertical(*views, row_shares=[2] * (len(views) - 1) + [2 if engines else 1])
    return rrb.Blueprint(
        rrb.Horizontal(scene, side, column_shares=[3, 1]),
        _time_panel(selection),
        rrb.SelectionPanel(state="hidden"),
        rrb.BlueprintPanel(state="hidden"),
        collapse_panels=False,
    )
