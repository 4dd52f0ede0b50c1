"""Where a Rerun recording goes: an ``.rrd`` file, a spawned native viewer, or a local server.

:func:`attached` sets a recording stream's sink for exactly one destination and yields where the
data goes; a server it started is stopped when the block ends. Servers bind 127.0.0.1 unless
the caller asks otherwise.
"""

from __future__ import annotations

import contextlib
import ctypes
import importlib.util
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import rerun as rr

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Iterator

    from workbench.viewer.web_cursor import WebCursor

__all__ = ["LOCALHOST", "Destination", "ReplayError", "attached"]

#: ``--serve`` binds the gRPC server here; Rerun's own default is every interface.
LOCALHOST = "127.0.0.1"


class ReplayError(WorkbenchError):
    """The replay could not be written or served."""


@dataclass(frozen=True, slots=True)
class Destination:
    """Exactly one place a recording goes (see :func:`attached`).

    Attributes:
        out: Write an ``.rrd`` file here (parent directories are created).
        spawn: Start a native viewer and stream to it.
        serve: Host a gRPC server plus the web viewer on ``bind``.
        connect: Stream to a running viewer's gRPC proxy (``rerun+http://HOST:PORT/proxy``).
        bind: With ``serve``, the address the gRPC proxy and the web viewer listen on.
        ports: ``(grpc_port, web_port)`` for ``serve``.
        web_cursor: With ``serve``: serves the web page so a review can move the browser's
            time cursor (:mod:`workbench.viewer.web_cursor`).
    """

    out: Path | None = None
    spawn: bool = False
    serve: bool = False
    connect: str | None = None
    bind: str = LOCALHOST
    ports: tuple[int, int] = (9876, 9090)
    web_cursor: WebCursor | None = None

    def attach(
        self, rec: rr.RecordingStream, blueprint: rr.blueprint.Blueprint
    ) -> contextlib.AbstractContextManager[str]:
        """:func:`attached` to this destination."""
        return attached(
            rec,
            blueprint,
            out=self.out,
            spawn=self.spawn,
            serve=self.serve,
            ports=self.ports,
            bind=self.bind,
            connect=self.connect,
            web_cursor=self.web_cursor,
        )


@contextlib.contextmanager
def _viewer_analytics_off() -> Iterator[None]:
    """Keep Rerun's usage analytics off in viewers started from here.

    rerun-sdk 0.41 reads no ``RERUN_ANALYTICS`` variable: the viewer skips analytics when
    ``CI`` is set (or when ``rerun analytics disable`` was run). ``CI`` is set only while a
    viewer or web server starts, so the child inherits it, then restored; set
    ``WORKBENCH_RERUN_ANALYTICS=1`` to leave the environment alone.
    """
    if os.environ.get("WORKBENCH_RERUN_ANALYTICS") == "1" or "CI" in os.environ:
        yield
        return
    os.environ["CI"] = "1"
    try:
        yield
    finally:
        os.environ.pop("CI", None)


@contextlib.contextmanager
def attached(
    rec: rr.RecordingStream,
    blueprint: rr.blueprint.Blueprint,
    *,
    out: Path | None,
    spawn: bool,
    serve: bool,
    ports: tuple[int, int],
    bind: str,
    connect: str | None = None,
    web_cursor: WebCursor | None = None,
) -> Iterator[str]:
    """Set the stream's sink and yield where the data goes (path or URL).

    A server started for ``serve`` is stopped when the block ends; ``connect`` streams to a
    running viewer's gRPC proxy (``rerun+http://HOST:PORT/proxy``). With ``web_cursor``,
    ``serve``'s web page is served by it (in front of Rerun's), so it can move the cursor.
    """
    if sum((out is not None, spawn, serve, connect is not None)) != 1:
        raise ReplayError("choose exactly one of an output file, spawn, serve or connect")
    if connect is not None:
        rec.connect_grpc(connect, default_blueprint=blueprint)
        yield connect
        return
    if out is not None:
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ReplayError(f"cannot create {out.parent}: {err.strerror}") from err
        rec.save(out, default_blueprint=blueprint)
        yield str(out)
        return
    if spawn:
        # The viewer shipped with rerun-sdk sits next to this interpreter, which need not be
        # on PATH (``.venv/bin/workbench`` run without activating the venv).
        viewer = Path(sys.executable).with_name("rerun")
        try:
            with _viewer_analytics_off():
                rr.spawn(
                    recording=rec,
                    default_blueprint=blueprint,
                    executable_path=str(viewer) if viewer.exists() else None,
                )
        except RuntimeError as err:
            raise ReplayError(f"cannot start the Rerun viewer: {err}".splitlines()[0]) from err
        yield "viewer"
        return
    url, server = _serve(rec, blueprint, ports=ports, bind=bind, web_cursor=web_cursor)
    try:
        yield url
    finally:
        rec.disconnect()
        if web_cursor is not None:
            web_cursor.stop()
        _stop(server)


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind((LOCALHOST, 0))
        return int(sock.getsockname()[1])


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _stop(proc: subprocess.Popen[bytes]) -> None:
    """Terminate the server's whole process group and wait until it is gone."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, sig)
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline:
            proc.poll()
            if not _group_alive(proc.pid):
                return
            time.sleep(0.05)


def _wait_for_port(host: str, port: int, proc: subprocess.Popen[bytes], timeout_s: float) -> None:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise ReplayError(f"the Rerun server exited with code {proc.returncode}")
        with contextlib.suppress(OSError), socket.create_connection((host, port), timeout=0.2):
            return
        time.sleep(0.1)
    raise ReplayError(f"the Rerun server did not listen on {host}:{port} within {timeout_s} s")


#: ``prctl`` option: the signal the kernel sends a process when its parent dies.
_PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:  # pragma: no cover - runs in the child before exec
    """Child side: ask Linux to SIGTERM this process when the workbench process dies."""
    ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)


def _viewer_binary() -> str:
    """The Rerun viewer binary itself (rerun-sdk's ``rerun_cli/rerun``), else the script.

    The ``rerun`` script only runs that binary as its child; started directly, the binary
    is the process that the parent-death signal reaches.
    """
    spec = importlib.util.find_spec("rerun_cli")
    if spec is not None and spec.origin is not None:
        binary = Path(spec.origin).with_name("rerun")
        if binary.is_file():
            return str(binary)
    script = Path(sys.executable).with_name("rerun")
    return str(script) if script.exists() else "rerun"


def _serve(
    rec: rr.RecordingStream,
    blueprint: rr.blueprint.Blueprint,
    *,
    ports: tuple[int, int],
    bind: str,
    web_cursor: WebCursor | None = None,
) -> tuple[str, subprocess.Popen[bytes]]:
    """Start ``rerun --serve-web --bind BIND`` and connect the stream to its gRPC proxy.

    The SDK's in-process web server has no bind option and listens on every interface; the
    viewer's own server binds both the gRPC proxy and the web page to ``bind``. With
    ``web_cursor``, Rerun's page is on a free port and ``web_cursor`` serves it on the web port.
    """
    grpc_port, web_port = ports
    rerun_web_port = web_port if web_cursor is None else _free_port()
    exe = _viewer_binary()
    cmd = [exe, "--serve-web", "--bind", bind, "--port", str(grpc_port)]
    cmd += ["--web-viewer-port", str(rerun_web_port)]
    with _viewer_analytics_off():
        try:
            # Own session, stopped as a group with the replay; on Linux also stopped by the
            # kernel when this process dies without cleaning up (SIGKILL): the parent-death
            # signal belongs to the creating thread, so only the main thread asks for it.
            linked = (
                sys.platform == "linux" and threading.current_thread() is threading.main_thread()
            )
            proc = subprocess.Popen(  # noqa: S603 - fixed argv, no shell
                cmd,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,
                preexec_fn=_die_with_parent if linked else None,  # noqa: PLW1509 - only prctl
            )
        except OSError as err:
            raise ReplayError(f"cannot start the Rerun server {exe}: {err.strerror}") from err
    host = "127.0.0.1" if bind in {"0.0.0.0", "::"} else bind  # noqa: S104 - compared, not bound
    try:
        _wait_for_port(host, grpc_port, proc, timeout_s=20.0)
        if web_cursor is not None:
            _wait_for_port(host, rerun_web_port, proc, timeout_s=20.0)
            web_cursor.start(bind, web_port, rerun_web_port)
    except ReplayError:
        _stop(proc)
        raise
    except OSError as err:
        _stop(proc)
        msg = f"cannot serve the web viewer on {bind}:{web_port}: {err.strerror}"
        raise ReplayError(msg) from err
    uri = f"rerun+http://{host}:{grpc_port}/proxy"
    rec.connect_grpc(uri, default_blueprint=blueprint)
    return f"http://{host}:{web_port}/?url={uri}", proc
