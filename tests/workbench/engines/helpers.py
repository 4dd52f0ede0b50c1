"""One-frame shortcuts over the engine runners and records, for the engine tests."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import pytest

from workbench.engines.reachsets.verdict import ReachVerdict
from workbench.engines.registry import engine
from workbench.engines.rss.verdict import RssVerdict
from workbench.engines.unstructured.verdict import UnstructuredVerdict

if TYPE_CHECKING:
    from collections.abc import Callable

    from loaders.records import Frame
    from workbench.engines.base import EngineRunner

__all__ = ["record", "run_cli", "step"]


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
