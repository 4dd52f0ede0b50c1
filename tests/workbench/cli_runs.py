"""Run the ``workbench`` CLI in-process, for the command tests."""

from __future__ import annotations

from tests.workbench.engines.helpers import run_cli
from workbench.cli.main import main

__all__ = ["run_workbench"]


def run_workbench(args: list[str]) -> int:
    """Exit code of ``workbench ARGS`` (run in this process)."""
    return run_cli(main, args)
