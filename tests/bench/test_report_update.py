"""``bench.run --update``: re-measured sections replace theirs, every other section stays."""

from __future__ import annotations

import pytest

from bench.run import _section, _updated

_REPORT = (
    "# Benchmarks\n\nMeasured by `make bench` on 2026-11-28.\n\nMachine: m.\n\n"
    "## A\n\nold a\n\n## B\n\nold b\n\n## C\n\nold c\n"
)


def test_sections_are_replaced_by_heading_and_new_ones_appended() -> None:
    out = _updated(_REPORT, "## B\n\nnew b\n\n## D\n\nnew d\n", "2026-11-29")
    headings = [line for line in out.splitlines() if line.startswith("## ")]
    assert headings == ["## A", "## B", "## C", "## D"]
    assert "old b" not in out
    assert "new b" in out
    assert "old a" in out
    assert "old c" in out
    assert "Measured by `make bench` on 2026-11-28." in out
    assert "Re-measured on 2026-11-29, commit `" in out
    assert '"B", "D"' in out


def test_a_second_update_keeps_one_note() -> None:
    once = _updated(_REPORT, "## B\n\nnew b\n", "2026-11-29")
    twice = _updated(once, "## C\n\nnew c\n", "2026-11-30")
    assert twice.count("Re-measured on") == 1
    assert "2026-11-30" in twice
    assert "new b" in twice


def test_each_module_runs_in_a_fresh_interpreter_and_returns_its_section() -> None:
    section = _section("bench_reach_cases", quick=True)
    assert section.startswith("## Reach-set conformance cases")
    assert "| simple | full sets |" in section


def test_only_benchmark_module_names_run() -> None:
    with pytest.raises(SystemExit, match="not a benchmark module name"):
        _section("os; import shutil", quick=True)
