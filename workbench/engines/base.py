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
    from workbench.engines.ids import ActorIds
    from workbench.replay.layout import ChunkLayout
    from workbench.replay.short_labels import ShortLabels

__all__ = [
    "BoundRunner",
    "EngineRunner",
    "EngineSink",
    "EngineSpec",
    "NoOptions",
    "RunnerFactory",
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

    @property
    def name(self) -> str:
        """The engine's name."""
        ...

    def step_many(self, frames: Sequence[Frame]) -> Sequence[Verdict]:
        """Evaluate consecutive frames (same verdicts as one frame per call, in turn)."""
        ...


class RunnerFactory(Protocol):
    """Builds an engine's runner for one drive."""

    def __call__(
        self,
        lane_map: LaneMap | None,
        options: Any,
        *,
        full_geometry: bool,
        actor_ids: ActorIds,
    ) -> EngineRunner:
        """A fresh runner for the drive's ``lane_map`` with the engine's own ``options``.

        ``full_geometry``: compute everything a viewer draws (replays), not only verdicts.
        ``actor_ids``: the drive's actor label table, one for all its engines (an engine
        that reports objects by integer id maps them through it).
        """
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
class NoOptions:
    """The options of an engine that has none."""


@dataclass(frozen=True, slots=True)
class EngineSpec:
    """One engine plugin.

    Attributes:
        name: ``--engines`` name and key of its per-frame JSON record.
        title: Name of its state-lane tab in the viewer.
        short: Column name in the ``demo`` table.
        state_origin: Entity path of its state lanes (the tab's origin).
        causes: The violation causes its verdicts can name (documentation, incident filters).
        build: Runner factory (:class:`RunnerFactory`) from the drive's lane map and the
            engine's own options object (an instance of ``options``).
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
        incident_overrides: Rerun property overrides of the engine's entities in one
            incident's view, or ``None``.
        options: The engine's options: a frozen dataclass whose fields are made with
            :func:`workbench.engines.options.option` (name, type, default, flag, help;
            validation in ``__post_init__``). The CLI options of every command that runs
            engines, the engine's ``--settings`` TOML section and its part of the incident
            request are generated from it.
        errors: The engine's error types that are the user's input (one-line CLI messages).
        what_if: The engine's what-if variants of its options for the review, as
            ``(label, options)`` pairs, or ``None`` (no what-if).
        describe: One line on the options in effect for a drive's lane map (``workbench
            info``), or ``None``.
        packages: Import packages the engine's verdicts depend on besides its folder (their
            code is fingerprinted by ``workbench batch``).
        case_document: A recorded drive as the engine library's conformance case document,
            called ``(drive, *, name, method, source)`` (``workbench conformance
            reachsets-cases --log``), or ``None``.
    """

    name: str
    title: str
    short: str
    state_origin: str
    causes: tuple[str, ...]
    build: RunnerFactory
    record: Callable[[Any], dict[str, Any]]
    sink: Callable[[rr.RecordingStream, ShortLabels], EngineSink]
    views: Callable[[], list[rrb.View]]
    incident_facts: Callable[[], Any] | None = None
    join_causes: Callable[[Sequence[object]], str] | None = None
    incident_overrides: Callable[[], dict[str, Any]] | None = None
    options: type[Any] = NoOptions
    errors: tuple[type[Exception], ...] = ()
    what_if: Callable[[Any], Sequence[tuple[str, Any]]] | None = None
    describe: Callable[[LaneMap | None, Any], str] | None = None
    packages: tuple[str, ...] = ()
    case_document: Callable[..., dict[str, Any]] | None = None


@dataclass(frozen=True, slots=True)
class BoundRunner:
    """An engine's runner with the spec it was built from (an :class:`EngineRunner`).

    The driver's chunks carry the specs of their engines, so the sinks and the incident
    detector use the engine's own ``record``, ``sink`` and incident hooks without asking the
    registry for a name.
    """

    spec: EngineSpec
    runner: EngineRunner

    @property
    def name(self) -> str:
        """The engine's name."""
        return self.spec.name

    def step_many(self, frames: Sequence[Frame]) -> Sequence[Verdict]:
        """The runner's verdicts on consecutive ``frames``."""
        return self.runner.step_many(frames)
