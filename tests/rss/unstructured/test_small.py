"""The point-by-point set builders of small batches equal the batched builders to the bit.

:mod:`rss.unstructured.vehicle_small` and :mod:`rss.unstructured.pedestrian_small` (compiled
with mypyc when the build is fresh, else run from their sources: both must agree) against
:func:`rss.unstructured.vehicle_batch.vehicle_sets_batch` and the batched moving-pedestrian
builder, on Hypothesis batches of up to :data:`SMALL_SETS_MAX` agents with their own
dynamics values; then whole frames with the small path on and off.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rss.dynamics import UnstructuredSettings
from rss.model import ObjectType
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured import UnstructuredAgents, check_unstructured, convex, engine, intersect
from rss.unstructured.batch import AgentDynamics
from rss.unstructured.kinematics import Points, footprints
from rss.unstructured.pedestrian_batch import pedestrian_sets_batch
from rss.unstructured.pedestrian_small import pedestrian_moving_small
from rss.unstructured.scalar_motion import corner_table
from rss.unstructured.vehicle_batch import vehicle_sets_batch
from rss.unstructured.vehicle_small import SMALL_SETS_MAX, vehicle_sets_small
from tests.rss.unstructured.generators import random_ego, random_frame, random_sequence

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.unstructured.sets import TrajectorySets

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])

#: Settings variants: the defaults, more intermediate steps, collapsed steps.
VARIANTS = (
    UnstructuredSettings(),
    UnstructuredSettings(
        vehicle_front_intermediate_yaw_rate_change_ratio_steps=1,
        vehicle_back_intermediate_yaw_rate_change_ratio_steps=2,
        vehicle_brake_intermediate_acceleration_steps=3,
        vehicle_continue_forward_intermediate_acceleration_steps=2,
        vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps=1,
        pedestrian_front_intermediate_heading_change_ratio_steps=2,
        pedestrian_brake_intermediate_acceleration_steps=1,
        pedestrian_continue_forward_intermediate_acceleration_steps=2,
        vehicle_trajectory_calculation_step=0.3,
    ),
    UnstructuredSettings(
        vehicle_front_intermediate_yaw_rate_change_ratio_steps=0,
        vehicle_brake_intermediate_acceleration_steps=0,
        vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps=0,
        pedestrian_front_intermediate_heading_change_ratio_steps=0,
        pedestrian_continue_forward_intermediate_heading_change_ratio_steps=0,
        pedestrian_brake_intermediate_acceleration_steps=0,
        vehicle_min_radius=0.5,
    ),
)


@st.composite
def _dynamics(draw: st.DrawFn, base: RssDynamics) -> RssDynamics:
    brake_max = draw(st.floats(-10.0, -1.0))
    return dataclasses.replace(
        base,
        response_time_s=draw(st.sampled_from([0.2, 0.5, 1.0, 2.0, draw(st.floats(0.05, 3.0))])),
        accel_max_mps2=draw(st.sampled_from([0.0, 1e-5, 2.0, draw(st.floats(0.0, 6.0))])),
        brake_max_mps2=brake_max,
        brake_min_mps2=draw(st.sampled_from([brake_max, draw(st.floats(brake_max, -0.5))])),
        brake_min_correct_mps2=-0.4,
        max_speed_on_acceleration_mps=draw(st.sampled_from([0.0, 5.0, 100.0])),
    )


@st.composite
def _batch(draw: st.DrawFn, kind: ObjectType) -> tuple[UnstructuredAgents, AgentDynamics]:
    n = draw(st.integers(1, SMALL_SETS_MAX))
    pedestrian = kind == ObjectType.Pedestrian
    top = 3.0 if pedestrian else 25.0
    speed = st.sampled_from([0.0, 5e-4, 0.05, draw(st.floats(0.0, top)), draw(st.floats(0.0, top))])
    rows, dynamics = [], []
    for i in range(n):
        low, high = sorted((draw(speed), draw(speed)))
        moving_high = high if not pedestrian or high > 1e-3 else 1.0  # moving: the twin's part
        rows.append(
            {
                "object_id": i,
                "object_type": int(kind),
                "x_m": draw(st.floats(-500.0, 500.0)),
                "y_m": draw(st.floats(-500.0, 500.0)),
                "yaw_rad": draw(st.floats(-2.0 * np.pi, 2.0 * np.pi)),
                "speed_min_mps": low,
                "speed_max_mps": moving_high,
                "yaw_rate_radps": draw(st.sampled_from([0.0, 5e-4, draw(st.floats(-1.0, 1.0))])),
                "length_m": draw(st.floats(0.3, 8.0)),
                "width_m": draw(st.floats(0.3, 3.0)),
            }
        )
        base = DEFAULT_PEDESTRIAN_DYNAMICS if pedestrian else DEFAULT_VEHICLE_DYNAMICS
        dynamics.append(draw(_dynamics(base)))
    u = draw(st.sampled_from(VARIANTS))
    dynamics = [dataclasses.replace(d, unstructured=u) for d in dynamics]
    extra = np.array([draw(st.sampled_from([0.0, 0.0, 1.5])) for _ in range(n)])
    return UnstructuredAgents.from_rows(rows), AgentDynamics.of(dynamics, extra)


def _same_bits(fast: TrajectorySets, ref: TrajectorySets) -> None:
    assert fast.coords.shape == ref.coords.shape
    assert np.array_equal(fast.coords.view(np.int64), ref.coords.view(np.int64))
    for name in ("size", "owner", "brake"):
        assert np.array_equal(getattr(fast, name), getattr(ref, name))
    assert fast.count == ref.count


@SETTINGS
@given(_batch(ObjectType.OtherVehicle))
def test_vehicle_sets_point_by_point_equal_the_batched_sets(batch) -> None:
    agents, dyn = batch
    small = vehicle_sets_small(agents, dyn)
    assert small is not None
    _same_bits(small, vehicle_sets_batch(agents, dyn))


@SETTINGS
@given(_batch(ObjectType.Pedestrian))
def test_moving_pedestrian_sets_point_by_point_equal_the_batched_sets(batch) -> None:
    agents, dyn = batch
    _same_bits(
        pedestrian_sets_batch(agents, dyn, pedestrian_moving_small),
        pedestrian_sets_batch(agents, dyn),
    )


def test_a_negative_zero_speed_goes_to_the_batched_builder() -> None:
    agents, dynamics = random_frame(np.random.default_rng(3), 1, pedestrian_share=0.0)
    zero = dataclasses.replace(agents, speed_min_mps=np.array([-0.0]))
    assert vehicle_sets_small(zero, AgentDynamics.of(dynamics, np.zeros(1))) is None


def _frames(seed: int) -> list[tuple[UnstructuredAgents, UnstructuredAgents, list[RssDynamics]]]:
    rng = np.random.default_rng(seed)
    frames = [(random_ego(rng), *random_frame(rng, int(rng.integers(0, 6)))) for _ in range(20)]
    return frames + random_sequence(rng, 12, 3)


def _run(frames, *, small: bool, monkeypatch: pytest.MonkeyPatch) -> list[tuple[Any, Any]]:
    monkeypatch.setattr(engine, "small_batch", lambda agents: small and agents <= SMALL_SETS_MAX)
    monkeypatch.setattr(intersect, "closed_form", lambda pairs: small and pairs <= 10_000)
    out, memory = [], None
    for ego, agents, dynamics in frames:
        result, memory = check_unstructured(
            ego, agents, DEFAULT_EGO_DYNAMICS, dynamics, DEFAULT_EGO_DYNAMICS, memory
        )
        out.append((result, memory))
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_frames_with_the_small_path_equal_the_batched_frames(seed, monkeypatch) -> None:
    """Random frames and a drive-away sequence: results and memories field by field."""
    frames = _frames(seed)
    fast = _run(frames, small=True, monkeypatch=monkeypatch)
    slow = _run(frames, small=False, monkeypatch=monkeypatch)
    for (a, mem_a), (b, mem_b) in zip(fast, slow, strict=True):
        for sets in ("ego_sets", "agent_sets"):
            _same_bits(getattr(a, sets), getattr(b, sets))
        assert a.proper_response == b.proper_response
        for name in a.decisions.__dataclass_fields__:
            assert np.array_equal(
                getattr(a.decisions, name), getattr(b.decisions, name), equal_nan=True
            )
        for name in mem_a.__dataclass_fields__:
            assert np.array_equal(getattr(mem_a, name), getattr(mem_b, name))


def _square(x: float, y: float, side: float = 1.0, turn: float = 0.0) -> list[list[float]]:
    c, s = np.cos(turn), np.sin(turn)
    corners = [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
    return [[x + c * u - s * v, y + s * u + c * v] for u, v in corners]


def _shapely_says(a: list[list[float]], b: list[list[float]]) -> bool:
    return bool(
        shapely.intersects(shapely.MultiPoint(a).convex_hull, shapely.MultiPoint(b).convex_hull)
    )


@SETTINGS
@given(
    st.floats(-3.0, 3.0),
    st.floats(-3.0, 3.0),
    st.floats(-np.pi, np.pi),
    st.floats(0.1, 2.0),
    st.sampled_from([0.0, 1e3, -4e5]),
)
def test_closed_form_verdicts_are_shapely_verdicts(dx, dy, turn, side, offset) -> None:
    """Where the closed form decides, shapely agrees (near-touching pairs stay unsure)."""
    a = _square(offset, offset)
    b = _square(offset + dx, offset + dy, side, turn)
    verdict = convex.verdict(convex.hull(a, 4), convex.hull(b, 4))
    if verdict != convex.UNSURE:
        assert (verdict == convex.OVERLAP) == _shapely_says(a, b)


@pytest.mark.parametrize(
    "b",
    [
        _square(1.0, 0.0),  # a shared edge
        _square(1.0, 1.0),  # a shared corner
        _square(1.0 + 1e-12, 0.0),  # apart by less than the margin
        _square(0.5, 0.5, 1.0, np.pi / 4),  # a corner inside
    ],
)
def test_touching_pairs_are_left_to_shapely_or_agree(b) -> None:
    a = _square(0.0, 0.0)
    verdict = convex.verdict(convex.hull(a, 4), convex.hull(b, 4))
    assert verdict in {convex.UNSURE, convex.OVERLAP}
    assert verdict == convex.UNSURE or _shapely_says(a, b)


@pytest.mark.parametrize("seed", [4, 5])
def test_closed_form_verdicts_of_real_pieces_are_shapely_verdicts(seed) -> None:
    """Every ego piece against every agent piece of random frames."""
    rng = np.random.default_rng(seed)
    decided = 0
    for _ in range(6):
        ego, (agents, dynamics) = random_ego(rng), random_frame(rng, 3)
        result, _ = check_unstructured(
            ego, agents, DEFAULT_EGO_DYNAMICS, dynamics, DEFAULT_EGO_DYNAMICS
        )
        own, other = result.ego_sets, result.agent_sets
        e, a = (
            x.ravel() for x in np.meshgrid(np.arange(own.size.size), np.arange(other.size.size))
        )
        points = [np.swapaxes(s.coords, 0, 1).tolist() for s in (own, other)]
        found = convex.verdicts(
            (points[0], own.size.tolist()),
            (points[1], other.size.tolist()),
            (e.tolist(), a.tolist()),
        )
        truth = shapely.intersects(own.hulls[e], other.hulls[a])
        for verdict, expected in zip(found, truth, strict=True):
            if verdict != convex.UNSURE:
                decided += 1
                assert (verdict == convex.OVERLAP) == expected
    assert decided > 0


_ODD = st.sampled_from([0.0, -0.0, 1.0, -1.0, 7.0, 1e-9, np.nan, np.inf, -np.inf, 6.3, -6.3])


@SETTINGS
@given(
    st.lists(
        st.tuples(st.sampled_from([0, 2, 3, 4, 8, -1]), st.lists(_ODD, min_size=9, max_size=9)),
        min_size=1,
        max_size=8,
    )
)
def test_row_by_row_validity_equals_the_array_test(rows) -> None:
    """Few agents are checked row by row; a table of more rows takes the array test."""
    fields = [f for f in UnstructuredAgents.__dataclass_fields__ if not f.startswith("object")]
    table = UnstructuredAgents.from_rows(
        [
            {"object_id": i, "object_type": kind, **dict(zip(fields, values, strict=True))}
            for i, (kind, values) in enumerate(rows)
        ]
    )
    padded = UnstructuredAgents.concat([table] * 9)  # beyond the row-by-row size
    assert np.array_equal(table.valid(), padded.valid()[: len(table)])
    unknown = dataclasses.replace(table, object_type=np.full(len(table), 99))
    with pytest.raises(IndexError):
        unknown.valid()


_COORD = st.floats(-5e3, 5e3, allow_nan=False)


@SETTINGS
@given(
    st.integers(1, SMALL_SETS_MAX).flatmap(
        lambda n: st.tuples(
            st.lists(
                st.lists(st.tuples(_COORD, _COORD, st.floats(-7.0, 7.0)), min_size=3, max_size=3),
                min_size=n,
                max_size=n,
            ),
            st.lists(
                st.tuples(st.floats(0.3, 8.0), st.floats(0.3, 3.0), st.sampled_from([0.0, 1.5])),
                min_size=n,
                max_size=n,
            ),
        )
    )
)
def test_corner_table_point_by_point_equals_the_array_footprints(case) -> None:
    """``scalar_motion.corner_table`` gives the corners of ``kinematics.footprints`` to the bit."""
    poses, sizes = case
    table = np.array(poses, dtype=np.float64)  # (N, R, 3)
    x, y, yaw = (table[:, :, k].T for k in range(3))
    length, width, extra = (np.array([s[k] for s in sizes]) for k in range(3))
    corners = footprints(Points(x, y, yaw, x, yaw), length, width, extra)  # (R, N, 4, 2)
    expected = corners.transpose(0, 2, 1, 3).reshape(-1, len(poses), 2)
    flat = corner_table(poses, [(s[0], s[1]) for s in sizes], extra.tolist())
    got = np.array(flat).reshape(-1, len(poses), 2)
    assert got.tobytes() == expected.tobytes()
