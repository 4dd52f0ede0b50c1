"""Structured RSS: constellations per second, our numpy engine vs the ad-rss 5.0 binding.

The same frame (one ego, N other vehicles on a 3-lane same-direction road, random gaps
and speeds) is evaluated by both engines in this process. The binding evaluates one world
per call (time index incremented); ours is timed per frame (one call per frame, memory
carried) and batched (many consecutive frames in one call, memory carried through them).
"""

from __future__ import annotations

import dataclasses
import time
from typing import TYPE_CHECKING

import numpy as np

import rss  # noqa: F401  (must be imported before ad_rss: the binding registers a module "rss")
from rss.dynamics import DYNAMICS_KEYS
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
from rss.physics import (
    DISTANCE_PRECISION,
    gt,
    stated_braking_lateral,
    stated_braking_longitudinal,
    stopping_distance,
    tmax,
)
from rss.structured.engine import FrameResult, check_frame, check_frames
from rss.structured.stacking import stack_constellations

if TYPE_CHECKING:
    from rss.arrays import IntArray
    from rss.structured.batch import ConstellationBatch
    from rss.structured.memory import RssMemory

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
    """Calls per CPU second of ``fn``: the best of repeated chunks within ``budget_s``.

    CPU time of this process (``time.process_time``), not wall time: on a machine shared
    with other jobs, time spent waiting for a core is not counted, and the best chunk is
    the one least disturbed (as ``timeit`` takes the minimum). Every engine and reference
    of the section is timed the same way.
    """
    assert callable(fn)
    fn()
    best, spent, calls = 0.0, 0.0, 1
    while spent < budget_s:
        start = time.process_time()
        for _ in range(calls):
            fn()
        elapsed = time.process_time() - start
        spent += elapsed
        if elapsed > 0.0:
            best = max(best, calls / elapsed)
        if elapsed < budget_s / 10:
            calls *= 2
    return best


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


def _numpy_limit(n_rows: int, budget_s: float) -> float:
    """Rows per second of the checks' arithmetic alone on ``(n_rows,)`` arrays.

    The same-direction longitudinal and the lateral safe distances and their tolerant
    comparisons (``rss.physics`` primitives, as the batched engine computes them), without
    extraction, merging, memory, response resolving or any per-call bookkeeping: what one
    core's numpy streams for this arithmetic on this machine.
    """
    rng = np.random.default_rng(1)
    d = DEFAULT_VEHICLE_DYNAMICS
    v_follow, v_lead = rng.uniform(0.0, 30.0, n_rows), rng.uniform(0.0, 30.0, n_rows)
    v_lat_l, v_lat_r = rng.uniform(-1.0, 1.0, n_rows), rng.uniform(-1.0, 1.0, n_rows)
    gap, lat_gap = rng.uniform(0.0, 100.0, n_rows), rng.uniform(0.0, 3.0, n_rows)
    full = {name: np.full(n_rows, getattr(d, name)) for name in DYNAMICS_KEYS.values()}

    def arithmetic() -> None:
        follow = stated_braking_longitudinal(
            v_follow,
            full["max_speed_on_acceleration_mps"],
            full["response_time_s"],
            full["accel_max_mps2"],
            full["brake_min_mps2"],
        )
        lead = stopping_distance(v_lead, full["brake_max_mps2"])
        lon = (
            tmax(follow - lead, 0.0, DISTANCE_PRECISION)
            + full["min_longitudinal_safety_distance_m"]
        )
        left = stated_braking_lateral(
            v_lat_l, full["response_time_s"], full["lat_accel_max_mps2"], full["lat_brake_min_mps2"]
        )
        right = stated_braking_lateral(
            v_lat_r,
            full["response_time_s"],
            -full["lat_accel_max_mps2"],
            -full["lat_brake_min_mps2"],
        )
        margin = 0.5 * (full["lateral_fluctuation_margin_m"] + full["lateral_fluctuation_margin_m"])
        lat = tmax(left - right + margin, 0.0, DISTANCE_PRECISION)
        _ = ~gt(gap, lon, DISTANCE_PRECISION) & ~gt(lat_gap, lat, DISTANCE_PRECISION)

    return _rate(arithmetic, budget_s) * n_rows


def _read_verdicts(result: FrameResult) -> None:
    """What a caller of the binding gets: the proper response and who is dangerous.

    The row path builds its result's arrays on first read (``SmallFrameResult``); these
    two are built here, in the timed call.
    """
    assert result.responses.is_safe.shape == (1,)
    assert result.dangerous.shape[0] >= 1


def _read_all(result: FrameResult) -> None:
    """Every field of the result (all ~45 arrays of the row path built)."""
    for field in dataclasses.fields(result):
        getattr(result, field.name)


def _ours_per_frame(
    frame: list[Constellation], budget_s: float
) -> tuple[float, float, float, float]:
    """One call per frame, memory carried, frames/s.

    Returns:
        ``(check_frame on a stacked batch, the same with every result field read, the same
        including stacking, the batched engine alone on the stacked batch)``; the last is
        what ``check_frame`` did before the small-frame path.
    """
    batch = stack_constellations(frame)
    state: dict[str, RssMemory | None] = {"memory": None}
    one_frame = np.zeros(batch.size, dtype=np.int64)

    def batched_engine() -> None:
        result, state["memory"] = check_frames(
            batch, one_frame, 1, DEFAULT_EGO_DYNAMICS, state["memory"]
        )
        _read_verdicts(result)

    def stacked() -> None:
        result, state["memory"] = check_frame(batch, DEFAULT_EGO_DYNAMICS, state["memory"])
        _read_verdicts(result)

    def every_field() -> None:
        result, state["memory"] = check_frame(batch, DEFAULT_EGO_DYNAMICS, state["memory"])
        _read_all(result)

    def with_stacking() -> None:
        result, state["memory"] = check_frame(
            stack_constellations(frame), DEFAULT_EGO_DYNAMICS, state["memory"]
        )
        _read_verdicts(result)

    return (
        _rate(stacked, budget_s),
        _rate(every_field, budget_s),
        _rate(with_stacking, budget_s),
        _rate(batched_engine, budget_s),
    )


def run(quick: bool) -> str:  # noqa: FBT001
    """Measure and return the Markdown section."""
    budget = 0.3 if quick else 1.5
    rng = np.random.default_rng(0)
    rows = []
    for n in SIZES:
        frame = _frame(n, rng)
        binding = _binding_rate(frame, budget)
        stacked, every_field, with_stacking, engine = _ours_per_frame(frame, budget)
        n_frames = max(1, (20_000 if quick else 100_000) // n)
        many = stack_constellations(frame * n_frames)
        frames = np.repeat(np.arange(n_frames), n)

        def ours_batched(
            many: ConstellationBatch = many, frames: IntArray = frames, n_frames: int = n_frames
        ) -> None:
            check_frames(many, frames, n_frames, DEFAULT_EGO_DYNAMICS)

        batched = _rate(ours_batched, budget) * n * n_frames

        def ours_both_sides(
            many: ConstellationBatch = many, frames: IntArray = frames, n_frames: int = n_frames
        ) -> None:
            check_frames(many, frames, n_frames, DEFAULT_EGO_DYNAMICS, with_responsibility=True)

        both = _rate(ours_both_sides, budget) * n * n_frames
        binding_rate = binding * n if binding else None
        rows.append(
            (
                n,
                binding_rate,
                (stacked * n, every_field * n, with_stacking * n, engine * n),
                batched,
                n_frames,
                both,
            )
        )
    limits = {size: _numpy_limit(size, budget) for size in (8_192, 100_000)}
    return _section(rows, limits)


def _ratio(ours: float, binding: float | None) -> str:
    return f"{ours / binding:.1f}x" if binding else "n/a"


def _section(
    rows: list[tuple[int, float | None, tuple[float, float, float, float], float, int, float]],
    limits: dict[int, float],
) -> str:
    lines = [
        "## Structured RSS engine vs ad-rss 5.0 binding",
        "",
        (
            "Constellations per second (one ego, N other vehicles, 3-lane same-direction road). "
            "Binding: `RssCheck.calculateProperResponse` on a pre-built world, one call per "
            "frame (it fills the proper response and the per-object states). Ours, one frame "
            "per call: `rss.structured.engine.check_frame`, memory carried, on a stacked "
            "batch (as the binding's world is pre-built), then the proper response and the "
            "per-object dangerous flags read (`_read_verdicts`); the same with every field of "
            "the result read (`_read_all`); and including `stack_constellations`. Up to "
            "`SMALL_FRAME_MAX` constellations `check_frame` takes the row-by-row path "
            "(`rss.structured.small`, compiled), which computes every value in the call but "
            "builds a result array on its first read. Before: the batched engine alone "
            "(`check_frames`, F = 1), what `check_frame` ran before. Ours batched: "
            "`rss.structured.engine.check_frames` over F consecutive frames in one call "
            "(memory carried through them), as a replay of a recorded drive does. Both sides: "
            "the same batched call with `with_responsibility=True` (every constellation also "
            "checked from the other object's side, `rss.structured.responsibility`); cost = "
            "batched / both sides. Rates are per CPU second of this process, the best of "
            "repeated chunks (`_rate`), for ours and the binding alike."
        ),
        "",
        (
            "| N objects | ad-rss binding, one frame per call | ours, one frame per call "
            "| ratio | ours, every field read | ratio "
            "| ours, one frame per call incl. stacking | ratio "
            "| batched engine, one frame per call (before) "
            "| ours, batched (F frames) | batched / binding | both sides, batched "
            "| cost of the object side |"
        ),
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for n, binding, per_call, batched, n_frames, both in rows:
        stacked, every_field, with_stacking, engine = per_call
        bind = f"{binding:,.0f}" if binding else "not installed"
        lines.append(
            f"| {n} | {bind} | {stacked:,.0f} | {_ratio(stacked, binding)} "
            f"| {every_field:,.0f} | {_ratio(every_field, binding)} "
            f"| {with_stacking:,.0f} | {_ratio(with_stacking, binding)} | {engine:,.0f} "
            f"| {batched:,.0f} (F={n_frames}) | {_ratio(batched, binding)} "
            f"| {both:,.0f} | {batched / both:.2f}x |"
        )
    best = max(row[3] for row in rows)
    measured = ", ".join(f"{rate:,.0f} rows/s at C = {size:,}" for size, rate in limits.items())
    lines += [
        "",
        (
            "Numpy's streaming limit for the checks' arithmetic on this machine, same timing "
            "(`_numpy_limit`: the same-direction longitudinal and the lateral safe distances "
            "and their tolerant comparisons with the `rss.physics` primitives on (C,) arrays, "
            f"nothing else): {measured}. The best batched figure above is "
            f"{best / max(limits.values()):.0%} of the higher one."
        ),
    ]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(run(quick=True))
