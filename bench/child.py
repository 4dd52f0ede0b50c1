"""Run a Python snippet in a fresh interpreter of this Python and read its JSON answer."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def run_json(code: str, *args: str, env: dict[str, str] | None = None) -> Any:
    """Run ``code`` (``python -c``, cwd the repository) and parse its last stdout line as JSON.

    Raises:
        subprocess.CalledProcessError: The snippet failed (its stderr is on the error).
    """
    done = subprocess.run(  # noqa: S603 - this interpreter running our own snippet
        [sys.executable, "-c", code, *args],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
        env=env,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])
