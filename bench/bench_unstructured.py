"""Unstructured RSS: ms per agent, ours vs the ad-rss 5.0 binding, in one run."""

from __future__ import annotations

import os
import time

import numpy as np

import rss  # noqa: F401  (must precede ad_rss: the binding registers a module named ``rss``)
from rss.params import DEFAULT_EGO_DYNAMICS
from rss.unstructured import check_unstructured

__all__ = ["run"]


def _time(fn: object, repeats: int) -> float:
    """Best of ``repeats`` calls (the machine is shared: the minimum is the least disturbed)."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        fn()  # type: ignore[operator]
        best = min(best, time.perf_counter() - start)
    return best


def run(quick: bool) -> str:  # noqa: FBT001  (bench/run.py interface)
    """Markdown section: per-agent time of ``check_unstructured`` and of ad-rss."""
    from tests.rss.oracle_unstructured import UnstructuredOracle  # noqa: PLC0415
    from tests.rss.unstructured.generators import random_ego, random_frame  # noqa: PLC0415

    rows = ["| agents | ours ms/agent | ad-rss ms/agent | speed-up |", "|---|---|---|---|"]
    repeats = 3 if quick else 7
    for n in (1, 10, 50):
        rng = np.random.default_rng(n)
        ego = random_ego(rng)
        agents, dyn = random_frame(rng, n)

        def ours(ego: object = ego, agents: object = agents, dyn: object = dyn) -> None:
            check_unstructured(ego, agents, DEFAULT_EGO_DYNAMICS, dyn, DEFAULT_EGO_DYNAMICS)  # type: ignore[arg-type]

        oracle = UnstructuredOracle()

        def theirs(
            ego: object = ego, agents: object = agents, dyn: object = dyn, oracle: object = oracle
        ) -> None:
            oracle.evaluate(ego, agents, DEFAULT_EGO_DYNAMICS, dyn, DEFAULT_EGO_DYNAMICS)  # type: ignore[attr-defined]

        ours()
        t_ours = _time(ours, repeats) / n * 1e3
        t_ref = _time(theirs, repeats) / n * 1e3
        rows.append(f"| {n} | {t_ours:.3f} | {t_ref:.2f} | {t_ref / t_ours:.0f}x |")
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    return (
        "## Unstructured RSS (trajectory sets)\n\n"
        + "\n".join(rows)
        + f"\n\nBest of {repeats} calls each; load average {load} ({os.cpu_count()} cores).\n"
    )


if __name__ == "__main__":
    print(run(quick=True))
