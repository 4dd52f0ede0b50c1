"""The compliance filter: a constant-acceleration fit of positions, and stopping as compliance."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.engines.rss.compliance import (
    MIN_SAMPLES,
    MIN_SPAN_NS,
    STOPPED_MPS,
    FittedMotion,
    fit_motion,
    shortfall_of,
)

DT_NS = 100_000_000


def _times(n: int) -> np.ndarray:
    return np.arange(n, dtype=np.int64) * DT_NS


def test_constant_deceleration_along_a_heading_is_fitted_exactly():
    t = _times(11)
    s = 15.0 * (t / 1e9) - 0.5 * 4.0 * (t / 1e9) ** 2
    heading = np.radians(35.0)
    motion = fit_motion(t, 10.0 + s * np.cos(heading), -3.0 + s * np.sin(heading))
    assert motion is not None
    assert motion.accel_mps2 == pytest.approx(-4.0, abs=1e-9)
    assert motion.speed_start_mps == pytest.approx(15.0, abs=1e-9)
    assert motion.speed_end_mps == pytest.approx(11.0, abs=1e-9)
    assert motion.span_s == pytest.approx(1.0)


def test_turning_at_constant_speed_is_no_longitudinal_acceleration():
    t = _times(11)
    radius, speed = 20.0, 10.0
    angle = speed / radius * (t / 1e9)
    motion = fit_motion(t, radius * np.sin(angle), radius * (1 - np.cos(angle)))
    assert motion is not None
    assert abs(motion.accel_mps2) < 0.05  # the centripetal 5 m/s² is lateral
    assert motion.speed_end_mps == pytest.approx(speed, rel=1e-2)


def test_too_short_a_stretch_is_not_judged():
    assert fit_motion(_times(MIN_SAMPLES - 1), np.zeros(MIN_SAMPLES - 1), np.zeros(4)) is None
    t = np.arange(10, dtype=np.int64) * (MIN_SPAN_NS // 10)  # 10 samples over 0.45 s
    assert fit_motion(t, np.arange(10.0), np.zeros(10)) is None


def test_speed_trace_noise_does_not_make_a_shortfall():
    # a car holding 10 m/s, positions with 3 cm noise: measured near 0, not +-8 m/s²
    rng = np.random.default_rng(7)
    t = _times(11)
    shortfalls = []
    for _ in range(200):
        x = 10.0 * t / 1e9 + rng.normal(0.0, 0.03, t.size)
        motion = fit_motion(t, x, rng.normal(0.0, 0.03, t.size))
        assert motion is not None
        shortfalls.append(shortfall_of(motion, -4.0) - 4.0)
    assert max(shortfalls) < 1.0


def test_a_party_that_stops_or_creeps_complies():
    # braking at 4 m/s² from 2 m/s: it stands after 0.5 s, the fit spans 1 s
    t = _times(11)
    tt = np.minimum(t / 1e9, 0.5)
    x = 2.0 * tt - 2.0 * tt**2
    motion = fit_motion(t, x, np.zeros_like(x))
    assert motion is not None
    assert motion.accel_mps2 > -4.0  # a constant-acceleration fit of "brake, then stand"
    assert shortfall_of(motion, -6.0) == pytest.approx(0.0, abs=0.1)
    # creeping at 0.3 m/s: braking by 6 m/s² cannot be asked of it over a second
    creep = FittedMotion(accel_mps2=0.0, speed_start_mps=0.3, speed_end_mps=0.3, span_s=1.0)
    assert shortfall_of(creep, -6.0) == pytest.approx(0.3)
    standing = FittedMotion(
        accel_mps2=2.0, speed_start_mps=0.0, speed_end_mps=STOPPED_MPS / 2, span_s=1.0
    )
    assert shortfall_of(standing, -6.0) == 0.0
    # a party at speed that does not brake falls short by the whole restriction
    cruising = FittedMotion(accel_mps2=0.5, speed_start_mps=12.0, speed_end_mps=12.5, span_s=1.0)
    assert shortfall_of(cruising, -4.0) == pytest.approx(4.5)
