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

from typing import TYPE_CHECKING

import rerun.blueprint as rrb

from workbench.engines.registry import engine, names
from workbench.replay.sink import FRAME_TIMELINE, TIME_TIMELINE

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["TRAIL_FRAMES", "TRAIL_SECONDS", "replay_blueprint"]

#: The ego trail shows this many past frames on the ``frame`` timeline ...
TRAIL_FRAMES = 100
#: ... or this many seconds on the ``log_time`` timeline.
TRAIL_SECONDS = 10.0

#: Camera offset from the ego: behind (-x), above (+z); metres, map frame.
_EYE_OFFSET_M = (-25.0, 0.0, 60.0)


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


def replay_blueprint(
    ego_start_m: tuple[float, float] | None = None, engines: Sequence[str] = ()
) -> rrb.Blueprint:
    """The default blueprint: scene, plots, engine result views, time panel on ``frame``.

    Args:
        ego_start_m: Ego position at the first frame ``(x, y)``; the camera starts there and
            then tracks ``world/ego``.
        engines: Names of the engines whose results are logged (registered engines); the
            first one's state lanes are the active tab.
    """
    x0, y0 = ego_start_m or (0.0, 0.0)
    dx, dy, dz = _EYE_OFFSET_M
    scene = rrb.Spatial3DView(
        name="scene",
        origin="/world",
        line_grid=rrb.LineGrid3D(visible=False),
        eye_controls=rrb.EyeControls3D(
            kind=rrb.Eye3DKind.Orbital,
            position=(x0 + dx, y0 + dy, dz),
            look_target=(x0, y0, 0.0),
            eye_up=(0.0, 0.0, 1.0),
            tracking_entity="/world/ego",
        ),
        overrides={"world/ego/trail": _trail_ranges()},
    )
    views: list[rrb.View | rrb.Container] = [
        rrb.TimeSeriesView(name="ego", origin="/plots/ego"),
        rrb.TimeSeriesView(name="actors", origin="/plots/actors"),
    ]
    for name in engines:
        views.extend(engine(name).views())
    specs = [engine(name) for name in names()]
    tabs = [rrb.StateTimelineView(name=spec.title, origin=spec.state_origin) for spec in specs]
    active = engine(engines[0]).title if engines else specs[0].title
    views.append(rrb.Tabs(*tabs, active_tab=active))
    side = rrb.Vertical(*views, row_shares=[2] * (len(views) - 1) + [2 if engines else 1])
    return rrb.Blueprint(
        rrb.Horizontal(scene, side, column_shares=[3, 1]),
        rrb.TimePanel(timeline=FRAME_TIMELINE, play_state="paused", state="collapsed"),
        rrb.SelectionPanel(state="hidden"),
        rrb.BlueprintPanel(state="hidden"),
        collapse_panels=False,
    )
