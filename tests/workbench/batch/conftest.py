"""The fleet and its process-pool batches, shared by the batch tests (built once)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from tests.workbench.batch.drives import BAD, GOOD, make_fleet
from tests.workbench.cli_runs import run_workbench

if TYPE_CHECKING:
    from pathlib import Path

#: Engines of every batch here (one keeps the suite short; the batch is engine-agnostic).
ENGINES = "rss"


@pytest.fixture(scope="session")
def fleet(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder with the good drives and the bad logs of :mod:`tests.workbench.batch.drives`."""
    folder = tmp_path_factory.mktemp("fleet")
    make_fleet(folder)
    return folder


def _batch(logs: list[str], out: Path) -> Path:
    args = ["batch", *logs, "--out", str(out), "--jobs", "2", "--engines", ENGINES]
    assert run_workbench(args) == 0
    return out


@pytest.fixture(scope="session")
def reference(fleet: Path) -> Path:
    """A process-pool batch of the good drives only."""
    return _batch([str(fleet / name) for name in GOOD], fleet.parent / "reference")


@pytest.fixture(scope="session")
def full(fleet: Path) -> Path:
    """A process-pool batch of the good drives and the bad logs."""
    return _batch([str(fleet / name) for name in (*GOOD, *BAD)], fleet.parent / "full")
