"""``workbench review`` with a viewer evaluates the drive once: each engine once per frame."""

from __future__ import annotations

import socket
from collections import Counter

import rerun as rr

from tests.workbench.cli_runs import run_workbench
from workbench.driver import run
from workbench.engines import names
from workbench.incidents import IncidentRequest, find_incidents
from workbench.review import loop
from workbench.viewer.outputs import Destination

SCENARIO = "USA_Peach-3_1_T-1.xml"


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def test_review_in_a_viewer_runs_each_engine_once_per_frame(external_dir, tmp_path, monkeypatch):
    log = external_dir / "commonroad_ngsim" / SCENARIO
    calls: Counter[tuple[str, int]] = Counter()
    evaluate = run.evaluate_chunk

    def counted(frames, runners):
        calls.update((r.name, f.index) for r in runners for f in frames)
        return evaluate(frames, runners)

    monkeypatch.setattr(run, "evaluate_chunk", counted)
    seen = []
    monkeypatch.setattr(loop, "run_review", lambda session, viewer=None: seen.append(viewer))
    sink = rr.RecordingStream("one-pass-test")  # an in-process gRPC proxy stands in for a viewer
    url = rr.serve_grpc(grpc_port=_free_port(), recording=sink)
    store = tmp_path / "labels.sqlite"
    assert run_workbench(["review", str(log), "--connect", url, "--store", str(store)]) == 0
    (viewer,) = seen
    assert viewer is not None  # the UI ran after the pass, with the viewer link

    frames = {index for _, index in calls}
    assert frames == set(range(max(frames) + 1))
    assert set(calls) == {(name, index) for name in names() for index in frames}
    assert set(calls.values()) == {1}, "an engine evaluated a frame more than once"

    # the pass found what `workbench incidents` finds (same ids, same frames)
    counted_calls = sum(calls.values())
    report = find_incidents(IncidentRequest(log, engines=tuple(names())))
    assert sum(calls.values()) == 2 * counted_calls  # this check's own pass, once more
    assert {index for index, _ in report.frame_times} == frames
    assert report.incidents


def test_the_viewer_pass_finds_the_same_incidents_as_the_command(external_dir):
    log = external_dir / "commonroad_ngsim" / SCENARIO
    request = IncidentRequest(log, engines=tuple(names()))
    sink = rr.RecordingStream("one-pass-test")  # an in-process gRPC proxy stands in for a viewer
    url = rr.serve_grpc(grpc_port=_free_port(), recording=sink)
    with loop.replayed(request, Destination(connect=url)) as live:
        found = live.report
        labels = live.labels
    expected = find_incidents(request)
    assert found.incidents
    assert [i.id for i in found.incidents] == [i.id for i in expected.incidents]
    assert [i.severity for i in found.incidents] == [i.severity for i in expected.incidents]
    assert found.frame_times == expected.frame_times
    assert found.drive_hash == expected.drive_hash
    assert found.settings == expected.settings
    assert dict(found.objects_at_start_m) == dict(expected.objects_at_start_m)
    # the viewer's short labels name every incident object: the review table shows them so
    assert {o for i in found.incidents for o in i.objects} <= set(labels)
