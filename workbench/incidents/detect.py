"""Incidents from the driver's chunks: runs of unsafe frames per engine, object and cause.

An engine whose spec joins causes (``EngineSpec.join_causes``: structured RSS) keys its
incidents per object only: a change of cause inside a run does not split it, the incident's
cause joins the causes of its frames, and its ``legacy_ids`` are the ids the pieces had when
each cause made its own incident (labels written then still find the incident).

Severity is the incident's own object's: its margin is the engine's margin for that object
(a verdict's ``object_margin(object_id)`` where the engine has one, else the frame's
margin), and its physical facts (:mod:`workbench.incidents.kinematics`) come from the
ego's and that object's states in the incident's unsafe frames.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s, s_to_ns
from workbench.engines.base import VerdictSummary
from workbench.incidents.facts import collectors_for
from workbench.incidents.kinematics import MotionFacts, motion_of
from workbench.incidents.model import Incident, IncidentSettings, Severity, incident_id
from workbench.incidents.order import severity_key
from workbench.quality import TrackCollector, check_tracks
from workbench.quality.suspect import flag_suspects
from workbench.sinks.runs import Run, RunMerger

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    from loaders.records import Frame
    from workbench.driver.run import Chunk
    from workbench.engines.base import EngineSpec, Verdict
    from workbench.incidents.model import Fact
    from workbench.quality import Finding

__all__ = ["IncidentDetector", "IncidentKey"]

#: ``(engine, object id or "", cause)``.
IncidentKey = tuple[str, str, str]


def own_margin(verdict: Verdict, object_id: str) -> float:
    """The verdict's margin for one of its culprits (the frame's when it has no per-object one)."""
    of = getattr(verdict, "object_margin", None)
    if of is None or not object_id:
        return verdict.margin
    return float(of(object_id))


class IncidentDetector:
    """A sink of driver chunks that merges each engine's unsafe frames into incidents.

    A frame an engine rates unsafe hits one key per culprit (``(engine, object, cause)``;
    a verdict naming no culprit hits ``(engine, "", cause)``). Memory grows with the
    incidents and the frame count (one time stamp per frame), not with the verdicts.
    """

    def __init__(
        self,
        drive_hash: str,
        settings: IncidentSettings | None = None,
        *,
        engines: Sequence[EngineSpec] = (),
    ) -> None:
        """Start empty for the drive of content hash ``drive_hash``.

        ``engines``: the specs of the engines whose verdicts :meth:`add` gets (their cause
        joining and severity facts); the chunks of :meth:`add_chunk` bring their own.
        """
        self.drive_hash = drive_hash
        self.settings = settings or IncidentSettings()
        self._runs: RunMerger[IncidentKey] = RunMerger(s_to_ns(self.settings.merge_gap_s))
        #: ``(frame index, t_ns)`` of every frame added, in order.
        self.frame_times: list[tuple[int, int]] = []
        #: Ego position ``(x, y)`` [m] at the first frame of each incident (chunks only).
        self.ego_at_start_m: dict[int, tuple[float, float]] = {}
        #: Positions ``(x, y)`` [m] of the frame's culprits at the first frame of each
        #: incident, by object id (chunks only): where the review camera looks.
        self.objects_at_start_m: dict[int, dict[str, tuple[float, float]]] = {}
        self._specs = {spec.name: spec for spec in engines}
        #: Per run of an engine that joins causes (by key and start frame): ``(frame,
        #: cause)`` where the (typed) cause changed, in order.
        self._trails: dict[tuple[IncidentKey, int], list[tuple[int, object]]] = {}
        #: Every object's states (chunks only), for the data-quality checks.
        self.tracks = TrackCollector()

    def _join_of(self, engine: str) -> Callable[[Sequence[object]], str] | None:
        spec = self._specs.get(engine)
        return None if spec is None else spec.join_causes

    def _hits(
        self, verdicts: Mapping[str, Verdict]
    ) -> tuple[dict[IncidentKey, Verdict], dict[IncidentKey, VerdictSummary]]:
        """The keys a frame hits, each with its verdict and with the own object's summary."""
        hits: dict[IncidentKey, Verdict] = {}
        own: dict[IncidentKey, VerdictSummary] = {}
        for engine, verdict in verdicts.items():
            if verdict.is_safe:
                continue
            cause = "" if self._join_of(engine) else str(verdict.cause)
            for obj in verdict.culprits or ("",):
                hits[engine, obj, cause] = verdict
                own[engine, obj, cause] = VerdictSummary(
                    is_safe=False,
                    culprits=(obj,) if obj else (),
                    cause=str(verdict.cause),
                    margin=own_margin(verdict, obj),
                )
        return hits, own

    def add(
        self, frame: int, t_ns: int, verdicts: Mapping[str, Verdict], scene: Frame | None = None
    ) -> bool:
        """Add one frame's verdicts per engine (frames in time order).

        ``scene``: the frame's states, for the physical facts (none without it).

        Returns:
            Whether the frame started an incident.
        """
        self.frame_times.append((frame, t_ns))
        hits, own = self._hits(verdicts)
        started = False
        index: dict[str, int] | None = None
        for run in self._runs.add(frame, t_ns, own):
            if run.unsafe_frames == 1:
                started = True
                spec = self._specs.get(run.key[0])
                facts = None if spec is None else spec.incident_facts
                run.extra = [MotionFacts(), *collectors_for(run.key[0], facts)]
            if scene is not None and run.key[1]:
                if index is None:
                    index = {oid: j for j, oid in enumerate(scene.actors.ids.tolist())}
                found = motion_of(scene, run.key[1], index)
                if found is not None:
                    run.extra[0].add(found)
            verdict = hits[run.key]
            if self._join_of(run.key[0]):
                trail = self._trails.setdefault((run.key, run.start_frame), [])
                if not trail or trail[-1][1] != verdict.cause:
                    trail.append((frame, verdict.cause))
            for collector in run.extra[1:]:
                collector.add(frame, t_ns, verdict, run.key[1])
        return started

    def add_chunk(self, chunk: Chunk) -> None:
        """Add every frame of a driver chunk."""
        self._specs.update(chunk.specs)
        self.tracks.add(chunk.frames)
        for k, frame in enumerate(chunk.frames):
            verdicts = {n: v[k] for n, v in chunk.verdicts.items()}
            if self.add(frame.index, frame.t_ns, verdicts, frame):
                self.ego_at_start_m[frame.index] = (frame.ego.x_m, frame.ego.y_m)
                culprits = {c for v in verdicts.values() if not v.is_safe for c in v.culprits}
                actors = frame.actors
                self.objects_at_start_m[frame.index] = {
                    str(oid): (float(actors.x_m[j]), float(actors.y_m[j]))
                    for j, oid in enumerate(actors.ids.tolist())
                    if oid in culprits
                }

    def _incident(self, run: Run[IncidentKey]) -> Incident:
        engine, obj, cause = run.key
        objects = (obj,) if obj else ()
        trail = self._trails.get((run.key, run.start_frame), [])
        legacy = tuple(
            dict.fromkeys(
                incident_id(self.drive_hash, engine, objects, str(piece), frame)
                for frame, piece in trail
            )
        )
        join = self._join_of(engine)
        shown = join([piece for _, piece in trail]) if join and trail else cause
        facts: dict[str, Fact] = {}
        worst = run.worst_frame
        for collector in run.extra:
            facts.update(collector.facts())
            finer = getattr(collector, "worst_frame", None)  # optional: the engine's own worst
            found = finer() if callable(finer) else None
            worst = found if isinstance(found, int) else worst
        severity = Severity(
            worst_margin=run.worst_margin,
            unsafe_frames=run.unsafe_frames,
            duration_s=ns_to_s(run.end_ns - run.start_ns),
            facts=facts,
        )
        return Incident(
            id=incident_id(self.drive_hash, engine, objects, cause, run.start_frame),
            engine=engine,
            objects=objects,
            cause=shown,
            start_frame=run.start_frame,
            end_frame=run.end_frame,
            start_ns=run.start_ns,
            end_ns=run.end_ns,
            severity=severity,
            legacy_ids=legacy,
            worst_frame=worst,
        )

    def findings(self) -> tuple[Finding, ...]:
        """The data-quality findings of the frames added by chunk (docs/data_quality.md)."""
        return check_tracks(self.tracks.tracks())

    def incidents(self, findings: Sequence[Finding] | None = None) -> list[Incident]:
        """Incidents at least ``min_duration_s`` long, most severe first (:mod:`.order`).

        ``data_suspect`` is set from ``findings`` (default: :meth:`findings`) before the sort,
        so suspect incidents rank after clean ones.
        """
        min_ns = s_to_ns(self.settings.min_duration_s)
        found = [self._incident(r) for r in self._runs.runs() if r.end_ns - r.start_ns >= min_ns]
        found = flag_suspects(found, self.findings() if findings is None else findings)
        found.sort(key=severity_key)
        return found
