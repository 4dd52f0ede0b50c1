"""Oracle scripts run in the ad-rss-map-integration interpreter, one process per core."""

from __future__ import annotations

import json
import subprocess
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["ask_in_parallel"]


def ask_in_parallel(
    python: str, script: Path, town: Path, jobs: list[Any], timeout_s: float | None
) -> list[tuple[int, str, str]]:
    """Run ``python script town`` once per job at the same time, the job as JSON on stdin.

    ``timeout_s`` bounds each process (``None``: no bound).

    Returns:
        ``(return code, stdout, stderr)`` of each process, in the order of ``jobs``.
    """
    procs = [
        subprocess.Popen(  # noqa: S603 - interpreter chosen by the tester
            [python, str(script), str(town)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in jobs
    ]
    with ThreadPoolExecutor(len(procs)) as pool:
        outs = list(
            pool.map(
                lambda job: job[0].communicate(json.dumps(job[1]), timeout=timeout_s),
                zip(procs, jobs, strict=True),
            )
        )
    return [(p.returncode, out, err) for p, (out, err) in zip(procs, outs, strict=True)]
