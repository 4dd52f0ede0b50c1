"""Moves the time cursor of the web viewer a reviewer has open in a browser.

A native viewer takes ``ViewerControl`` requests on its gRPC port; the gRPC proxy that
``rerun --serve-web`` runs does not (rerun-sdk 0.41 answers ``Unimplemented``): the viewer
lives in the browser. So the web page is served from here, in front of Rerun's own web
server: every file is passed through, and the page gets one small script that polls
``/workbench-cursor`` and hands a changed cursor to the viewer (``window._handle`` of
Rerun's ``index.html``: its ``viewer_control``, the ``ViewerControlRequest`` a native viewer
takes, as protobuf bytes), then writes it into the page address as ``#when=frame@N``.

::

    browser ──> 127.0.0.1:WEB (this relay) ──> 127.0.0.1:internal (rerun --serve-web)
      └── polls /workbench-cursor <── TimeCursor.move() from the review loop

The relay binds the address the server was asked to bind (127.0.0.1 by default) and only
reads from Rerun's server on this machine.
"""

from __future__ import annotations

import contextlib
import threading
import urllib.error
import urllib.request
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import TYPE_CHECKING, ClassVar
from urllib.parse import parse_qs, urlsplit

from workbench.outputs import json_text

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = ["CURSOR_PATH", "WebCursor"]

#: Where the page reads the cursor: ``{"seq": n, "timeline": ..., "time": ...}``.
CURSOR_PATH = "/workbench-cursor"
_SCRIPT_PATH = "/workbench-cursor.js"
#: How often the page asks for the cursor [ms].
_POLL_MS = 300

_SCRIPT = """// rss-workbench: follow the review loop's time cursor (workbench/viewer/web_cursor.py)
(() => {
  // The web viewer's viewer_control takes a ViewerControlRequest as protobuf bytes:
  // set_time_cursor = 6 {timeline = 2 {name = 1}, time = 3 {time = 1}, play_state = 5}.
  const varint = (n) => {
    let v = BigInt(n);
    if (v < 0n) v += 1n << 64n;
    const out = [];
    while (v >= 0x80n) { out.push(Number(v & 0x7fn) | 0x80); v >>= 7n; }
    out.push(Number(v));
    return out;
  };
  const message = (field, bytes) => [(field << 3) | 2, ...varint(bytes.length), ...bytes];
  const seek = (timeline, time) => {
    const name = message(1, [...new TextEncoder().encode(timeline)]);
    const when = [(1 << 3) | 0, ...varint(time)];
    const paused = [(5 << 3) | 0, 1];
    return new Uint8Array(message(6, [...message(2, name), ...message(3, when), ...paused]));
  };
  let seen = 0;
  async function tick() {
    try {
      const reply = await fetch("%(path)s", { cache: "no-store" });
      const cursor = await reply.json();
      const viewer = window._handle;
      if (cursor.seq > seen && viewer && viewer.viewer_control) {
        await viewer.viewer_control(seek(cursor.timeline, cursor.time));
        if (seen === 0) await fetch("%(path)s?applied=" + cursor.seq, { cache: "no-store" });
        seen = cursor.seq;
        const when = "#when=" + cursor.timeline + "@" + cursor.time;
        history.replaceState(history.state, "", location.pathname + location.search + when);
      }
    } catch (err) {
      // the viewer is still loading the recording: try again
    }
    setTimeout(tick, %(poll)d);
  }
  tick();
})();
""" % {"path": CURSOR_PATH, "poll": _POLL_MS}  # noqa: UP031 - braces of the script

_TAG = f'<script src="{_SCRIPT_PATH}"></script>'.encode()


class WebCursor:
    """The web viewer's page, served in front of Rerun's, and the cursor it follows."""

    def __init__(self) -> None:
        """No cursor yet (``seq`` 0: the page leaves the viewer's time alone)."""
        self._lock = threading.Lock()
        self._cursor: dict[str, object] = {"seq": 0, "timeline": "frame", "time": 0}
        self._server: ThreadingHTTPServer | None = None
        #: Called once, when a page first put the viewer's cursor (its recording has loaded):
        #: the review re-sends the incident's blueprint, which a page that connected later
        #: got before its data and showed without the incident's window.
        self.on_loaded: Callable[[], None] | None = None
        self._loaded = False

    def loaded(self) -> None:
        """A page reports its first cursor put: call :attr:`on_loaded` the first time."""
        with self._lock:
            first, self._loaded = not self._loaded, True
        if first and self.on_loaded is not None:
            self.on_loaded()

    @property
    def cursor(self) -> dict[str, object]:
        """The cursor the page follows (a copy)."""
        with self._lock:
            return dict(self._cursor)

    def move(self, timeline: str, sequence: int) -> None:
        """Ask the page to put the viewer's cursor at ``sequence`` on ``timeline``, paused."""
        with self._lock:
            seq = int(str(self._cursor["seq"])) + 1
            self._cursor = {"seq": seq, "timeline": timeline, "time": int(sequence)}

    def start(self, bind: str, port: int, upstream_port: int) -> None:
        """Serve on ``bind:port``, passing every file through from 127.0.0.1:``upstream_port``.

        Raises:
            OSError: The port cannot be bound.
        """
        relay = self

        class Handler(_Handler):
            owner: ClassVar[WebCursor] = relay
            upstream: ClassVar[str] = f"http://127.0.0.1:{upstream_port}"

        self._server = ThreadingHTTPServer((bind, port), Handler)
        self._server.daemon_threads = True
        threading.Thread(target=self._server.serve_forever, daemon=True).start()

    def stop(self) -> None:
        """Stop serving."""
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None


class _Handler(BaseHTTPRequestHandler):
    owner: ClassVar[WebCursor]
    upstream: ClassVar[str]

    def log_message(self, format: str, *args: object) -> None:  # noqa: A002 - base signature
        """Quiet: the review UI owns the terminal."""

    def _reply(self, status: int, body: bytes, content_type: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        with contextlib.suppress(BrokenPipeError, ConnectionResetError):
            self.wfile.write(body)

    def do_GET(self) -> None:
        """The cursor, the script, or a file of Rerun's web viewer (the page with the script)."""
        path = urlsplit(self.path).path
        if path == CURSOR_PATH:
            if "applied" in parse_qs(urlsplit(self.path).query):
                self.owner.loaded()
            body = json_text(self.owner.cursor).encode()
            self._reply(HTTPStatus.OK, body, "application/json")
            return
        if path == _SCRIPT_PATH:
            self._reply(HTTPStatus.OK, _SCRIPT.encode(), "text/javascript")
            return
        try:
            # Rerun's own web server on this machine (http, fixed host): no user URL.
            with urllib.request.urlopen(self.upstream + self.path, timeout=30) as reply:  # noqa: S310
                body = reply.read()
                content_type = reply.headers.get("Content-Type", "application/octet-stream")
                status = reply.status
        except urllib.error.HTTPError as err:
            self._reply(err.code, b"", "text/plain")
            return
        except OSError:
            self._reply(HTTPStatus.BAD_GATEWAY, b"no answer from Rerun's web server", "text/plain")
            return
        if path in {"/", "/index.html"} and b"</body>" in body:
            body = body.replace(b"</body>", _TAG + b"</body>", 1)
        self._reply(status, body, content_type)
