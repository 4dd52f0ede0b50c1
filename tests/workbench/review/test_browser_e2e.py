"""End to end in a real browser: ``workbench review --serve`` in tmux, the web viewer in Chromium.

The page loads, the recording arrives, and the viewer's time cursor follows the review loop:
on the first incident, then after ``j`` (next) on a later one, each at its worst frame, read
back from the viewer (``viewer_state``) and from the page address (``#when=frame@N``).

Needs Debian's ``chromium`` (``.ci/run`` installs it), the ``playwright`` package driving it
(no browser download) and tmux; skips only where they are missing, and fails under CI=true.
"""

from __future__ import annotations

import shlex
import time
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import running_in_ci
from tests.workbench.review.test_tmux_e2e import (
    ARGS,
    CLI,
    LOG,
    ROOT,
    _free_port,
    _keys,
    _tmux,
    _wait_for,
    session_name,
)
from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, find_incidents
from workbench.review.viewer import worst_frame

__all__ = ["session_name"]

CHROMIUM = Path("/usr/bin/chromium")
#: Software WebGL on two cores: the page and the recording take tens of seconds.
LOAD_S = 300.0
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
]
#: The viewer's state: a ``GetStateResponse`` as protobuf bytes (a list of ints here).
_STATE_JS = """async () => {
  const viewer = window._handle;
  if (!viewer || !viewer.viewer_state) return null;
  return Array.from(await viewer.viewer_state());
}"""


def _need(reason: str) -> None:
    if running_in_ci():
        pytest.fail(reason)
    pytest.skip(reason)


@pytest.fixture
def browser(tmp_path):
    if not CHROMIUM.is_file():
        _need(f"no browser at {CHROMIUM} (apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright  # noqa: PLC0415 - optional
    except ImportError:
        _need("the playwright package is not installed (pip install -e '.[test]')")
    with sync_playwright() as pw:
        launched = pw.chromium.launch_persistent_context(
            tmp_path / "chromium",  # a fresh profile
            executable_path=str(CHROMIUM),
            headless=True,
            args=FLAGS,
            viewport={"width": 1600, "height": 900},
        )
        try:
            yield launched
        finally:
            launched.close()


def _fields(data: bytes) -> list[tuple[int, int | bytes]]:
    """The fields of one protobuf message: ``(number, varint or bytes)``, in order."""
    found: list[tuple[int, int | bytes]] = []
    pos = 0

    def varint() -> int:
        nonlocal pos
        value, shift = 0, 0
        while True:
            byte = data[pos]
            pos += 1
            value |= (byte & 0x7F) << shift
            shift += 7
            if byte < 0x80:
                return value

    while pos < len(data):
        tag = varint()
        number, wire = tag >> 3, tag & 7
        if wire == 0:
            found.append((number, varint()))
        elif wire == 2:
            size = varint()
            found.append((number, data[pos : pos + size]))
            pos += size
        else:
            msg = f"unexpected wire type {wire}"
            raise ValueError(msg)
    return found


def _sub(fields: list[tuple[int, int | bytes]], number: int) -> list[bytes]:
    return [v for n, v in fields if n == number and isinstance(v, bytes)]


def _times(state: list[int] | None) -> list[tuple[str, int]]:
    """``(timeline, time)`` of each recording's time cursor in a ``GetStateResponse``.

    ``recordings = 3 {current_time = 3 {timeline = 1 {name = 1}, time = 3 {time = 1}}}``
    (rerun 0.41's ``viewer_control.proto``).
    """
    found = []
    for recording in _sub(_fields(bytes(state or [])), 3):
        for cursor in _sub(_fields(recording), 3):
            parts = _fields(cursor)
            names = [_sub(_fields(t), 1) for t in _sub(parts, 1)]
            times = [[v for n, v in _fields(t) if n == 1] for t in _sub(parts, 3)]
            name = names[0][0].decode() if names and names[0] else ""
            value = times[0][0] if times and times[0] else 0
            found.append((name, int(value)))
    return found


def _wait_cursor(page: Any, frame: int) -> tuple[list[tuple[str, int]], str]:
    deadline = time.monotonic() + LOAD_S
    seen: list[tuple[str, int]] = []
    while time.monotonic() < deadline:
        seen = _times(page.evaluate(_STATE_JS))
        if ("frame", frame) in seen and page.url.endswith(f"#when=frame@{frame}"):
            break
        time.sleep(1.0)
    return seen, page.url


def test_the_web_viewer_follows_the_review_cursor(tmp_path, session_name, browser):
    request = IncidentRequest(LOG, engines=("rss", "reachsets"), options=engine_options(
        {"reach_method": "simple", "reach_rules": "reference"}))  # fmt: skip
    incidents = find_incidents(request).incidents
    frames = [worst_frame(i) for i in incidents]
    # the first incident further down the list whose worst frame is another one
    steps = next(k for k, f in enumerate(frames) if f != frames[0])
    wanted = [frames[0], frames[steps]]
    grpc, web = _free_port(), _free_port()
    home = tmp_path / "home"
    home.mkdir()
    command = [*CLI, "review", str(LOG), *ARGS, "--store", str(tmp_path / "labels.sqlite")]
    command += ["--reviewer", "ann", "--serve", "--grpc-port", str(grpc), "--web-port", str(web)]
    env = f"PYTHONPATH={shlex.quote(str(ROOT))} HOME={shlex.quote(str(home))} CI=1"
    shell = f"cd {shlex.quote(str(ROOT))} && env {env} {shlex.join(command)}; sleep 600"
    _tmux("new-session", "-d", "-s", session_name, "-x", "160", "-y", "40", shell)
    _wait_for(session_name, f"0 of {len(incidents)} reviewed")

    page = browser.new_page()
    proxy = f"rerun%2Bhttp%3A%2F%2F127.0.0.1%3A{grpc}%2Fproxy"
    page.goto(f"http://127.0.0.1:{web}/?url={proxy}", timeout=LOAD_S * 1000)
    page.wait_for_function("() => window._handle !== undefined", timeout=LOAD_S * 1000)

    seen, url = _wait_cursor(page, wanted[0])
    assert ("frame", wanted[0]) in seen, (seen, url)  # the recording arrived, cursor on it
    assert url.endswith(f"#when=frame@{wanted[0]}")
    _keys(session_name, *["j"] * steps)
    seen, url = _wait_cursor(page, wanted[1])
    assert ("frame", wanted[1]) in seen, (seen, url)
    assert url.endswith(f"#when=frame@{wanted[1]}")
