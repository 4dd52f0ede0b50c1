"""Run a Python snippet in a fresh interpreter of this Python and read its JSON answer."""

from __future__ import annotations

import json
import resource
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def peak_rss_mib() -> float:
    """Peak resident memory of this process since it started its program [MiB].

    Linux: ``VmHWM`` of ``/proc/self/status``, the high-water mark of this program's own
    memory. ``getrusage``'s ``ru_maxrss`` is not used where ``/proc`` exists: Linux keeps
    it across ``execve``, so a child started by a large parent reports the parent's peak
    (a full ``make bench`` run gave every child the 3 GiB of an earlier in-process step).
    """
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


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
