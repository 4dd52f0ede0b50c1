"""The peak memory a benchmark child reports is its own, not its parent's."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bench.child import peak_rss_mib, run_json

_PARENT_MIB = 300


@pytest.mark.skipif(
    not Path("/proc/self/status").is_file(), reason="VmHWM needs Linux /proc (elsewhere ru_maxrss)"
)
def test_a_child_of_a_large_parent_reports_its_own_peak() -> None:
    ballast = np.ones(_PARENT_MIB * 2**20 // 8)  # touched: resident in this process
    assert peak_rss_mib() >= _PARENT_MIB
    child = run_json(
        "import json; from bench.child import peak_rss_mib; print(json.dumps(peak_rss_mib()))"
    )
    # a bare interpreter with numpy unimported stays far below the parent's ballast
    assert 0 < child < _PARENT_MIB / 2
    del ballast  # kept alive until the child has run
