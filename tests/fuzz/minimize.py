"""Shrink a finding to a small input that fails the same way (delta debugging over bytes).

Two inputs fail "the same way" when the same exception type is raised from the same line of
code (the innermost frame of its traceback). The minimized input is what
``tests/fuzz/corpus/<target>/`` keeps as the regression input of the finding.
"""

from __future__ import annotations

import shutil
import tempfile
import time
import traceback
from pathlib import Path
from typing import TYPE_CHECKING

from tests.fuzz.targets import run_input

if TYPE_CHECKING:
    from tests.fuzz.targets import Target

__all__ = ["failure", "minimize"]


def failure(target: Target, data: bytes, assets: Path | None) -> tuple[str, str, str] | None:
    """How ``data`` fails: ``(exception type, file:line of the raise, message)``; None if it
    reads or fails with a typed error."""
    directory = Path(tempfile.mkdtemp(prefix=f"fuzz-min-{target.name}-"))
    try:
        run_input(target, data, directory, assets)
    except Exception as err:  # noqa: BLE001 - every untyped error is what we look for
        where = traceback.extract_tb(err.__traceback__)[-1]
        return type(err).__name__, f"{where.filename}:{where.lineno}", str(err).split("\n")[0]
    finally:
        shutil.rmtree(directory, ignore_errors=True)
    return None


def minimize(target: Target, data: bytes, assets: Path | None, *, budget_s: float = 120.0) -> bytes:
    """The smallest input found within ``budget_s`` that fails like ``data``.

    Raises:
        ValueError: ``data`` does not fail (nothing to minimize).
    """
    found = failure(target, data, assets)
    if found is None:
        msg = f"{target.name}: the input reads or fails typed; nothing to minimize"
        raise ValueError(msg)
    signature = found[:2]
    deadline = time.monotonic() + budget_s
    chunk = max(1, len(data) // 2)
    while time.monotonic() < deadline:
        start, removed = 0, False
        while start < len(data) and time.monotonic() < deadline:
            candidate = data[:start] + data[start + chunk :]
            again = failure(target, candidate, assets)
            if again is not None and again[:2] == signature:
                data, removed = candidate, True
            else:
                start += chunk
        if chunk == 1 and not removed:
            break
        chunk = chunk if removed else max(1, chunk // 2)
    return data
