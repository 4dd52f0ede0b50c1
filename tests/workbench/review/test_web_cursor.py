"""The web viewer's page relay: files passed through, the page gets the cursor script."""

import json
import socket
import threading
import urllib.error
import urllib.request
from functools import partial
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer

import pytest

from workbench.viewer.web_cursor import CURSOR_PATH, WebCursor


def _port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _get(url: str) -> tuple[int, bytes, str]:
    with urllib.request.urlopen(url, timeout=10) as reply:  # noqa: S310 - our own 127.0.0.1 server
        return reply.status, reply.read(), reply.headers.get("Content-Type", "")


@pytest.fixture
def relay(tmp_path):
    (tmp_path / "index.html").write_text("<html><body><p>viewer</p></body></html>")
    (tmp_path / "app.wasm").write_bytes(b"\0asm\1\0\0\0")
    handler = partial(SimpleHTTPRequestHandler, directory=str(tmp_path))
    upstream = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=upstream.serve_forever, daemon=True).start()
    cursor = WebCursor()
    port = _port()
    cursor.start("127.0.0.1", port, upstream.server_address[1])
    try:
        yield cursor, f"http://127.0.0.1:{port}"
    finally:
        cursor.stop()
        upstream.shutdown()
        upstream.server_close()


def test_the_page_gets_the_script_and_other_files_pass_through_unchanged(relay):
    _, base = relay
    status, page, _ = _get(base + "/?url=rerun%2Bhttp%3A%2F%2F127.0.0.1%3A1%2Fproxy")
    assert status == 200
    assert (
        page
        == b'<html><body><p>viewer</p><script src="/workbench-cursor.js"></script></body></html>'
    )
    assert _get(base + "/app.wasm")[1] == b"\0asm\1\0\0\0"
    status, script, kind = _get(base + "/workbench-cursor.js")
    assert (status, kind) == (200, "text/javascript")
    assert b"viewer_control" in script
    assert CURSOR_PATH.encode() in script
    with pytest.raises(urllib.error.HTTPError) as missing:
        _get(base + "/nothing-here.js")
    assert missing.value.code == 404


def test_each_move_is_a_new_cursor_for_the_page(relay):
    cursor, base = relay
    assert json.loads(_get(base + CURSOR_PATH)[1]) == {"seq": 0, "timeline": "frame", "time": 0}
    cursor.move("frame", 78)
    cursor.move(
        "frame", 78
    )  # the same frame again is still a move (the reviewer may have scrolled)
    assert json.loads(_get(base + CURSOR_PATH)[1]) == {"seq": 2, "timeline": "frame", "time": 78}
