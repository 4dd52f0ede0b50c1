"""The rule-based reach-set supervisor as a workbench engine.

Files: ``adapter`` (lane map and frames to reach-set inputs), ``runner``, ``verdict``,
``record`` (its pinned JSON), ``layout`` and ``sink`` (what the viewer shows).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from reachsets.errors import ReachSetError
from workbench.engines.base import EngineSpec
from workbench.engines.reachsets.options import ReachOptions
from workbench.engines.reachsets.record import reach_record

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb

    from loaders.drive import Drive
    from loaders.maps.model import LaneMap
    from workbench.engines.base import EngineRunner, EngineSink
    from workbench.engines.ids import ActorIds
    from workbench.replay.short_labels import ShortLabels

__all__ = ["SPEC"]


def _build(
    lane_map: LaneMap | None, options: ReachOptions, *, full_geometry: bool, actor_ids: ActorIds
) -> EngineRunner:
    from workbench.engines.reachsets.runner import ReachRunner  # noqa: PLC0415 - on demand

    del actor_ids  # the reach sets report objects by their own string ids

    return ReachRunner(
        lane_map,
        method=options.method,
        full_geometry=full_geometry,
        rules=options.rules.setting,
        trajectory=options.trajectory.value,
    )


def _sink(recording: rr.RecordingStream, labels: ShortLabels) -> EngineSink:
    from workbench.engines.reachsets.sink import ReachSink  # noqa: PLC0415

    return ReachSink(recording, labels)


def _views() -> list[rrb.View]:
    import rerun.blueprint as rrb  # noqa: PLC0415 - the viewer's, on demand

    return [rrb.TimeSeriesView(name="first collision [s into plan]", origin="/plots/reach")]


def _case_document(drive: Drive, **how: Any) -> dict[str, Any]:
    from workbench.engines.reachsets.cases import drive_case_document  # noqa: PLC0415

    return drive_case_document(drive, **how)


def _incident_overrides() -> dict[str, Any]:
    """In one incident's view: no per-object labels (the incident's objects are highlighted)."""
    import rerun as rr  # noqa: PLC0415 - the viewer's, on demand

    return {"world/reach/collisions": rr.Points3D.from_fields(show_labels=False)}


SPEC = EngineSpec(
    name="reachsets",
    title="reach sets",
    short="reach",
    state_origin="/reach",
    causes=("reach-set collision",),
    build=_build,
    record=reach_record,
    sink=_sink,
    views=_views,
    incident_overrides=_incident_overrides,
    options=ReachOptions,
    errors=(ReachSetError,),
    packages=("reachsets",),
    case_document=_case_document,
)
