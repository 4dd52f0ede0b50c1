"""Unstructured RSS (ad-rss 5.0 trajectory sets) as a workbench engine.

Files: ``adapter`` (which pairs are unstructured; frames to agents), ``runner``, ``verdict``,
``record`` (its pinned JSON), ``layout`` and ``sink`` (what the viewer shows).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.errors import RssError
from workbench.engines.base import EngineSpec
from workbench.engines.rss.options import RssOptions, load_params, scene_sized, what_if
from workbench.engines.unstructured.record import unstructured_record

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
    from workbench.engines.unstructured.runner import UnstructuredRunner  # noqa: PLC0415

    del full_geometry  # the verdict is all it draws
    params = load_params(options, lane_map)
    return scene_sized(UnstructuredRunner(lane_map, params, ids=actor_ids), params)


def _sink(recording: rr.RecordingStream, labels: ShortLabels) -> EngineSink:
    from workbench.engines.unstructured.sink import UnstructuredSink  # noqa: PLC0415

    return UnstructuredSink(recording, labels)


def _views() -> list[rrb.View]:
    return []


SPEC = EngineSpec(
    name="unstructured",
    title="unstructured",
    short="unstr.",
    state_origin="/rss/unstructured",
    causes=(
        "unstructured: brake",
        "unstructured: drive-away",
        "unstructured: continue-forward",
        "unstructured: none",
    ),
    build=_build,
    record=unstructured_record,
    sink=_sink,
    views=_views,
    options=RssOptions,
    errors=(RssError,),
    what_if=what_if,
    packages=("rss",),
)
