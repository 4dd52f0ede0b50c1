"""Fused kernels of the batched structured engine against their plain definitions.

The batched engine computes relative positions with one difference per bound and masks
filled in place, and rules out similar constellations with one sort of a 64-bit mix of
their keys; here both are checked against the plain formulations element by element,
boundary cases (gaps within a millimetre of the 1 mm precision, touching intervals, NaN)
included.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import pytest

from rss.structured import formulas
from rss.structured.batch import DynamicsArrays, readonly_ints
from rss.structured.extraction import relative_position
from rss.structured.merge import _may_share
from rss.structured.scalar_extract import relative_position as scalar_relative_position
from rss.structured.stacking import stack_constellations
from tests.rss.structured.test_invalid_input import _constellation

if TYPE_CHECKING:
    from rss.structured.batch import ConstellationBatch


def _intervals(rng: np.random.Generator, n: int) -> tuple[np.ndarray, ...]:
    """Random intervals whose ends lie near each other (gaps of 0, ±1 mm, a few m)."""
    start = rng.uniform(-5.0, 5.0, n)
    length = rng.choice([0.0, 0.001, 0.0009999, 0.0010001, 2.0, 4.5], n)
    other_start = start + rng.choice([-6.0, -0.001, -0.0005, 0.0, 0.0005, 0.001, 3.0], n)
    other_length = rng.choice([0.0, 0.001, 1.0, 4.5, 9.0], n)
    ego_min, other_min = start, other_start
    ego_max, other_max = start + length, other_start + other_length
    nan_rows = rng.random(n) < 0.02
    ego_min[nan_rows] = np.nan
    return ego_min, ego_max, other_min, other_max


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_relative_position_matches_its_definition(seed: int) -> None:
    ego_min, ego_max, other_min, other_max = _intervals(np.random.default_rng(seed), 4000)
    position, distance = relative_position(ego_min, ego_max, other_min, other_max)
    want = [
        scalar_relative_position(*values)
        for values in zip(
            ego_min.tolist(), ego_max.tolist(), other_min.tolist(), other_max.tolist(), strict=True
        )
    ]
    assert position.dtype == np.int64
    assert position.tolist() == [code for code, _ in want]
    np.testing.assert_allclose(distance, [gap for _, gap in want], rtol=0.0, atol=1e-12)
    assert set(position.tolist()) == {0, 1, 2, 3, 4}  # every code occurs


def test_relative_position_broadcasts_rows() -> None:
    rng = np.random.default_rng(7)
    rows = np.stack(_intervals(rng, 300)).reshape(4, 3, 100)
    position, distance = relative_position(*rows)
    for k in range(3):
        row_position, row_distance = relative_position(*rows[:, k])
        assert position[k].tolist() == row_position.tolist()
        np.testing.assert_allclose(distance[k], row_distance, rtol=0.0, atol=0.0)


def _batch_with_ids(ego_ids: list[int], other_ids: list[int]) -> ConstellationBatch:
    base = _constellation()
    rows = [
        dataclasses.replace(
            base,
            ego=dataclasses.replace(base.ego, object_id=e),
            other=dataclasses.replace(base.other, object_id=o),
        )
        for e, o in zip(ego_ids, other_ids, strict=True)
    ]
    return stack_constellations(rows)


def test_may_share_finds_every_repeated_key() -> None:
    rng = np.random.default_rng(3)
    n = 400
    others = rng.permutation(n) + 1
    batch = _batch_with_ids([0] * n, others.tolist())
    frames = readonly_ints(np.zeros(n, dtype=np.int64))
    rows = np.arange(n)
    assert not _may_share(frames, batch, rows)
    # one object twice in one frame: found; the same object in two frames: not a repeat
    twice = others.copy()
    twice[17] = twice[250]
    batch = _batch_with_ids([0] * n, twice.tolist())
    assert _may_share(frames, batch, rows)
    split = np.zeros(n, dtype=np.int64)
    split[17] = 1
    assert not _may_share(split, batch, rows)
    # rows left out of the selection do not count
    assert not _may_share(frames[rows != 17], batch, rows[rows != 17])


def _dynamics(rng: np.random.Generator, n: int) -> DynamicsArrays:
    brake_max = rng.uniform(-10.0, -6.0, n)
    brake_min = rng.uniform(-6.0, -3.0, n)
    return DynamicsArrays(
        accel_max_mps2=rng.choice([0.0, 2.0, 3.5], n),
        brake_max_mps2=brake_max,
        brake_min_mps2=brake_min,
        brake_min_correct_mps2=rng.uniform(-3.0, -1.0, n),
        lat_accel_max_mps2=rng.choice([0.0, 0.2, 1.0], n),
        lat_brake_min_mps2=rng.uniform(-1.5, -0.5, n),
        lateral_fluctuation_margin_m=rng.uniform(0.0, 0.3, n),
        response_time_s=rng.uniform(0.2, 2.0, n),
        max_speed_on_acceleration_mps=rng.uniform(5.0, 40.0, n),
        min_longitudinal_safety_distance_m=rng.uniform(0.0, 2.0, n),
    )


def _only(dyn: DynamicsArrays, names: tuple[str, ...]) -> DynamicsArrays:
    """``dyn`` with every field but ``names`` NaN (a formula reading one shows NaN)."""
    nan = np.full(dyn.response_time_s.shape, np.nan)
    fields = {
        f.name: getattr(dyn, f.name) if f.name in names else nan for f in dataclasses.fields(dyn)
    }
    return DynamicsArrays(**fields)


def test_field_lists_name_everything_the_formulas_read() -> None:
    # pick_fields picks only the named fields: a formula reading another one would get the
    # wrong party's value there, so each list must cover what its formula reads
    rng = np.random.default_rng(11)
    n = 500
    a, b = _dynamics(rng, n), _dynamics(rng, n)
    v1, v2 = rng.uniform(0.0, 30.0, n), rng.uniform(-2.0, 2.0, n)
    same = formulas.safe_longitudinal_distance_same
    opposite = formulas.safe_longitudinal_distance_opposite
    lateral = formulas.safe_lateral_distance
    checks = [
        (same, formulas.SAME_FOLLOWER_FIELDS, formulas.SAME_LEADER_FIELDS, v1),
        (opposite, formulas.OPPOSITE_FIELDS, formulas.OPPOSITE_FIELDS, v1),
        (lateral, formulas.LATERAL_FIELDS, formulas.LATERAL_FIELDS, v2),
    ]
    for formula, first, second, speed in checks:
        full = formula(a, speed, b, speed[::-1])
        reduced = formula(_only(a, first), speed, _only(b, second), speed[::-1])
        assert np.isfinite(full).all()
        np.testing.assert_allclose(reduced, full, rtol=0.0, atol=0.0)
    mask = rng.random(n) < 0.5
    picked = formulas.pick_fields(mask, a, b, formulas.LATERAL_FIELDS)
    for name in formulas.LATERAL_FIELDS:
        assert (
            getattr(picked, name).tolist()
            == np.where(mask, getattr(a, name), getattr(b, name)).tolist()
        )
