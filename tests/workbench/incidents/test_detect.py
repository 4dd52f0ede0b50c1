import dataclasses
import math

import pytest

from rss.structured.states import LateralResponse, LongitudinalResponse
from workbench.engines.base import VerdictSummary
from workbench.engines.registry import engine, names
from workbench.engines.rss.causes import RssCause
from workbench.incidents import (
    Incident,
    IncidentDetector,
    IncidentSettings,
    incident_id,
    register_facts,
    unregister_facts,
)

T0 = 1_000_000_000
DT = 100_000_000  # 10 Hz

#: The registered engines' specs (what a chunk of the driver carries).
SPECS = tuple(engine(name) for name in names())


BRAKE = RssCause(lon=LongitudinalResponse.BrakeMin)


@dataclasses.dataclass(frozen=True)
class _Verdict:
    """An unsafe verdict with a typed cause (RSS') or a text one (the other engines')."""

    is_safe: bool
    culprits: tuple[str, ...]
    cause: object
    margin: float


def _verdict(culprits: tuple[str, ...], cause: object = BRAKE, margin: float = 0.0):
    return _Verdict(is_safe=False, culprits=culprits, cause=cause, margin=margin)


SAFE = VerdictSummary(is_safe=True)


def _detect(frames, drive_hash="h1", settings=None) -> list[Incident]:
    detector = IncidentDetector(drive_hash, settings, engines=SPECS)
    for i, verdicts in enumerate(frames):
        detector.add(i, T0 + i * DT, verdicts)
    return detector.incidents()


def test_unsafe_frames_split_per_engine_object_and_cause():
    brake, away = "unstructured: brake", "unstructured: drive-away"
    frames = [
        {"unstructured": SAFE},
        {"unstructured": _verdict(("a", "b"), cause=brake)},
        {"unstructured": _verdict(("a",), cause=brake)},
        {"unstructured": _verdict(("a",), cause=away)},
        {"unstructured": SAFE, "reachsets": _verdict((), cause="reach-set collision", margin=0.4)},
    ]
    found = {(i.engine, i.objects, i.cause): (i.start_frame, i.end_frame) for i in _detect(frames)}
    assert found == {
        ("unstructured", ("a",), brake): (1, 2),
        ("unstructured", ("b",), brake): (1, 1),
        ("unstructured", ("a",), away): (3, 3),
        ("reachsets", (), "reach-set collision"): (4, 4),
    }
    assert all(i.legacy_ids == () for i in _detect(frames))


def test_rss_incidents_are_one_per_object_with_the_union_of_the_responses():
    # the frame's responses change with other objects (b) and over the approach: one
    # incident per object and run; its cause joins the frames' (BrakeMin over BrakeMinCorrect)
    lon = RssCause(lon=LongitudinalResponse.BrakeMinCorrect)
    both = RssCause(LongitudinalResponse.BrakeMin, LateralResponse.BrakeMin)
    frames = [
        {"rss": _verdict(("a",), cause=lon)},
        {"rss": _verdict(("a", "b"), cause=both)},
        {"rss": _verdict(("a",), cause=lon)},
        {"rss": SAFE},
        {"rss": _verdict(("a",), cause=lon)},
    ]
    found = _detect(frames)
    runs = {(i.objects, i.cause): (i.start_frame, i.end_frame) for i in found}
    assert runs == {
        (("a",), "RSS lon BrakeMin, lat-left BrakeMin"): (0, 2),
        (("b",), str(both)): (1, 1),
        (("a",), str(lon)): (4, 4),
    }
    # the ids each piece had when every cause made its own incident (labels written then)
    first = next(i for i in found if i.objects == ("a",) and i.start_frame == 0)
    assert first.legacy_ids == (
        incident_id("h1", "rss", ("a",), "RSS lon BrakeMinCorrect", 0),
        incident_id("h1", "rss", ("a",), "RSS lon BrakeMin, lat-left BrakeMin", 1),
        incident_id("h1", "rss", ("a",), "RSS lon BrakeMinCorrect", 2),
    )
    assert first.id not in first.legacy_ids


def test_ids_are_stable_and_depend_on_the_drive_content():
    frames = [{"rss": _verdict(("a",))}, {"rss": _verdict(("a", "b"))}]
    first = [i.id for i in _detect(frames)]
    again = [i.id for i in _detect(frames)]
    other = [i.id for i in _detect(frames, drive_hash="h2")]
    assert first == again
    assert len(set(first)) == 2
    assert not set(first) & set(other)
    assert all(i.startswith("rss-00000") for i in first)


def test_times_duration_and_severity_facts():
    frames = [{"rss": SAFE}] + [{"reachsets": _verdict(("a",), margin=m)} for m in (2.0, 0.6, 1.0)]
    (incident,) = _detect(frames)
    assert (incident.start_ns, incident.end_ns) == (T0 + DT, T0 + 3 * DT)
    assert incident.duration_s == pytest.approx(0.2)
    assert incident.severity.worst_margin == 0.6
    assert incident.severity.unsafe_frames == 3
    record = incident.record()
    assert {"id", "engine", "objects", "start_ns", "end_ns", "severity"} <= set(record)
    assert record["severity"]["worst_margin"] == 0.6


def test_min_duration_drops_short_incidents_and_merge_gap_bridges():
    hit = {"rss": _verdict(("a",))}
    frames = [hit, hit, {"rss": SAFE}, hit, {"rss": SAFE}, {"rss": SAFE}, {"rss": SAFE}, hit]
    spans = [(i.start_frame, i.end_frame) for i in _detect(frames)]
    assert sorted(spans) == [(0, 1), (3, 3), (7, 7)]
    longer = _detect(frames, settings=IncidentSettings(min_duration_s=0.1))
    assert [(i.start_frame, i.end_frame) for i in longer] == [(0, 1)]
    bridged = _detect(frames, settings=IncidentSettings(merge_gap_s=0.1))
    assert sorted((i.start_frame, i.end_frame, i.severity.unsafe_frames) for i in bridged) == [
        (0, 3, 3),
        (7, 7, 1),
    ]


def test_without_states_margins_of_different_engines_are_not_compared():
    # no states, so no physical facts: longer first, then earlier start; the reach-set
    # offset [s] of c and the RSS ratio of b are not one unit (docs/review.md, order)
    frames = [
        {"reachsets": _verdict(("a",), margin=1.0), "rss": _verdict(("b",))},
        {"reachsets": _verdict(("a",), margin=1.0), "rss": SAFE},
        {"reachsets": _verdict(("c",), margin=0.5), "rss": SAFE},
    ]
    order = [(i.engine, i.objects[0]) for i in _detect(frames)]
    assert order == [("reachsets", "a"), ("rss", "b"), ("reachsets", "c")]


def test_negative_settings_are_rejected():
    with pytest.raises(ValueError, match="merge_gap_s"):
        IncidentSettings(merge_gap_s=-1.0)
    with pytest.raises(ValueError, match="min_duration_s"):
        IncidentSettings(min_duration_s=math.nan)


@dataclasses.dataclass
class _FramesSeen:
    frames: list[int] = dataclasses.field(default_factory=list)

    def add(self, frame, t_ns, verdict, object_id):
        assert not verdict.is_safe
        self.frames.append(frame)

    def facts(self):
        return {"first_frame_seen": self.frames[0], "frames_seen": len(self.frames)}


def test_registered_fact_collectors_add_severity_facts():
    register_facts("rss", _FramesSeen)
    try:
        frames = [{"rss": SAFE}, {"rss": _verdict(("a",))}, {"rss": _verdict(("a",))}]
        (incident,) = _detect(frames)
    finally:
        unregister_facts("rss", _FramesSeen)
    assert incident.severity.facts == {"first_frame_seen": 1, "frames_seen": 2}
    assert incident.record()["severity"]["frames_seen"] == 2
    (plain,) = _detect(frames)
    assert plain.severity.facts == {}
