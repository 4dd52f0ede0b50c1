"""Structured RSS: constellations per second, our numpy engine vs the ad-rss 5.0 binding.

The same frame (one ego, N other vehicles on a 3-lane same-direction road, random gaps
and speeds) is evaluated by both engines in this process. The binding evaluates one world
per call (time index incremented); ours is timed per frame (one call per frame, memory
carried) and batched (many consecutive frames in one call, memory carried through them).
"""

from __future__ import annotations

import time

import numpy as np

import rss  # noqa: F401  (must be imported before ad_rss: the binding registers a module "rss")
from rss.model import (
    Constellation,
    ConstellationType,
    LaneDrivingDirection,
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    SpeedInterval,
)
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.structured.engine import check_frame, check_frames
from rss.structured.stacking import stack_constellations

SIZES = (1, 10, 50, 200)
ROAD_M = 1000.0
LANE_M = 3.5


def _frame(n: int, rng: np.random.Generator) -> list[Constellation]:
    lanes = tuple(
        LaneSegment(i + 1, LaneDrivingDirection.Positive, ROAD_M, ROAD_M, LANE_M, LANE_M)
        for i in range(3)
    )
    road = (RoadSegment(lanes),)
    ego_region = OccupiedRegion(2, 0.300, 0.3045, 0.2, 0.8)
    ego = LaneObject(0, ObjectType.EgoVehicle, (ego_region,), SpeedInterval(20.0, 20.0, 0.0, 0.0))
    out = []
    for i in range(n):
        start = float(rng.uniform(0.05, 0.9))
        lane = int(rng.integers(1, 4))
        region = OccupiedRegion(lane, start, start + 0.0045, 0.2, 0.8)
        v = float(rng.uniform(0.0, 30.0))
        other = LaneObject(
            i + 1, ObjectType.OtherVehicle, (region,), SpeedInterval(v, v, -0.2, 0.2)
        )
        out.append(
            Constellation(
                ConstellationType.SameDirection,
                ego,
                other,
                DEFAULT_EGO_DYNAMICS,
                DEFAULT_VEHICLE_DYNAMICS,
                road,
            )
        )
    return out


def _rate(fn: object, budget_s: float) -> float:
    """Calls per second of ``fn`` over roughly ``budget_s``."""
    assert callable(fn)
    fn()
    calls, start = 0, time.perf_counter()
    while True:
        fn()
        calls += 1
        elapsed = time.perf_counter() - start
        if elapsed >= budget_s:
            return calls / elapsed


def _binding_rate(frame: list[Constellation], budget_s: float) -> float | None:
    try:
        from tests.rss.oracle import AdRssOracle  # noqa: PLC0415
    except ImportError:
        return None
    try:
        oracle = AdRssOracle()
    except BaseException:  # noqa: BLE001  (pytest.skip when ad_rss is missing)
        return None
    world = oracle.world_model(frame, DEFAULT_EGO_DYNAMICS)
    counter = [world.time_index]

    def call() -> None:
        counter[0] += 1
        world.time_index = counter[0]
        ok, _, _ = oracle.run(world)
        assert ok

    return _rate(call, budget_s)


def run(quick: bool) -> str:  # noqa: FBT001
    """Measure and return the Markdown section."""
    budget = 0.3 if quick else 1.5
    rng = np.random.default_rng(0)
    rows = []
    for n in SIZES:
        frame = _frame(n, rng)
        batch = stack_constellations(frame)
        state: dict[str, object] = {"memory": None}

        def ours_frame(batch: object = batch, state: dict[str, object] = state) -> None:
            _, state["memory"] = check_frame(batch, DEFAULT_EGO_DYNAMICS, state["memory"])  # type: ignore[arg-type]

        per_frame = _rate(ours_frame, budget) * n
        n_frames = max(1, (20_000 if quick else 100_000) // n)
        many = stack_constellations(frame * n_frames)
        frames = np.repeat(np.arange(n_frames), n)

        def ours_batched(
            many: object = many, frames: np.ndarray = frames, n_frames: int = n_frames
        ) -> None:
            check_frames(many, frames, n_frames, DEFAULT_EGO_DYNAMICS)  # type: ignore[arg-type]

        batched = _rate(ours_batched, budget) * n * n_frames

        def ours_both_sides(
            many: object = many, frames: np.ndarray = frames, n_frames: int = n_frames
        ) -> None:
            check_frames(many, frames, n_frames, DEFAULT_EGO_DYNAMICS, with_responsibility=True)  # type: ignore[arg-type]

        both = _rate(ours_both_sides, budget) * n * n_frames
        binding = _binding_rate(frame, budget)
        binding_rate = binding * n if binding else None
        rows.append((n, binding_rate, per_frame, batched, n_frames, both))
    lines = [
        "## Structured RSS engine vs ad-rss 5.0 binding",
        "",
        (
            "Constellations per second (one ego, N other vehicles, 3-lane same-direction road). "
            "Binding: `RssCheck.calculateProperResponse` on a pre-built world, one call per "
            "frame. Ours per frame: `rss.structured.engine.check_frame`, one call per frame, "
            "memory carried. Ours batched: `rss.structured.engine.check_frames` over F "
            "consecutive frames in one call (memory carried through them), as a replay of a "
            "recorded drive does. Both sides: the same batched call with "
            "`with_responsibility=True` (every constellation also checked from the other "
            "object's side, `rss.structured.responsibility`); cost = batched / both sides."
        ),
        "",
        (
            "| N objects | ad-rss binding | ours, per frame | ours, batched (F frames) "
            "| batched / binding | both sides, batched | cost of the object side |"
        ),
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for n, binding_rate, per_frame, batched, n_frames, both in rows:
        ratio = f"{batched / binding_rate:.0f}x" if binding_rate else "n/a"
        bind = f"{binding_rate:,.0f}" if binding_rate else "not installed"
        lines.append(
            f"| {n} | {bind} | {per_frame:,.0f} | {batched:,.0f} (F={n_frames}) | {ratio} "
            f"| {both:,.0f} | {batched / both:.2f}x |"
        )
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(run(quick=True))
