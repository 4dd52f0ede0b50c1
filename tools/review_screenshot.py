"""Screenshot of the review layout at one incident (docs/review.md), by a headless viewer.

    python tools/review_screenshot.py LOG OUT.png [--engines rss,reachsets] [--rank 0]

Does what ``workbench review LOG --connect URL`` does against a headless viewer started on
127.0.0.1 (Vulkan: Mesa lavapipe): streams the drive's review recording (scene, engine lanes,
incident lanes and markers) to it and sends the incident's blueprint (time panel selecting
its frames, incidents tab active); then puts the time cursor 10 frames into the incident
and saves the screenshot. Prints the incident.
"""

from __future__ import annotations

import argparse
import os
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import rerun_cli  # type: ignore[import-untyped]
from rerun.experimental import ViewerClient

from workbench.drives import open_log
from workbench.engines import EngineSettings, build_runners
from workbench.incidents import IncidentRequest, find_incidents
from workbench.review.viewer import RerunLink
from workbench.viewer.replay import APPLICATION_ID, recording_id, replay_drive


def _port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _viewer(port: int, deadline: float) -> ViewerClient:
    while True:
        try:
            viewer = ViewerClient.connect(f"rerun+http://127.0.0.1:{port}/proxy")
            viewer.get_state()
        except Exception:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.3)
        else:
            return viewer


def main() -> None:
    """Parse the arguments, stream the review recording, take the screenshot."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("log", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("--engines", default="rss,reachsets")
    parser.add_argument("--rank", type=int, default=0, help="0 = the worst incident")
    parser.add_argument("--size", default="1600x900")
    args = parser.parse_args()
    engines = tuple(args.engines.split(","))
    report = find_incidents(IncidentRequest(args.log, engines=engines))
    incident = report.incidents[args.rank]
    print(f"{incident.id}: {incident.engine} {incident.cause} object {incident.objects} "
          f"frames {incident.start_frame}-{incident.end_frame}")  # fmt: skip
    port = _port()
    url = f"rerun+http://127.0.0.1:{port}/proxy"
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "CI": "1", "RUST_LOG": "error"}
        env.setdefault("XDG_RUNTIME_DIR", tmp)
        viewer_bin = Path(rerun_cli.__file__).parent / "rerun"
        cmd = [str(viewer_bin), "--headless", "--renderer", "vulkan", "--bind", "127.0.0.1"]
        cmd += ["--port", str(port), "--window-size", args.size, "--hide-welcome-screen"]
        quiet = subprocess.DEVNULL
        proc = subprocess.Popen(cmd, env=env, stdout=quiet, stderr=quiet)  # noqa: S603
        try:
            viewer = _viewer(port, time.monotonic() + 60)
            drive = open_log(args.log, map_path=None, profile=None, ego_id=None)
            try:
                first = next(iter(drive.frames()))
                settings = EngineSettings(full_geometry=True)
                runners = build_runners(list(engines), drive.lane_map, settings)
                replay_drive(drive, connect=url, engines=runners)
                rid = recording_id(drive, None, None)
            finally:
                drive.close()
            link = RerunLink(
                url,
                application_id=APPLICATION_ID,
                recording_id=rid,
                ego_start_m=(first.ego.x_m, first.ego.y_m),
                engines=engines,
                ego_at_m=report.ego_at_start_m,
            )
            link.show(incident)
            link.close()
            time.sleep(2.0)
            frame = min(incident.start_frame + 10, incident.end_frame)
            viewer.set_time("frame", sequence=frame, play_state="paused")
            time.sleep(2.0)
            args.out.parent.mkdir(parents=True, exist_ok=True)
            viewer.save_screenshot(str(args.out))
        finally:
            proc.terminate()
            proc.wait(timeout=20)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
