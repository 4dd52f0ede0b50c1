"""PNG screenshots of recordings from a headless Rerun viewer (thumbnails, docs).

One headless viewer process (``--renderer vulkan``, bound to 127.0.0.1 on a free port) is
started per :func:`headless_viewer` block and driven through
``rerun.experimental.ViewerClient``: open a recording, wait until it has loaded, move the
time cursor, save a screenshot. Without a Vulkan driver (on Debian:
``mesa-vulkan-drivers``, software rendering) the viewer cannot start and
:class:`ScreenshotUnavailableError` says so in one line.

Run as ``python -m workbench.viewer.screenshot RRD PNG [FRAME] [WIDTHxHEIGHT]``.
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Iterator

    import rerun.blueprint as rrb
    from rerun.experimental import ViewerClient

__all__ = ["ScreenshotUnavailableError", "headless_viewer", "main", "screenshot"]

#: How long the viewer may take to start or to load a recording [s].
START_TIMEOUT_S = 30.0
#: Wait after moving the time cursor, so the viewer repaints [s].
_REPAINT_S = 1.0


class ScreenshotUnavailableError(WorkbenchError):
    """No headless viewer can run here (no ``rerun`` binary or no Vulkan driver)."""


def _viewer_binary() -> str:
    spec = importlib.util.find_spec("rerun_cli")  # the binary shipped with rerun-sdk
    if spec is not None and spec.origin is not None:
        candidate = Path(spec.origin).parent / "rerun"
        if candidate.is_file():
            return str(candidate)
    found = shutil.which("rerun")
    if found is None:
        msg = "no rerun viewer binary found (install rerun-sdk)"
        raise ScreenshotUnavailableError(msg)
    return found


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextlib.contextmanager
def headless_viewer(size: tuple[int, int] = (1600, 900)) -> Iterator[ViewerClient]:
    """A headless viewer on 127.0.0.1 for the block; stopped afterwards.

    Raises:
        ScreenshotUnavailableError: The viewer did not start (no binary, no Vulkan driver).
    """
    from rerun.experimental import ViewerClient  # noqa: PLC0415 - heavy, on demand

    port = _free_port()
    with tempfile.TemporaryDirectory(prefix="rss-workbench-viewer-") as runtime:
        env = {
            **os.environ,
            "XDG_RUNTIME_DIR": os.environ.get("XDG_RUNTIME_DIR", runtime),
            "CI": os.environ.get("CI", "1"),  # rerun 0.41 skips usage analytics under CI
            "RUST_LOG": os.environ.get("RUST_LOG", "error"),
        }
        args = [
            _viewer_binary(),
            "--headless",
            "--renderer",
            "vulkan",
            "--bind",
            "127.0.0.1",
            "--port",
            str(port),
            "--window-size",
            f"{size[0]}x{size[1]}",
            "--hide-welcome-screen",
        ]
        process = subprocess.Popen(  # noqa: S603 - the rerun binary with fixed arguments
            args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        try:
            yield _connect(ViewerClient, port, process)
        finally:
            process.kill()
            process.wait()


def _connect(
    client: type[ViewerClient], port: int, process: subprocess.Popen[bytes]
) -> ViewerClient:
    deadline = time.monotonic() + START_TIMEOUT_S
    while True:
        if process.poll() is not None:
            msg = (
                f"the headless viewer exited with code {process.returncode} "
                "(no Vulkan driver? on Debian: apt-get install mesa-vulkan-drivers)"
            )
            raise ScreenshotUnavailableError(msg)
        try:
            viewer = client.connect(f"rerun+http://127.0.0.1:{port}/proxy")
            viewer.get_state()
        except Exception as err:  # still starting: any connection error
            if time.monotonic() > deadline:
                msg = f"the headless viewer did not answer within {START_TIMEOUT_S:.0f} s"
                raise ScreenshotUnavailableError(msg) from err
            time.sleep(0.3)
        else:
            return viewer


def _wait_loaded(viewer: ViewerClient) -> None:
    deadline = time.monotonic() + START_TIMEOUT_S
    time.sleep(0.3)
    while viewer.get_state().loading and time.monotonic() < deadline:
        time.sleep(0.3)


def _send_blueprint(viewer: ViewerClient, blueprint: rrb.Blueprint) -> None:
    """Make ``blueprint`` the active recording's; wait until the viewer shows its views.

    The views counted are the root container's (a blueprint of views side by side).
    """
    import rerun as rr  # noqa: PLC0415 - heavy, on demand

    active = viewer.get_state().active_recording  # "Recording:<application>:<recording>"
    if active is None:
        msg = "the headless viewer shows no recording to lay out"
        raise WorkbenchError(msg)
    _, application, recording = active.split(":", 2)
    stream = rr.RecordingStream(application, recording_id=recording)
    stream.connect_grpc(viewer.url)
    try:
        stream.send_blueprint(blueprint, make_active=True)
        stream.flush()
    finally:
        stream.disconnect()
    root = blueprint.root_container
    wanted = len(list(root.contents)) if root is not None else 1
    deadline = time.monotonic() + START_TIMEOUT_S
    while len(viewer.get_state().views) != wanted and time.monotonic() < deadline:
        time.sleep(0.2)


def screenshot(
    viewer: ViewerClient,
    rrd: Path,
    png: Path,
    frame: int | None = None,
    timeline: str = "frame",
    *,
    blueprint: rrb.Blueprint | None = None,
) -> None:
    """Open ``rrd`` in ``viewer``, move to ``frame`` on ``timeline``, save ``png``.

    ``blueprint``: shown instead of the recording's own (sent into the opened recording).

    Raises:
        WorkbenchError: No PNG was written.
    """
    viewer.open(str(rrd.resolve()))
    _wait_loaded(viewer)
    if blueprint is not None:
        _send_blueprint(viewer, blueprint)
    if frame is not None:
        viewer.set_time(timeline, sequence=frame, play_state="paused")
    time.sleep(_REPAINT_S)
    png.parent.mkdir(parents=True, exist_ok=True)
    viewer.save_screenshot(str(png.resolve()))
    if not png.is_file() or png.stat().st_size == 0:
        msg = f"{png}: the viewer wrote no screenshot of {rrd}"
        raise WorkbenchError(msg)


def main(argv: list[str] | None = None) -> int:
    """``RRD PNG [FRAME] [WIDTHxHEIGHT]``: one screenshot; exit 2 with one line on failure."""
    args = sys.argv[1:] if argv is None else argv
    if len(args) < 2:  # noqa: PLR2004 - two required arguments
        sys.stderr.write("usage: python -m workbench.viewer.screenshot RRD PNG [FRAME] [WxH]\n")
        return 2
    rrd, png = Path(args[0]), Path(args[1])
    frame = int(args[2]) if len(args) > 2 and args[2] else None  # noqa: PLR2004
    width, height = (int(v) for v in (args[3] if len(args) > 3 else "1600x900").split("x"))  # noqa: PLR2004
    if not rrd.is_file():
        sys.stderr.write(f"error: {rrd}: no such file\n")
        return 2
    try:
        with headless_viewer((width, height)) as viewer:
            screenshot(viewer, rrd, png, frame)
    except WorkbenchError as err:
        sys.stderr.write(f"error: {err}\n")
        return 2
    sys.stdout.write(f"wrote {png}\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
