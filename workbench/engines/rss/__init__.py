"""Structured RSS as a workbench engine: scene creation from the lane map + ad-rss 5.0 checks.

Files: ``adapter`` (lane map and frames to scene inputs), ``runner`` (state across frames),
``verdict`` (the typed per-frame verdict), ``record`` (its pinned JSON), ``outlines``,
``layout`` and ``sink`` (what the viewer shows).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rss.errors import RssError
from workbench.engines.base import EngineSpec
from workbench.engines.rss.causes import CAUSES, join_causes
from workbench.engines.rss.incident_facts import RssIncidentFacts
from workbench.engines.rss.options import (
    RssOptions,
    describe,
    load_params,
    scene_sized,
    what_if,
)
from workbench.engines.rss.record import rss_record

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb

    from loaders.maps.model import LaneMap
    from workbench.engines.base import EngineRunner, EngineSink
    from workbench.engines.ids import ActorIds
    from workbench.replay.short_labels import ShortLabels

__all__ = ["SPEC"]


def _build(
    lane_map: LaneMap | None, options: RssOptions, *, full_geometry: bool, actor_ids: ActorIds
) -> EngineRunner:
    from workbench.engines.rss.runner import RssRunner  # noqa: PLC0415 - heavy, on demand

    params = load_params(options, lane_map)
    return scene_sized(RssRunner(lane_map, params, outlines=full_geometry, ids=actor_ids), params)


def _sink(recording: rr.RecordingStream, labels: ShortLabels) -> EngineSink:
    from workbench.engines.rss.sink import RssSink  # noqa: PLC0415

    return RssSink(recording, labels)


def _views() -> list[rrb.View]:
    import rerun.blueprint as rrb  # noqa: PLC0415 - the viewer's, on demand

    return [
        rrb.TimeSeriesView(name="rss acceleration limits [m/s²]", origin="/plots/rss/acceleration"),
        rrb.TimeSeriesView(name="rss distance vs safe [m]", origin="/plots/rss/distances"),
        rrb.TimeSeriesView(
            name="rss proper response: allowed vs measured accel [m/s²]",
            origin="/plots/rss/compliance",
        ),
    ]


def _incident_overrides() -> dict[str, Any]:
    """In one incident's view: no per-object labels (the incident's objects are highlighted)."""
    import rerun as rr  # noqa: PLC0415 - the viewer's, on demand

    return {"world/rss/constellations": rr.LineStrips3D.from_fields(show_labels=False)}


SPEC = EngineSpec(
    name="rss",
    title="rss",
    short="rss",
    state_origin="/rss/structured",
    # the proper responses an unsafe frame demands, e.g. "RSS lon BrakeMin, lat-left BrakeMin"
    causes=CAUSES,
    build=_build,
    record=rss_record,
    sink=_sink,
    views=_views,
    incident_overrides=_incident_overrides,
    incident_facts=RssIncidentFacts,
    join_causes=join_causes,
    options=RssOptions,
    errors=(RssError,),
    what_if=what_if,
    describe=describe,
    packages=("rss",),
)
