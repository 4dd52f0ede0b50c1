"""The committed ``sample_logs/`` match the generator, and generation is deterministic."""

from __future__ import annotations

import hashlib
from typing import TYPE_CHECKING

from tests.workbench.samples.conftest import SAMPLE_DIR
from workbench.samples.generate import SCENARIOS, generate_scenario

if TYPE_CHECKING:
    from pathlib import Path

_NOT_GENERATED = {"README.md"}


def _hashes(root: Path) -> dict[str, str]:
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(root.rglob("*"))
        if p.is_file() and p.name not in _NOT_GENERATED and not p.name.endswith(".expected.json")
    }


def test_generation_is_byte_identical(tmp_path):
    scenario = SCENARIOS["parking_lot"]
    generate_scenario(scenario(), tmp_path / "a")
    generate_scenario(scenario(), tmp_path / "b")
    first, second = _hashes(tmp_path / "a"), _hashes(tmp_path / "b")
    assert first
    assert first == second


def test_committed_samples_are_up_to_date(generated):
    committed = _hashes(SAMPLE_DIR)
    fresh = _hashes(generated)
    assert sorted(committed) == sorted(fresh), "run `make samples` and commit sample_logs/"
    stale = [name for name, digest in fresh.items() if committed[name] != digest]
    assert not stale, f"stale samples (run `make samples`): {stale}"


def test_samples_total_size_below_5mb():
    total = sum(p.stat().st_size for p in SAMPLE_DIR.rglob("*") if p.is_file())
    assert total < 5 * 1024 * 1024
