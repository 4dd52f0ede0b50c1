"""The review loop moves a live viewer: a headless viewer on 127.0.0.1, driven as review does.

Needs a Vulkan driver (Debian: mesa-vulkan-drivers); skips without one, fails under CI=true.
"""

from __future__ import annotations

import os
import socket
import subprocess
import time
from pathlib import Path

import pytest
import rerun_cli  # type: ignore[import-untyped]
from rerun.experimental import ViewerClient

from tests.conftest import running_in_ci
from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, find_incidents
from workbench.review.viewer import RerunLink, ViewerCursor, worst_frame
from workbench.viewer.replay import APPLICATION_ID, recording_id, replay_drive

ROOT = Path(__file__).resolve().parents[3]
ICD_DIR = Path("/usr/share/vulkan/icd.d")
ENGINES = ("rss", "reachsets")


@pytest.fixture
def viewer_url(tmp_path):
    if not (ICD_DIR.is_dir() and any(ICD_DIR.glob("*.json"))):
        reason = f"no Vulkan driver in {ICD_DIR} (apt-get install mesa-vulkan-drivers)"
        if running_in_ci():
            pytest.fail(reason)
        pytest.skip(reason)
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    env = {**os.environ, "CI": "1", "RUST_LOG": "error", "XDG_RUNTIME_DIR": str(tmp_path)}
    cmd = [str(Path(rerun_cli.__file__).parent / "rerun"), "--headless", "--renderer", "vulkan"]
    cmd += ["--bind", "127.0.0.1", "--port", str(port), "--hide-welcome-screen"]
    quiet = subprocess.DEVNULL
    proc = subprocess.Popen(cmd, env=env, stdout=quiet, stderr=quiet)  # noqa: S603
    try:
        yield f"rerun+http://127.0.0.1:{port}/proxy"
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def _connect(url: str) -> ViewerClient:
    deadline = time.monotonic() + 60
    while True:
        try:
            client = ViewerClient.connect(url)
            client.get_state()
        except Exception:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.3)
        else:
            return client


def _selection(client: ViewerClient, want: dict[str, int]) -> dict[str, int]:
    """The viewer's time selection, once it shows ``want`` (or the last one seen)."""
    deadline = time.monotonic() + 30
    seen: dict[str, int] = {}
    while time.monotonic() < deadline:
        panel = client.get_blueprint().blueprint.get("/time_panel", {})
        seen = panel.get("TimePanelBlueprint", {}).get("time_selection", {})
        if seen == want:
            break
        time.sleep(0.3)
    return seen


def _cursor(client: ViewerClient, frame: int) -> tuple[str | None, int | None]:
    """The recording's timeline and time, once at ``frame`` (or the last seen)."""
    deadline = time.monotonic() + 30
    seen: tuple[str | None, int | None] = (None, None)
    while time.monotonic() < deadline:
        recordings = client.get_state().recordings
        if recordings:
            seen = (recordings[0].current_timeline, recordings[0].current_time)
            if seen == ("frame", frame):
                break
        time.sleep(0.3)
    return seen


def test_each_incident_shown_selects_its_frames_in_the_live_recording(viewer_url):
    log = ROOT / "sample_logs" / "hard_braking_lead.mcap"
    request = IncidentRequest(
        log,
        engines=ENGINES,
        options=engine_options({"reach_method": "simple", "reach_rules": "reference"}),
    )
    report = find_incidents(request)
    client = _connect(viewer_url)
    drive = request.open_drive()
    try:
        runners, ego = request.engines_for(drive, full_geometry=True)  # the report's settings
        summary = replay_drive(drive, connect=viewer_url, engines=runners, ego_size=ego)
        rid = recording_id(drive, None, None)
    finally:
        drive.close()
    assert [i.id for i in summary.incidents] == [i.id for i in report.incidents]
    link = RerunLink(
        viewer_url,
        application_id=APPLICATION_ID,
        recording_id=rid,
        ego_start_m=None,
        engines=ENGINES,
    )
    try:
        moves = [report.incidents[0], report.incidents[3], report.incidents[0]]
        assert worst_frame(moves[0]) != worst_frame(moves[1])  # the cursor must really move
        for incident in moves:
            link.show(incident)
            link.recording.flush()
            want = {"min": incident.start_frame, "max": incident.end_frame}
            assert _selection(client, want) == want
            # the time cursor is on the incident's worst frame, inside its window
            timeline, at = _cursor(client, worst_frame(incident))
            assert (timeline, at) == ("frame", worst_frame(incident))
            assert incident.start_frame <= worst_frame(incident) <= incident.end_frame
            assert isinstance(link.cursor, ViewerCursor)
            assert link.cursor.error is None
    finally:
        link.close()
    state = client.get_state()
    # the link's stream joined the replay's recording: one recording, the replay's id
    assert [str(r.store_id).rsplit(":", 1)[-1] for r in state.recordings] == [rid]
