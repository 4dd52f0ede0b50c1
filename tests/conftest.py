"""Shared pytest fixtures.

``external_dir`` locates the real-world test data in the sibling ``shared/external``
directory of the repository (never committed). Tests that use it skip with a reason when
the directory is absent, except under ``CI=true``, where a missing directory is a failure.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from rss import compiled

# As the workbench at its start: the compiled scene modules (``rss.compiled``), when
# fresh, before any test imports ``rss`` submodules.
compiled.activate()

#: ``RSS_WORKBENCH_EXTERNAL`` overrides the place (e.g. for a git worktree elsewhere).
EXTERNAL_DIR = Path(
    os.environ.get("RSS_WORKBENCH_EXTERNAL")
    or Path(__file__).resolve().parents[1] / ".." / "shared" / "external"
).resolve()


def require_external_dir(path: Path, *, ci: bool) -> Path:
    """Return ``path`` if it is a directory; otherwise skip (or fail when ``ci``)."""
    if not path.is_dir():
        reason = f"external test data not found at {path}"
        if ci:
            pytest.fail(f"{reason} (CI=true: external data is required)")
        pytest.skip(reason)
    return path


def running_in_ci() -> bool:
    """Whether the environment variable ``CI`` is set to a true value."""
    return os.environ.get("CI", "").strip().lower() in {"1", "true", "yes"}


@pytest.fixture(scope="session")
def external_dir() -> Path:
    """The ``shared/external`` data directory next to the repository.

    Skips the requesting test when the directory is absent; fails it instead when the
    environment variable ``CI`` is ``true``.
    """
    return require_external_dir(EXTERNAL_DIR, ci=running_in_ci())


@pytest.fixture(scope="session")
def town01_regressions(external_dir: Path) -> Path:
    """The Town01 regression drives with the reference's verdicts (conformance/town01_regressions).

    Skipped when absent; a failure under ``CI``.
    """
    return require_external_dir(
        external_dir.parent / "conformance" / "town01_regressions", ci=running_in_ci()
    )
