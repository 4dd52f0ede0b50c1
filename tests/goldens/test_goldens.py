"""In every variant, every registered engine's per-frame records on every log equal its golden file.

Parametrized over the variants x the engine registry x ``sample_logs/``: a new engine
(built-in or plugin) or variant (an entry of ``VARIANTS``) gets a test per log without new
test code, and fails until ``make goldens`` wrote its files. The tests only compare
(tolerance: :mod:`tests.goldens.compare`); nothing here writes a golden file.
docs/testing.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from tests.goldens.compare import compare
from tests.goldens.golden_file import read_golden
from tests.goldens.samples import GOLDEN_DIR, VARIANTS, evaluate_log, golden_path, sample_logs
from workbench.engines.registry import names

if TYPE_CHECKING:
    from pathlib import Path

    from tests.goldens.golden_file import FrameRecord

LOGS = sample_logs()
ENGINES = names()
_HOW = "if the change is intended, `make goldens` rewrites the file and reports the change"


@pytest.fixture(scope="module")
def evaluated() -> dict[str, dict[str, list[FrameRecord]]]:
    """Records per variant and log, then engine; each evaluated once (lazily, on first use)."""
    return {}


def _records(
    cache: dict[str, dict[str, list[FrameRecord]]], variant: str, log: Path
) -> dict[str, list[FrameRecord]]:
    key = f"{variant}/{log.name}"
    if key not in cache:
        cache[key] = evaluate_log(log, ENGINES, variant)
    return cache[key]


def test_the_harness_sees_the_samples_and_the_engines():
    assert len(LOGS) >= 14, LOGS
    assert {"reachsets", "rss", "unstructured"} <= set(ENGINES)
    assert {"default", "adrss-5.0"} <= set(VARIANTS)


@pytest.mark.parametrize("log", LOGS, ids=lambda p: p.name)
@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("variant", VARIANTS)
def test_records_equal_the_golden_file(variant: str, engine: str, log: Path, evaluated):
    got = _records(evaluated, variant, log)[engine]
    assert got, f"{log.name}: no frames evaluated"
    path = golden_path(variant, engine, log.name)
    assert path.is_file(), f"no golden file {path.relative_to(GOLDEN_DIR)}: run `make goldens`"
    golden = read_golden(path)
    assert (golden.variant, golden.engine, golden.log) == (variant, engine, log.name)
    changes = compare(golden.frames, got)
    rel = path.relative_to(GOLDEN_DIR)
    assert not changes, f"{rel} differs:\n{changes.summary()}\n({_HOW})"


def test_no_golden_file_without_a_variant_an_engine_and_a_log():
    wanted = {golden_path(v, e, log.name) for v in VARIANTS for e in ENGINES for log in LOGS}
    found = sorted(str(p.relative_to(GOLDEN_DIR)) for p in GOLDEN_DIR.rglob("*.jsonl"))
    assert [p for p in found if GOLDEN_DIR / p not in wanted] == []
