"""Unstructured RSS: ms per agent, ours vs the ad-rss 5.0 binding, side by side in one run.

One ego and N agents per frame, one call per frame (the pipeline's call). Three kinds of
frames (seeded, agents within 60 m of the ego): mixed (half pedestrians), vehicles only,
pedestrians only. "ours" is ``check_unstructured`` as the pipeline runs it (hulls of the
set pieces built only where a box test cannot rule a pair out); "ours + sets" also builds
every piece's hull, the geometry the viewer draws (ad-rss always computes its polygons).
"""

from __future__ import annotations

import os
import time

import numpy as np

import rss  # noqa: F401  (must precede ad_rss: the binding registers a module named ``rss``)
from rss.params import DEFAULT_EGO_DYNAMICS
from rss.unstructured import check_unstructured

__all__ = ["run"]

#: (label, pedestrian share) of the frame kinds.
KINDS = (("mixed", 0.5), ("vehicles", 0.0), ("pedestrians", 1.0))
SIZES = (1, 10, 50)


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

    header = (
        "| frame | agents | ours ms/agent | ours + sets ms/agent | ad-rss ms/agent "
        "| speed-up | speed-up with sets |"
    )
    rows = [header, "|---|---|---|---|---|---|---|"]
    repeats = 3 if quick else 7
    d = DEFAULT_EGO_DYNAMICS
    for label, share in KINDS:
        for n in SIZES:
            rng = np.random.default_rng(n)
            ego = random_ego(rng)
            agents, dyn = random_frame(rng, n, pedestrian_share=share)

            def ours(ego: object = ego, agents: object = agents, dyn: object = dyn) -> None:
                check_unstructured(ego, agents, d, dyn, d)  # type: ignore[arg-type]

            def with_sets(ego: object = ego, agents: object = agents, dyn: object = dyn) -> None:
                result, _ = check_unstructured(ego, agents, d, dyn, d)  # type: ignore[arg-type]
                _ = result.ego_sets.hulls, result.agent_sets.hulls

            oracle = UnstructuredOracle()

            def theirs(
                ego: object = ego,
                agents: object = agents,
                dyn: object = dyn,
                oracle: object = oracle,
            ) -> None:
                oracle.evaluate(ego, agents, d, dyn, d)  # type: ignore[attr-defined]

            ours()
            theirs()
            t_ours = _time(ours, repeats) / n * 1e3
            t_sets = _time(with_sets, repeats) / n * 1e3
            t_ref = _time(theirs, repeats) / n * 1e3
            rows.append(
                f"| {label} | {n} | {t_ours:.3f} | {t_sets:.3f} | {t_ref:.2f} "
                f"| {t_ref / t_ours:.0f}x | {t_ref / t_sets:.0f}x |"
            )
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    return (
        "## Unstructured RSS (trajectory sets)\n\n"
        + "\n".join(rows)
        + f"\n\nBest of {repeats} calls each, one ego + N agents per call; load average {load}"
        f" ({os.cpu_count()} cores).\n"
    )


if __name__ == "__main__":
    print(run(quick=True))
