"""A clip's ``.rrd`` finds its incident again under the drive's id (engine, objects, start).

The clips are cut from one pass over the drive, so each clip's engines are warm from the
drive's start and its frames carry the drive's numbers (a fixed 10 s lead-in numbered the
frames of a CommonRoad window twice: US101-23's ``rss-000135`` came out at frame 140).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.workbench.engines.helpers import rrd_states
from workbench.engines import names
from workbench.engines.registry import engine_options
from workbench.export import Selection, plan_clips
from workbench.export.recordings import clip_incident
from workbench.export.views import write_recordings
from workbench.incidents import Incident, IncidentRequest, Severity, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
MARGIN_NS = 3_000_000_000


def _lane_start(rrd: Path, incident: Incident) -> int | None:
    """First frame of the incident's lane in the clip's recording (``None``: no such lane)."""
    states = rrd_states(rrd, f"/incidents/lanes/{incident.engine}/{incident.id}")
    return min(states) if states else None


def _check_clips(request: IncidentRequest, out: Path, ids: tuple[str, ...] = ()) -> int:
    report = find_incidents(request)
    selection = Selection(ids=ids) if ids else Selection(all=True)
    plans = plan_clips(report, {}, selection, MARGIN_NS)
    written = write_recordings(report, plans, out, request)
    assert set(written) == {p.stem for p in plans}
    for plan in plans:
        incident = plan.incident
        assert incident is not None
        rrd, view = written[plan.stem]
        assert _lane_start(rrd, incident) == incident.start_frame, (plan.stem, incident.id)
        assert view.boxes_m is not None, f"{incident.id}: no box at its worst frame"
    return len(plans)


@pytest.mark.parametrize("log", sorted(p.name for p in SAMPLES.glob("*.mcap")))
def test_every_clip_of_a_sample_finds_its_incident_under_the_drive_id(log, tmp_path):
    request = IncidentRequest(
        SAMPLES / log, engines=tuple(names()), options=engine_options({"reach_method": "simple"})
    )
    assert _check_clips(request, tmp_path) > 0


def test_us101_23_rss_000135_in_its_clip(external_dir, tmp_path):
    log = external_dir / "commonroad_ngsim" / "USA_US101-23_1_T-1.xml"
    request = IncidentRequest(log, engines=("rss",))
    found = [i.id for i in find_incidents(request).incidents if i.id.startswith("rss-000135-")]
    assert len(found) == 1
    assert _check_clips(request, tmp_path, ids=(found[0],)) == 1


def _incident(engine: str, objects: tuple[str, ...], frames: tuple[int, int]) -> Incident:
    return Incident(
        id=f"{engine}-{frames[0]:06d}-x",
        engine=engine,
        objects=objects,
        cause="c",
        start_frame=frames[0],
        end_frame=frames[1],
        start_ns=frames[0],
        end_ns=frames[1],
        severity=Severity(0.0, frames[1] - frames[0] + 1, 0.1),
    )


def test_the_clip_incident_is_matched_by_engine_objects_and_overlap_not_by_id():
    drive = _incident("rss", ("7",), (10, 14))
    same_elsewhere = _incident("rss", ("7",), (12, 20))  # another id (start), same danger
    other_object = _incident("rss", ("8",), (10, 14))
    other_engine = _incident("reachsets", ("7",), (10, 14))
    later = _incident("rss", ("7",), (30, 31))
    found = [other_object, other_engine, later, same_elsewhere]
    assert clip_incident(found, drive) is same_elsewhere
    assert clip_incident([other_object, other_engine, later], drive) is None
    exact = _incident("rss", ("7",), (10, 14))
    assert clip_incident([same_elsewhere, exact], drive) is exact
