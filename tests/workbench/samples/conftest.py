"""Fixtures: the committed sample directory and one fresh generation of all scenarios."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from workbench.samples.generate import generate

SAMPLE_DIR = Path(__file__).resolve().parents[3] / "sample_logs"
_NOT_GENERATED = {"README.md"}


def sample_hashes(root: Path, stems: tuple[str, ...] = ("",)) -> dict[str, str]:
    """SHA-256 of every generated file under ``root`` whose relative path starts with a stem.

    ``README.md`` is not generated, so skipped (the goldens live in tests/goldens).
    """
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(root.rglob("*"))
        if p.is_file()
        and p.name not in _NOT_GENERATED
        and str(p.relative_to(root)).startswith(stems)
    }


@pytest.fixture(scope="session")
def generated(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """All scenarios generated once into a temporary directory."""
    out = tmp_path_factory.mktemp("samples")
    generate(out)
    return out
