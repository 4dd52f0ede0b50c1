"""The house rules that keep the code easy to live in, checked on every run.

* No import cycles among the modules of the four packages (TYPE_CHECKING imports count:
  a cycle of type references is a knot too). import-linter checks the layers between the
  packages (``make layers``); this checks the modules inside them.
* Every module is at most :data:`MAX_LINES` lines.
"""

from __future__ import annotations

from pathlib import Path

import grimp
import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("workbench", "loaders", "rss", "reachsets")
MAX_LINES = 400


def _imports_in_cycles() -> list[tuple[str, str]]:
    """Direct imports ``(a, b)`` of modules ``b`` that import ``a`` back, directly or not."""
    graph = grimp.build_graph(*PACKAGES, cache_dir=None)
    return sorted(
        (a, b)
        for a in graph.modules
        for b in graph.find_modules_directly_imported_by(a)
        if graph.chain_exists(importer=b, imported=a)
    )


def test_no_import_cycles_inside_the_packages():
    assert _imports_in_cycles() == []


@pytest.mark.parametrize("package", PACKAGES)
def test_no_module_is_longer_than_the_limit(package):
    long = {
        str(path.relative_to(ROOT)): n
        for path in sorted((ROOT / package).rglob("*.py"))
        if (n := len(path.read_text().splitlines())) > MAX_LINES
    }
    assert long == {}
