"""Runners carry their spec: the sinks and the incident detector use the chunk's specs."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

from tests.workbench.fakes import FakeDrive
from workbench.driver import DriveRun
from workbench.engines.base import BoundRunner, VerdictSummary
from workbench.engines.registry import build_runners, engine, find
from workbench.incidents import IncidentDetector
from workbench.sinks.per_frame import frame_records

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.records import Frame


class _Unsafe:
    """Rates every frame unsafe for object ``a``, the cause alternating between two texts."""

    name = "unlisted"

    def step_many(self, frames: Sequence[Frame]) -> list[VerdictSummary]:
        return [VerdictSummary(False, ("a",), f"near {f.index % 2}", 0.5) for f in frames]


def _record(verdict: Any) -> dict[str, Any]:
    return {"cause": verdict.cause}


def _unlisted_spec() -> Any:
    """A spec under a name the registry does not know, with its own record and cause join."""
    return dataclasses.replace(
        engine("reachsets"),
        name="unlisted",
        record=_record,
        join_causes=lambda causes: " + ".join(sorted({str(c) for c in causes})),
    )


def test_build_runners_binds_each_runner_to_its_engines_spec():
    drive = FakeDrive(n_frames=3)
    runners = build_runners(["rss", "reachsets"], drive.lane_map)
    assert [(r.name, r.spec) for r in runners] == [
        ("rss", engine("rss")),
        ("reachsets", engine("reachsets")),
    ]
    (chunk,) = DriveRun(drive, runners)
    assert chunk.specs == {"rss": engine("rss"), "reachsets": engine("reachsets")}
    assert [len(v) for v in chunk.verdicts.values()] == [3, 3]


def test_sinks_and_detector_use_the_chunks_spec_not_the_registry():
    assert find("unlisted") is None
    drive = FakeDrive(n_frames=4)
    (chunk,) = DriveRun(drive, [BoundRunner(_unlisted_spec(), _Unsafe())])
    records = frame_records(chunk)
    assert [r["unlisted"] for r in records] == [{"cause": f"near {k % 2}"} for k in range(4)]
    detector = IncidentDetector("h")
    detector.add_chunk(chunk)
    (incident,) = detector.incidents()  # joined: one incident although the cause alternates
    assert (incident.engine, incident.objects, incident.cause) == (
        "unlisted",
        ("a",),
        "near 0 + near 1",
    )
    assert (incident.start_frame, incident.end_frame) == (0, 3)


def test_a_part_of_a_chunk_keeps_its_specs():
    drive = FakeDrive(n_frames=5)
    (chunk,) = DriveRun(drive, [BoundRunner(_unlisted_spec(), _Unsafe())])
    part = chunk.part(1, 3)
    assert [f.index for f in part.frames] == [1, 2]
    assert [v.cause for v in part.verdicts["unlisted"]] == ["near 1", "near 0"]
    assert part.specs is chunk.specs
