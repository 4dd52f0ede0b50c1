"""The frame the review viewer shows: the incident's worst, found again frame by frame."""

import dataclasses
from pathlib import Path

from tests.workbench.review.helpers import incident
from workbench.driver.run import DriveRun
from workbench.engines.rss.verdict import RssVerdict
from workbench.incidents import IncidentRequest, find_incidents
from workbench.replay.highlight import CulpritBoxes
from workbench.replay.incidents import short_labels
from workbench.review.viewer import worst_frame

ROOT = Path(__file__).resolve().parents[3]
LOG = ROOT / "sample_logs" / "highway_cut_in.mcap"


def test_without_a_worst_frame_the_viewer_shows_the_first():
    first = incident(1, 0.0)
    assert worst_frame(first) == first.start_frame
    assert worst_frame(dataclasses.replace(first, worst_frame=first.start_frame + 2)) == 12
    # a worst frame outside the window (stale data) is not trusted
    assert worst_frame(dataclasses.replace(first, worst_frame=999)) == first.start_frame


def test_rss_worst_frame_is_the_smallest_distance_ratio_and_the_replay_knows_where_it_was():
    request = IncidentRequest(LOG, engines=("rss",))
    report = find_incidents(request)
    assert report.incidents
    drive = request.open_drive()
    ratios: dict[tuple[int, str], float] = {}
    boxes = CulpritBoxes()
    try:
        runners, ego = request.engines_for(drive)
        for chunk in DriveRun(drive, runners, ego_size=ego):
            boxes.add_chunk(chunk)
            for frame, verdict in zip(chunk.frames, chunk.verdicts["rss"], strict=True):
                if verdict.is_safe or not isinstance(verdict, RssVerdict):
                    continue
                for obj, facts in verdict.severity().items():
                    ratios[frame.index, obj] = facts.distance_ratio
    finally:
        drive.close()
    for found in report.incidents:
        (obj,) = found.objects
        window = [
            (ratio, frame)
            for (frame, o), ratio in ratios.items()
            if o == obj and found.start_frame <= frame <= found.end_frame
        ]
        best = min(window)  # smallest ratio, then the earliest frame
        assert found.worst_frame == best[1], found.id
        ego_m, objects_m = boxes.at(worst_frame(found), found.objects)
        assert ego_m is not None
        assert len(objects_m) == 1  # the camera frames the incident's object there

    lights = {h.path: h for h in boxes.layout(report.incidents, short_labels(report.incidents),
                                               report.frame_times)}  # fmt: skip
    for found in report.incidents:
        light = lights[f"world/incidents/rss/{found.id}"]
        shown = light.frames[light.counts > 0]
        assert shown.min() == found.start_frame
        assert shown.max() == found.end_frame
        assert set(light.labels.tolist()) == {short_labels(report.incidents)[found.objects[0]]}
        assert int(light.counts.sum()) == len(light.labels)
        if found.end_frame < report.frame_times[-1][0]:  # cleared after the incident
            assert light.counts[-1] == 0
            assert light.frames[-1] > found.end_frame
