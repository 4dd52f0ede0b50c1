"""Vectorised kernels vs the scalar reference and vs the binding's own functions."""

from __future__ import annotations

import numpy as np
import pytest

from rss import physics, reference
from tests.rss.oracle import load_ad_rss


def _inputs(seed: int, n: int) -> list[tuple[float, float, float, float, float, float]]:
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        v = float(rng.choice([0.0, rng.uniform(0, 40), rng.uniform(0, 0.002)]))
        cap = float(rng.choice([rng.uniform(0, 40), 100.0, v]))
        rho = float(rng.uniform(0.1, 3))
        if rng.random() < 0.5:
            a1, a2 = float(rng.choice([rng.uniform(0, 4), 0.0])), float(rng.uniform(-8, -0.5))
        else:
            a1 = float(rng.uniform(-8, -0.5))
            a2 = a1
        s = float(rng.choice([rng.uniform(0, 150), 0.0, rng.uniform(0.002, 0.01)]))
        out.append((v, cap, rho, a1, a2, s))
    return out


def test_kernels_match_scalar_reference() -> None:
    rows = _inputs(1, 3000)
    v, cap, rho, a1, a2, s = (np.array(col) for col in zip(*rows, strict=True))
    ttc = physics.time_to_cover_distance(v, cap, rho, a1, a2, s)
    v1, d1 = physics.accelerated_limited_movement(v, cap, a1, rho)
    stated = physics.stated_braking_longitudinal(v, cap, rho, np.abs(a1), a2)
    lateral = physics.stated_braking_lateral(v - 20.0, rho, np.abs(a1) / 10.0, a2 / 10.0)
    for i, row in enumerate(rows):
        assert ttc[i] == pytest.approx(reference.time_to_cover_distance(*row), abs=1e-9), row
        ref_v, ref_d = reference.accelerated_limited_movement(row[0], row[1], row[3], row[2])
        assert (v1[i], d1[i]) == pytest.approx((ref_v, ref_d), abs=1e-9)
        assert stated[i] == pytest.approx(
            reference.stated_braking_longitudinal(row[0], row[1], row[2], abs(row[3]), row[4]),
            abs=1e-9,
        )
        assert lateral[i] == pytest.approx(
            reference.stated_braking_lateral(
                row[0] - 20.0, row[2], abs(row[3]) / 10.0, row[4] / 10.0
            ),
            abs=1e-9,
        )


@pytest.mark.oracle
def test_kernels_match_binding_functions() -> None:
    ad = load_ad_rss()
    p, core = ad.physics, ad.rss.core
    for row in _inputs(2, 2000):
        v, cap, rho, a1, a2, s = row
        out = p.Duration(0.0)
        try:
            ok = core.calculateTimeToCoverDistance(
                p.Speed(v),
                p.Speed(cap),
                p.Duration(rho),
                p.Acceleration(a1),
                p.Acceleration(a2),
                p.Distance(s),
                out,
            )
        except IndexError:  # the binding computes a NaN for some inputs and throws
            continue
        assert ok
        ours = physics.time_to_cover_distance(*(np.array(x) for x in row))
        assert float(ours) == pytest.approx(out.mDuration, abs=1e-6), row
        speed, dist = p.Speed(0.0), p.Distance(0.0)
        assert core.calculateAcceleratedLimitedMovement(
            p.Speed(v), p.Speed(cap), p.Acceleration(a1), p.Duration(rho), speed, dist
        )
        ours_v, ours_d = physics.accelerated_limited_movement(
            *(np.array(x) for x in (v, cap, a1, rho))
        )
        assert (float(ours_v), float(ours_d)) == pytest.approx(
            (speed.mSpeed, dist.mDistance), abs=1e-9
        )


def test_tolerant_comparisons() -> None:
    assert not physics.gt(59.7239, 59.722994, physics.DISTANCE_PRECISION)
    assert physics.gt(59.7241, 59.722994, physics.DISTANCE_PRECISION)
    assert physics.eq(6.0, 6.0005, physics.DISTANCE_PRECISION)
    assert float(physics.tmax(-0.0005, 0.0, physics.DISTANCE_PRECISION)) == -0.0005


def test_tolerant_comparisons_match_their_definitions() -> None:
    """One-subtraction forms vs ``a > b and not a == b`` (and the others) element by element."""
    rng = np.random.default_rng(0)
    p = physics.DISTANCE_PRECISION
    base = rng.uniform(-10.0, 10.0, 4000)
    offsets = np.array([0.0, p, -p, p / 2, -p / 2, np.nextafter(p, 0.0), np.nextafter(p, 1.0)])
    a = np.concatenate((base, base, [np.nan, np.inf, -np.inf, np.inf, 1.0, np.nan]))
    b = np.concatenate(
        (
            base + rng.choice(offsets, 4000),
            rng.uniform(-10.0, 10.0, 4000),
            [1.0, np.inf, -np.inf, 1.0, np.inf, np.nan],
        )
    )
    with np.errstate(invalid="ignore"):  # inf - inf
        _compare_all(a, b, p)


def _compare_all(a: np.ndarray, b: np.ndarray, p: float) -> None:
    for i in range(a.size):
        x, y = float(a[i]), float(b[i])
        eq = abs(x - y) < p
        gt = x > y and not eq
        lt = x < y and not eq
        assert bool(physics.gt(x, y, p)) == gt, (x, y)
        assert bool(physics.lt(x, y, p)) == lt, (x, y)
        assert bool(physics.ge(x, y, p)) == (gt or eq), (x, y)
        assert bool(physics.le(x, y, p)) == (lt or eq), (x, y)
    assert (
        physics.gt(a, b, p)
        == np.array([bool(physics.gt(x, y, p)) for x, y in zip(a, b, strict=True)])
    ).all()
