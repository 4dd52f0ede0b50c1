"""Unstructured RSS: ms per agent, ours vs the ad-rss 5.0 binding, side by side in one run.

One ego and N agents per frame, one call per frame (the pipeline's call). Three kinds of
frames (seeded, agents within 60 m of the ego): mixed (half pedestrians), vehicles only,
pedestrians only. "ours" is ``check_unstructured`` as the pipeline runs it (hulls of the
set pieces built only where a box test cannot rule a pair out); "ours + sets" also builds
every piece's hull, the geometry the viewer draws (ad-rss always computes its polygons).

"Batched frames" (:func:`run_frames`, after the per-call table of :func:`run_calls`): the
pipeline's call. A random mixed scene advanced in time (0.1 s per frame, everyone along
its heading at its top speed) gives 32 consecutive frames; ours evaluates them one call
per frame and in one ``evaluate_frames`` call (what ``workbench evaluate`` /
``replay`` run, 32 frames per chunk); ad-rss evaluates them one call per frame (it has no
batch call), timed on the first frames only (its time per agent-frame hardly depends on
the frame).
"""

from __future__ import annotations

import dataclasses
import os
import time
from typing import TYPE_CHECKING

import numpy as np

import rss  # noqa: F401  (must precede ad_rss: the binding registers a module named ``rss``)
from rss.params import DEFAULT_EGO_DYNAMICS, RssParams
from rss.unstructured import FrameInputs, check_unstructured, evaluate_frames

if TYPE_CHECKING:
    from rss.unstructured import UnstructuredAgents

__all__ = ["run", "run_calls", "run_conformance", "run_frames"]

#: (label, pedestrian share) of the frame kinds.
KINDS = (("mixed", 0.5), ("vehicles", 0.0), ("pedestrians", 1.0))
SIZES = (1, 10, 50)
#: Consecutive frames of one batched call (``workbench.driver.run.CHUNK_FRAMES``).
CHUNK = 32
#: Frames of the chunk the binding is timed on.
BINDING_FRAMES = 6
#: CPU time [s] each function spends per round of the per-call and consecutive-frames
#: tables, at least (short calls get many tries, so that their best is stable on a shared
#: machine).
CALL_BUDGET_S = 0.05
#: Time between frames [s].
FRAME_DT_S = 0.1


def _advanced(agents: UnstructuredAgents, t_s: float) -> UnstructuredAgents:
    """The agents ``t_s`` later, each moved along its heading at its top speed."""
    step = agents.speed_max_mps * t_s
    return dataclasses.replace(
        agents,
        x_m=agents.x_m + step * np.cos(agents.yaw_rad),
        y_m=agents.y_m + step * np.sin(agents.yaw_rad),
    )


def _best(
    fns: tuple[object, ...], rounds: int, calls: int = 3, budget_s: float = 0.0
) -> list[float]:
    """Best CPU time [s] of one call of each function over ``rounds`` rounds.

    CPU time of this process (``time.process_time``), not wall time: the machine is shared
    and a pinned process is often descheduled mid-call. Each round runs every function
    ``calls`` times in a row (warm caches), and more until it has spent ``budget_s`` of CPU
    time in that round (the same rule for every function: a short call gets enough tries
    for its best to be stable, a long one keeps its ``calls``), the functions taking turns
    round by round so that all of them meet the same load.
    """
    best = [float("inf")] * len(fns)
    for _ in range(rounds):
        for i, fn in enumerate(fns):
            done, spent = 0, 0.0
            while done < calls or spent < budget_s:
                start = time.process_time()
                fn()  # type: ignore[operator]
                elapsed = time.process_time() - start
                best[i] = min(best[i], elapsed)
                done, spent = done + 1, spent + elapsed
    return best


def _row(labels: tuple[str, ...], ours_ms: tuple[float, float], ref_ms: float) -> str:
    """A table row: labels, our two times, the binding's time, the two speed-ups."""
    a, b = ours_ms
    cells = [*labels, f"{a:.3f}", f"{b:.3f}", f"{ref_ms:.2f}", f"{ref_ms / a:.0f}x"]
    return "| " + " | ".join([*cells, f"{ref_ms / b:.0f}x"]) + " |"


def _section(title: str, rows: list[str], note: str) -> str:
    """A Markdown section: the table, then the note and the machine's load."""
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    return (
        f"## {title}\n\n"
        + "\n".join(rows)
        + f"\n\n{note}; load average {load} ({os.cpu_count()} cores).\n"
    )


def run(quick: bool) -> str:  # noqa: FBT001  (bench/run.py interface)
    """Markdown sections: per call, batched frames, conformance cases (the ``run_*`` below)."""
    return run_calls(quick) + "\n" + run_frames(quick) + "\n" + run_conformance(quick)


def run_conformance(quick: bool) -> str:  # noqa: FBT001  (bench/run.py interface)
    """Markdown section: ms per random unstructured case through the conformance code.

    Ours: :func:`rss.conformance.evaluate_document` on a document of random ``kind:
    unstructured`` cases (what ``workbench conformance rss`` runs after reading the file;
    start-up excluded), per case. ad-rss: the binding's check of the same ego, agent and
    dynamics, one fresh check per case.
    """
    from rss.conformance import evaluate_document  # noqa: PLC0415
    from rss.conformance.cases import parse_defaults  # noqa: PLC0415
    from rss.conformance.unstructured import parse_unstructured_case  # noqa: PLC0415
    from tests.rss.oracle_unstructured import UnstructuredOracle  # noqa: PLC0415
    from tests.rss.unstructured.generators import random_case  # noqa: PLC0415

    count, rounds = (50, 3) if quick else (200, 5)
    rng = np.random.default_rng(31)
    document = {"cases": [random_case(rng, f"u{i}") for i in range(count)]}
    defaults = parse_defaults(document)
    inputs = [parse_unstructured_case(c, defaults, str(c["id"])) for c in document["cases"]]

    def ours() -> None:
        for _ in evaluate_document(document):
            pass

    def theirs() -> None:
        for ego, other, ego_dyn, other_dyn in inputs:
            UnstructuredOracle().evaluate(ego, other, ego_dyn, [other_dyn], defaults.ego)

    t_ours, t_ref = (t / count * 1e3 for t in _best((ours, theirs), rounds, calls=1))
    rows = [
        "| cases | ours ms/case | ad-rss ms/case | speed-up |",
        "|---|---|---|---|",
        f"| {count} | {t_ours:.3f} | {t_ref:.2f} | {t_ref / t_ours:.0f}x |",
    ]
    return _section(
        "Unstructured conformance cases (`workbench conformance rss`)",
        rows,
        f"{count} random unstructured cases (ego + one vehicle or pedestrian, half"
        " pedestrians); ours through `evaluate_document` (parsing, engine, records), ad-rss"
        f" one binding check per case; best of {rounds} rounds (CPU time, taking turns)",
    )


def run_calls(quick: bool) -> str:  # noqa: FBT001
    """Markdown section: per-agent time of ``check_unstructured`` and of ad-rss, per call."""
    from tests.rss.oracle_unstructured import UnstructuredOracle  # noqa: PLC0415
    from tests.rss.unstructured.generators import random_ego, random_frame  # noqa: PLC0415

    header = (
        "| frame | agents | ours ms/agent | ours + sets ms/agent | ad-rss ms/agent "
        "| speed-up | speed-up with sets |"
    )
    rows = [header, "|---|---|---|---|---|---|---|"]
    repeats, budget_s = (3, 0.02) if quick else (5, CALL_BUDGET_S)
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
            t_ours, t_sets, t_ref = (
                t / n * 1e3 for t in _best((ours, with_sets, theirs), repeats, budget_s=budget_s)
            )
            rows.append(_row((label, str(n)), (t_ours, t_sets), t_ref))
    return _section(
        "Unstructured RSS (trajectory sets)",
        rows,
        f"Best call of {repeats} rounds; each round runs every function at least 3 times and"
        f" until it has spent {budget_s * 1e3:.0f} ms of CPU time (the same rule for ours and"
        f" ad-rss: a 0.3 ms call gets ~{budget_s / 3e-4:.0f} tries per round, a 9 ms call"
        f" ~{budget_s / 9e-3:.0f}), ours and ad-rss"
        " taking turns round by round; CPU time of the process; one ego + N agents per call",
    )


def run_frames(quick: bool) -> str:  # noqa: FBT001  (bench/run.py interface)
    """Markdown section: per agent-frame time over 32 consecutive frames, batched and not."""
    from tests.rss.oracle_unstructured import UnstructuredOracle  # noqa: PLC0415
    from tests.rss.unstructured.generators import random_ego, random_frame  # noqa: PLC0415

    rows = [
        (
            "| agents per frame | ours per frame ms/agent-frame | ours batched ms/agent-frame "
            "| ad-rss ms/agent-frame | speed-up per frame | speed-up batched |"
        ),
        "|---|---|---|---|---|---|",
    ]
    rounds, budget_s = (3, 0.02) if quick else (5, CALL_BUDGET_S)
    d = DEFAULT_EGO_DYNAMICS
    for n in SIZES:
        rng = np.random.default_rng(100 + n)
        ego0 = random_ego(rng)
        agents0, dyn = random_frame(rng, n)
        frames = [
            FrameInputs(
                _advanced(ego0, k * FRAME_DT_S), _advanced(agents0, k * FRAME_DT_S), dyn, d, d
            )
            for k in range(CHUNK)
        ]

        def per_frame(frames: list[FrameInputs] = frames) -> None:
            memory = None
            for f in frames:
                _, memory = check_unstructured(f.ego, f.agents, d, f.agent_dynamics, d, memory)

        def batched(frames: list[FrameInputs] = frames) -> None:
            evaluate_frames(frames, RssParams())

        oracle = UnstructuredOracle()

        def theirs(frames: list[FrameInputs] = frames, oracle: object = oracle) -> None:
            for f in frames[:BINDING_FRAMES]:
                oracle.evaluate(f.ego, f.agents, d, f.agent_dynamics, d)  # type: ignore[attr-defined]

        t_frame, t_batch, t_ref = _best(
            (per_frame, batched, theirs), rounds, calls=1, budget_s=budget_s
        )
        t_frame, t_batch = (t / (CHUNK * n) * 1e3 for t in (t_frame, t_batch))
        t_ref = t_ref / (BINDING_FRAMES * n) * 1e3
        rows.append(_row((str(n),), (t_frame, t_batch), t_ref))
    return _section(
        "Unstructured RSS, consecutive frames (ours batched)",
        rows,
        f"{CHUNK} consecutive frames of one mixed scene (ego + N agents, half"
        f" pedestrians, advanced {FRAME_DT_S} s per frame); ours once per frame and in one"
        f" batched call (the pipeline's), ad-rss once per frame on the first {BINDING_FRAMES}"
        f" frames; best of {rounds} rounds, each running every function at least once and"
        f" until it has spent {budget_s * 1e3:.0f} ms of CPU time (CPU time, taking turns)",
    )


if __name__ == "__main__":
    print(run(quick=True))
