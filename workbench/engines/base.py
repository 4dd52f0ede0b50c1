"""What every engine plugin provides: its runner, typed verdicts, record, Rerun sink and views.

An engine is one :class:`EngineSpec` registered in :mod:`workbench.engines.registry`. The
driver (:mod:`workbench.driver`) calls its runner on chunks of frames; the runner returns one
frozen, typed verdict per frame. The sinks consume the verdicts: the per-frame JSON line
(:mod:`workbench.sinks.per_frame`, through the spec's ``record``), violation intervals
(:mod:`workbench.sinks.violations`, through the four summary attributes every verdict
has) and Rerun (the spec's ``sink`` and ``views``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    import rerun as rr
    import rerun.blueprint as rrb

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.params import RssParams
    from workbench.engines.ids import ActorIds
    from workbench.replay.layout import ChunkLayout
    from workbench.replay.short_labels import ShortLabels

__all__ = [
    "EngineRunner",
    "EngineSettings",
    "EngineSink",
    "EngineSpec",
    "Verdict",
    "VerdictSummary",
    "summarise",
]


class Verdict(Protocol):
    """What every engine's per-frame verdict carries besides its own typed fields.

    Attributes:
        is_safe: The frame verdict of this engine.
        culprits: Ids of the objects that make the frame unsafe, sorted.
        cause: Short reason (rule or response) for violation intervals; ``""`` when safe.
            Typed as the engine likes (an enum, a frozen record: hashable, equal when the
            reason is) until a sink writes it: its ``str()`` is the text.
        margin: Engine-specific severity, smaller is worse (``inf`` when safe).
    """

    @property
    def is_safe(self) -> bool: ...  # noqa: D102
    @property
    def culprits(self) -> tuple[str, ...]: ...  # noqa: D102
    @property
    def cause(self) -> object: ...  # noqa: D102
    @property
    def margin(self) -> float: ...  # noqa: D102


@dataclass(frozen=True, slots=True)
class VerdictSummary:
    """The light part of a verdict (no geometry): what violation detection keeps per frame.

    ``cause`` is the verdict's cause as text.
    """

    is_safe: bool
    culprits: tuple[str, ...] = ()
    cause: str = ""
    margin: float = float("inf")


def summarise(verdict: Verdict) -> VerdictSummary:
    """The summary of any engine's verdict."""
    return VerdictSummary(verdict.is_safe, verdict.culprits, str(verdict.cause), verdict.margin)


class EngineRunner(Protocol):
    """A stateful wrapper of one pure engine, carrying its explicit state across calls."""

    name: str

    def step_many(self, frames: Sequence[Frame]) -> Sequence[Verdict]:
        """Evaluate consecutive frames (same verdicts as one frame per call, in turn)."""
        ...


class EngineSink(Protocol):
    """Sends one engine's verdicts of a chunk of frames to a Rerun recording."""

    def send_chunk(
        self, frames: Sequence[Frame], layout: ChunkLayout, verdicts: Sequence[Any]
    ) -> None:
        """Lay out and send the verdicts of ``frames`` (``layout``: the scene columns).

        ``verdicts`` are the engine's own verdict type (the runner's ``step_many`` output).
        """
        ...


@dataclass(frozen=True, slots=True)
class EngineSettings:
    """The user's settings every engine factory receives.

    Attributes:
        rss_params: RSS dynamics, scene settings and the ego's dimensions
            (``--rss-params``); ``None`` = defaults.
        reach_method: ``--reach-method`` (``simple``, ``turn`` or ``bound``).
        full_geometry: Compute everything the viewer draws (replay), not only the verdict.
        reach_rules: ``--reach-rules``: ``public_road`` (the reference's rules plus the lane
            rules, the default for recorded drives) or ``reference``.
        reach_trajectory: ``--reach-trajectory``: ``auto`` (the log's emergency trajectory
            when it has one, else braking from the ego's state; the default), ``planned`` or
            ``braking``.
        actor_ids: The drive's actor label table, one for all its engines (set per drive by
            :func:`~workbench.engines.registry.build_runners`; ``None``: a runner keeps its
            own).
    """

    rss_params: RssParams | None = None
    reach_method: str = "turn"
    full_geometry: bool = False
    reach_rules: str = "public_road"
    reach_trajectory: str = "auto"
    actor_ids: ActorIds | None = None


@dataclass(frozen=True, slots=True)
class EngineSpec:
    """One engine plugin.

    Attributes:
        name: ``--engines`` name and key of its per-frame JSON record.
        title: Name of its state-lane tab in the viewer.
        short: Column name in the ``demo`` table.
        state_origin: Entity path of its state lanes (the tab's origin).
        causes: The violation causes its verdicts can name (documentation, incident filters).
        build: Runner factory from the drive's lane map and the user's settings.
        record: The engine's part of the pinned per-frame JSON line, from one verdict.
        sink: Rerun sink factory (sends static configuration on creation) from the
            recording and the drive's short-label table: every object label the sink draws is
            the object's short label (``#1``), the full id kept beside it
            (:mod:`workbench.replay.short_labels`).
        views: Extra viewer panels (plots) shown while the engine runs.
        incident_facts: Factory of a collector of the engine's own severity facts per incident
            (``workbench.incidents.FactCollector``: ``add(frame, t_ns, verdict, object_id)``,
            ``facts()``), or ``None``.
        join_causes: When set, the engine's incidents are one per object and unsafe run,
            whatever causes its frames name, and this joins the causes of a run (the
            verdicts' typed causes, in order of appearance) into the incident's cause text;
            ``None``: a change of cause starts a new incident.
    """

    name: str
    title: str
    short: str
    state_origin: str
    causes: tuple[str, ...]
    build: Callable[[LaneMap | None, EngineSettings], EngineRunner]
    record: Callable[[Any], dict[str, Any]]
    sink: Callable[[rr.RecordingStream, ShortLabels], EngineSink]
    views: Callable[[], list[rrb.View]]
    incident_facts: Callable[[], Any] | None = None
    join_causes: Callable[[Sequence[object]], str] | None = None
    incident_overrides: Callable[[], dict[str, Any]] | None = None
