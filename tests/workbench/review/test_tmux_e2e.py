"""End to end in a real terminal: ``workbench review`` in tmux with a served viewer.

Review three incidents, quit, start again (it resumes at the fourth), give a verdict and undo
it, quit: the store holds exactly the three verdicts given. Needs tmux; skips without it
(fails under CI=true).
"""

from __future__ import annotations

import json
import os
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from tests.conftest import running_in_ci
from workbench.annotations import LabelStore
from workbench.incidents import drive_content_hash

ROOT = Path(__file__).resolve().parents[3]
LOG = ROOT / "sample_logs" / "hard_braking_lead.mcap"
# the reference reach rules flag more of this drive: four incidents to walk through, one by
# one (--by incident; the events of the engines' overlapping incidents are fewer)
ARGS = [
    "--engines", "rss,reachsets", "--reach-method", "simple", "--reach-rules", "reference",
    "--by", "incident",
]  # fmt: skip
WAIT_S = 180.0
TMUX = shutil.which("tmux")
#: The workbench CLI run by this interpreter (the worktree first on PYTHONPATH).
CLI = [sys.executable, "-c", "from workbench.cli.main import main; main()"]


def _tmux(*args: str) -> str:
    done = subprocess.run(  # noqa: S603 - tmux with fixed arguments
        [TMUX or "tmux", *args],
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _wait_for(session: str, text: str) -> str:
    deadline = time.monotonic() + WAIT_S
    screen = ""
    while time.monotonic() < deadline:
        screen = _tmux("capture-pane", "-p", "-t", session)
        if text in screen:
            return screen
        time.sleep(0.3)
    pytest.fail(f"{text!r} never appeared; screen:\n{screen}")


def _start(session: str, store: Path, home: Path, *, viewer: bool = True) -> None:
    command = [*CLI, "review", str(LOG), *ARGS, "--store", str(store), "--reviewer", "ann"]
    if viewer:
        command += ["--serve", "--grpc-port", str(_free_port()), "--web-port", str(_free_port())]
    env = f"PYTHONPATH={shlex.quote(str(ROOT))} HOME={shlex.quote(str(home))} CI=1"
    run = f"env {env} {shlex.join(command)}"
    shell = f"cd {shlex.quote(str(ROOT))} && {run}; echo REVIEW-EXIT $?; sleep 600"
    # a tmux server whose last session was just killed may still be exiting: the first
    # new-session can fail then; the next one starts a fresh server
    for attempt in range(5):
        try:
            _tmux("new-session", "-d", "-s", session, "-x", "160", "-y", "40", shell)
            break
        except subprocess.CalledProcessError as err:
            if attempt == 4:  # the last attempt
                pytest.fail(f"tmux new-session failed: {err.stderr}")
            time.sleep(0.5)
    _tmux("resize-window", "-t", session, "-x", "160", "-y", "40")


def _keys(session: str, *keys: str) -> None:
    for key in keys:
        _tmux("send-keys", "-t", session, key)
        time.sleep(0.4)


@pytest.fixture
def session_name():
    if TMUX is None:
        if running_in_ci():
            pytest.fail("tmux is required under CI=true")
        pytest.skip("tmux not installed")
    name = f"wb-review-{uuid.uuid4().hex[:8]}"
    yield name
    subprocess.run([TMUX, "kill-session", "-t", name], capture_output=True, check=False)  # noqa: S603


def test_review_quit_resume_undo_in_a_real_terminal(tmp_path, session_name):
    ids = main_json_incidents(tmp_path)  # the order the UI must show (worst first)
    assert len(ids) >= 4
    store = tmp_path / "labels.sqlite"
    home = tmp_path / "home"
    home.mkdir()

    _start(session_name, store, home)
    _wait_for(session_name, f"0 of {len(ids)} reviewed")
    _wait_for(session_name, ids[0])
    _keys(session_name, "c", "f", "u")
    _wait_for(session_name, f"3 of {len(ids)} reviewed")
    _keys(session_name, "q")
    _wait_for(session_name, "REVIEW-EXIT 0")
    _tmux("kill-session", "-t", session_name)

    _start(session_name, store, home)
    screen = _wait_for(session_name, f"3 of {len(ids)} reviewed")
    assert f"{ids[3]}  [unreviewed]" in _wait_for(session_name, f"{ids[3]}  [")
    _keys(session_name, "c")
    _wait_for(session_name, f"4 of {len(ids)} reviewed")
    _keys(session_name, "z")
    screen = _wait_for(session_name, f"3 of {len(ids)} reviewed")
    _keys(session_name, "q")
    _wait_for(session_name, "REVIEW-EXIT 0")
    assert "Traceback" not in screen

    with LabelStore(store) as labels:
        found = labels.labels(drive_content_hash(LOG))
    assert {k: (v.verdict, v.reviewer) for k, v in found.items()} == {
        ids[0]: ("confirmed", "ann"),
        ids[1]: ("false_positive", "ann"),
        ids[2]: ("follow_up", "ann"),
    }


def main_json_incidents(tmp_path: Path) -> list[str]:
    """The incident ids, worst first, from ``workbench incidents --out`` (another process)."""
    out = tmp_path / "incidents.json"
    if not out.exists():
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        subprocess.run(  # noqa: S603 - our own interpreter and CLI
            [*CLI, "incidents", str(LOG), *ARGS,
             "--out", str(out)],
            check=True, cwd=ROOT, env=env, capture_output=True,
        )  # fmt: skip
    return [row["id"] for row in json.loads(out.read_text())]


def _review_pid(session: str) -> int:
    """The review process: the child of the pane's shell."""
    shell = _tmux("display-message", "-p", "-t", session, "#{pane_pid}").strip()
    children = Path(f"/proc/{shell}/task/{shell}/children").read_text().split()
    assert len(children) == 1, children
    return int(children[0])


def test_sigkill_in_the_middle_of_a_session_loses_no_saved_verdict(tmp_path, session_name):
    ids = main_json_incidents(tmp_path)
    store = tmp_path / "labels.sqlite"
    home = tmp_path / "home"
    home.mkdir()
    _start(session_name, store, home, viewer=False)
    _wait_for(session_name, f"0 of {len(ids)} reviewed")
    _keys(session_name, "c", "t", *"kill-test", "Enter", "f")
    _wait_for(session_name, f"2 of {len(ids)} reviewed")
    _keys(session_name, "n", *"typing when killed")  # an unsaved note, mid-edit
    os.kill(_review_pid(session_name), signal.SIGKILL)
    _wait_for(session_name, "REVIEW-EXIT 137")
    with LabelStore(store) as labels:
        found = labels.labels(drive_content_hash(LOG))
    assert {k: (v.verdict, v.tags, v.note) for k, v in found.items()} == {
        ids[0]: ("confirmed", (), ""),
        ids[1]: ("false_positive", ("kill-test",), ""),
    }
