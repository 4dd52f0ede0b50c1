"""Fixtures: the committed sample directory and one fresh generation of all scenarios."""

from __future__ import annotations

from pathlib import Path

import pytest

from workbench.samples.generate import generate

SAMPLE_DIR = Path(__file__).resolve().parents[3] / "sample_logs"


@pytest.fixture(scope="session")
def generated(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """All scenarios generated once into a temporary directory."""
    out = tmp_path_factory.mktemp("samples")
    generate(out)
    return out
