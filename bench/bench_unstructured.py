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


def _best(fns: tuple[object, ...], rounds: int, calls: int = 3) -> list[float]:
    """Best CPU time [s] of one call of each function over ``rounds`` rounds.

    CPU time of this process (``time.process_time``), not wall time: the machine is shared
    and a pinned process is often descheduled mid-call. Each round runs every function
    ``calls`` times in a row (warm caches), the functions taking turns round by round so
    that all of them meet the same load.
    """
    best = [float("inf")] * len(fns)
    for _ in range(rounds):
        for i, fn in enumerate(fns):
            for _ in range(calls):
                start = time.process_time()
                fn()  # type: ignore[operator]
                best[i] = min(best[i], time.process_time() - start)
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
    repeats = 3 if quick else 5
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
            t_ours, t_sets, t_ref = (t / n * 1e3 for t in _best((ours, with_sets, theirs), repeats))
            rows.append(
                f"| {label} | {n} | {t_ours:.3f} | {t_sets:.3f} | {t_ref:.2f} "
                f"| {t_ref / t_ours:.0f}x | {t_ref / t_sets:.0f}x |"
            )
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    return (
        "## Unstructured RSS (trajectory sets)\n\n"
        + "\n".join(rows)
        + f"\n\nBest call of {repeats} rounds x 3 calls each (CPU time of the process; ours and"
        f" ad-rss take turns round by round), one ego + N agents per call; load average {load}"
        f" ({os.cpu_count()} cores).\n"
    )


if __name__ == "__main__":
    print(run(quick=True))
