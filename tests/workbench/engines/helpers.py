"""One-frame shortcuts over the engine runners and records, for the engine tests."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import pytest
from rerun.chunk import RrdReader

from workbench.engines.reachsets.verdict import ReachVerdict
from workbench.engines.registry import engine
from workbench.engines.rss.verdict import RssVerdict
from workbench.engines.unstructured.verdict import UnstructuredVerdict

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.records import Frame
    from workbench.engines.base import EngineRunner

__all__ = ["forward_fill", "open_window", "record", "rrd_states", "rss_window", "run_cli", "step"]


def step(runner: EngineRunner, frame: Frame) -> Any:
    """The runner's verdict on one frame (advancing its state)."""
    return runner.step_many([frame])[0]


def record(verdict: Any) -> dict[str, Any]:
    """The pinned per-frame JSON record of any built-in engine's verdict."""
    name = {RssVerdict: "rss", UnstructuredVerdict: "unstructured", ReachVerdict: "reachsets"}
    return engine(name[type(verdict)]).record(verdict)


def run_cli(main: Callable[[list[str]], object], args: list[str]) -> int:
    """Exit code of the CLI ``main`` on ``args`` (it always ends with ``SystemExit``)."""
    with pytest.raises(SystemExit) as info:
        main(args)
    code = info.value.code
    return 0 if code is None else int(code)


def rrd_states(path: Path, entity: str) -> dict[int, str]:
    """The state changes of one state lane of an ``.rrd``: frame -> state."""
    store = RrdReader(path).store().stream().collect()
    table = store.reader(index="frame", contents=entity).to_arrow_table().to_pydict()
    column = f"{entity}:StateChange:state"
    return {f: s[0] for f, s in zip(table["frame"], table[column], strict=True) if s}


def forward_fill(changes: dict[int, str], frames: list[int]) -> list[str | None]:
    """The state in each of ``frames`` from a lane's changes (None before the first)."""
    out: list[str | None] = []
    current = None
    for f in frames:
        current = changes.get(f, current)
        out.append(current)
    return out


def open_window(log: Path, window_s: tuple[float, float]) -> Drive:
    """``log`` opened on ``window_s`` seconds from its start (``[start, end)``)."""
    from loaders import open_drive  # noqa: PLC0415 - only the window tests need it

    drive = open_drive(log)
    t0 = drive.info.start_ns
    drive.close()
    return open_drive(log, window=(t0 + int(window_s[0] * 1e9), t0 + int(window_s[1] * 1e9)))


def rss_window(
    log: Path, window_s: tuple[float, float], *, outlines: bool = False
) -> tuple[list[Frame], list[RssVerdict]]:
    """The frames of ``log`` in ``window_s`` and a fresh ``RssRunner``'s verdicts on them."""
    from workbench.engines.rss.runner import RssRunner  # noqa: PLC0415 - heavy, on demand

    drive = open_window(log, window_s)
    try:
        runner = RssRunner(drive.lane_map, outlines=outlines)
        frames = list(drive.frames())
        return frames, [step(runner, f) for f in frames]
    finally:
        drive.close()
