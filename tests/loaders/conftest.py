"""Loader test fixtures: the synthetic drive written once per session in every format."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from tests.loaders.fixtures import FORMATS, write_format

if TYPE_CHECKING:
    from pathlib import Path


@pytest.fixture(scope="session")
def drive_files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Format name → path of the synthetic drive in that format."""
    directory = tmp_path_factory.mktemp("drives")
    return {name: write_format(name, directory) for name in FORMATS}
