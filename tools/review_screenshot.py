"""Screenshot of the review layout at one incident (docs/review.md), by a headless viewer.

    python tools/review_screenshot.py LOG OUT.png [--engines rss,reachsets] [--rank 0]

Does what ``workbench review LOG --connect URL`` does against a headless viewer started on
127.0.0.1 (``workbench.viewer.screenshot.headless_viewer``; Vulkan: Mesa lavapipe): streams
the drive's review recording (scene, engine lanes, incident lanes and markers) to it and sends
the incident's blueprint (time panel selecting its frames, incidents tab active, the camera
framing the ego and the incident's objects, which are highlighted, the others dimmed) and
moves the time cursor to the incident's worst frame, as review does; then saves the
screenshot. Prints the incident.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from workbench.incidents import IncidentRequest, find_incidents
from workbench.replay.highlight import CulpritBoxes
from workbench.review.viewer import RerunLink, worst_frame
from workbench.viewer.replay import APPLICATION_ID, recording_id, replay_drive
from workbench.viewer.screenshot import headless_viewer


def main() -> None:
    """Parse the arguments, stream the review recording, take the screenshot."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("log", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("--engines", default="rss,reachsets")
    parser.add_argument("--rank", type=int, default=0, help="0 = the worst incident")
    parser.add_argument("--incident", help="this incident id instead of --rank")
    parser.add_argument("--size", default="1600x900")
    args = parser.parse_args()
    request = IncidentRequest(args.log, engines=tuple(args.engines.split(",")))
    report = find_incidents(request)
    incident = report.find(args.incident) if args.incident else report.incidents[args.rank]
    if incident is None:
        parser.error(f"{args.log}: no incident {args.incident}")
    # fmt: off
    print(f"{incident.id}: {incident.engine} {incident.cause} object {incident.objects} "
          f"frames {incident.start_frame}-{incident.end_frame}, worst {worst_frame(incident)}",
    )
    # fmt: on
    width, height = (int(v) for v in args.size.split("x"))
    with headless_viewer((width, height)) as viewer:
        url = viewer.url
        drive = request.open_drive()
        try:
            first = next(iter(drive.frames()))
            runners, ego = request.engines_for(drive, full_geometry=True)
            positions = CulpritBoxes()
            replay_drive(drive, connect=url, engines=runners, ego_size=ego, culprits=positions)
            rid = recording_id(drive, None, None)
        finally:
            drive.close()
        link = RerunLink(
            url,
            application_id=APPLICATION_ID,
            recording_id=rid,
            ego_start_m=(first.ego.x_m, first.ego.y_m),
            engines=request.engines,
            ego_at_m=report.ego_at_start_m,
            objects_at_m=report.objects_at_start_m,
            positions=positions,
        )
        link.show(incident)
        link.close()
        time.sleep(3.0)
        args.out.parent.mkdir(parents=True, exist_ok=True)
        viewer.save_screenshot(str(args.out.resolve()))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
