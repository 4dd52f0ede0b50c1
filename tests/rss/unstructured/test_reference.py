"""The fast (vectorised) trajectory-set kernels agree with the slow scalar reference."""

from __future__ import annotations

import numpy as np
import pytest

from rss.unstructured.kinematics import (
    Phase,
    Points,
    footprints,
    pedestrian_move,
    time_to_stop,
    vehicle_arc,
    vehicle_integrate,
)
from rss.unstructured.reference_kinematics import (
    Pose,
    ref_footprint,
    ref_pedestrian_move,
    ref_time_to_stop,
    ref_vehicle_arc,
    ref_vehicle_integrate,
)

M = 400
TOL = 1e-9


def _points(rng: np.random.Generator, m: int = M) -> Points:
    speed = rng.choice([0.0, 5e-4, 0.05, 1.0, 8.0, 30.0], m) * rng.uniform(0.5, 1.0, m)
    rate = rng.choice([0.0, 5e-4, -0.002, 0.1, -0.4, 1.5], m) * rng.uniform(0.5, 1.0, m)
    return Points(
        rng.uniform(-50, 50, m),
        rng.uniform(-50, 50, m),
        rng.uniform(-2 * np.pi, 2 * np.pi, m),
        speed,
        rate,
    )


def _pose(p: Points, i: int) -> Pose:
    return Pose(
        float(p.x_m[i]),
        float(p.y_m[i]),
        float(p.yaw_rad[i]),
        float(p.speed_mps[i]),
        float(p.yaw_rate_radps[i]),
    )


def _assert_close(fast: Points, ref: list[Pose]) -> None:
    for name, attr in (
        ("x_m", "x"),
        ("y_m", "y"),
        ("yaw_rad", "yaw"),
        ("speed_mps", "speed"),
        ("yaw_rate_radps", "yaw_rate"),
    ):
        want = np.array([getattr(r, attr) for r in ref])
        np.testing.assert_allclose(
            np.ravel(getattr(fast, name)), want, atol=TOL, rtol=0, err_msg=name
        )


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_vehicle_integrate_matches_the_stepwise_reference(seed: int) -> None:
    rng = np.random.default_rng(seed)
    p = _points(rng)
    accel = rng.choice([-8.0, -4.0, -1e-3, 0.0, 2e-4, 0.5, 3.5], M)
    duration = rng.choice([0.0, 5e-4, 0.1, 0.2, 0.5, 1.0, 2.0, 3.3, 7.9], M)
    ratio = rng.choice([-1.0, -0.25, 0.0, 0.5, 1.0], M)
    vcap = rng.choice([0.0, 10.0, 100.0])
    fast = vehicle_integrate(p, accel, duration, ratio, 0.3, 0.2, vcap, 3.5)
    ref = [
        ref_vehicle_integrate(
            _pose(p, i), accel[i], duration[i], ratio[i], 0.3, 0.2, float(vcap), 3.5
        )
        for i in range(M)
    ]
    _assert_close(fast, ref)


@pytest.mark.parametrize("seed", [3, 4])
def test_two_phase_integration_matches_two_stepwise_drives(seed: int) -> None:
    """``then`` continues from the end point (braking to standstill, caps, mixed durations)."""
    rng = np.random.default_rng(seed)
    p = _points(rng)
    accel = rng.choice([-8.0, -4.0, 0.0, 3.5], (2, M))
    duration = rng.choice([0.0, 5e-4, 0.2, 1.0, 2.0, 3.3], (2, M))
    ratio = rng.choice([-1.0, 0.0, 0.5, 1.0], (2, M))
    vcap = rng.choice([10.0, 100.0], M)
    fast = vehicle_integrate(
        p,
        accel[0],
        duration[0],
        ratio[0],
        0.3,
        0.2,
        vcap,
        3.5,
        Phase(accel[1], duration[1], ratio[1]),
    )
    ref = []
    for i in range(M):
        mid = ref_vehicle_integrate(
            _pose(p, i), accel[0, i], duration[0, i], ratio[0, i], 0.3, 0.2, vcap[i], 3.5
        )
        ref.append(
            ref_vehicle_integrate(
                mid, accel[1, i], duration[1, i], ratio[1, i], 0.3, 0.2, vcap[i], 3.5
            )
        )
    _assert_close(fast, ref)


def test_vehicle_integrate_falls_back_for_tiny_accelerations() -> None:
    """Speeds the running-sum guess cannot reproduce are iterated (same answer)."""
    p = Points(np.zeros(3), np.zeros(3), np.zeros(3), np.array([2e-4, 10.0, 10.2]), np.zeros(3))
    accel = np.array([1e-3, 2e-3, 1e-3])
    fast = vehicle_integrate(p, accel, 2.0, 0.5, 0.3, 0.2, 10.0, 3.5)
    ref = [
        ref_vehicle_integrate(_pose(p, i), accel[i], 2.0, 0.5, 0.3, 0.2, 10.0, 3.5)
        for i in range(3)
    ]
    _assert_close(fast, ref)


def test_vehicle_arc_matches_the_reference() -> None:
    rng = np.random.default_rng(7)
    p = _points(rng)
    accel = rng.choice([-8.0, -4.0, 0.0, 3.5], M)
    duration = rng.choice([0.0, 5e-4, 0.7, 4.0], M)
    fast = vehicle_arc(p, accel, duration, 100.0, 3.5)
    ref = [ref_vehicle_arc(_pose(p, i), accel[i], duration[i], 100.0, 3.5) for i in range(M)]
    _assert_close(fast, ref)


def test_pedestrian_move_matches_the_reference() -> None:
    rng = np.random.default_rng(8)
    p = _points(rng)
    distance = rng.choice([0.0, 5e-4, 0.3, 4.0, 12.0], M)
    ratio = rng.choice([-1.0, -0.5, 0.0, 1e-3, 0.25, 1.0], M)
    fast = pedestrian_move(p, distance, ratio, 2.0)
    ref = [ref_pedestrian_move(_pose(p, i), distance[i], ratio[i], 2.0) for i in range(M)]
    _assert_close(fast, ref)


def test_time_to_stop_and_footprints_match_the_reference() -> None:
    rng = np.random.default_rng(9)
    p = _points(rng)
    rho = rng.choice([0.0, 0.5, 2.0], M)
    fast = time_to_stop(p.speed_mps, rho, 20.0, 3.5, -4.0)
    ref = [
        ref_time_to_stop(float(p.speed_mps[i]), float(rho[i]), 20.0, 3.5, -4.0) for i in range(M)
    ]
    np.testing.assert_allclose(fast, ref, atol=TOL, rtol=0)
    length, width, extra = rng.uniform(0.5, 6, M), rng.uniform(0.5, 2.5, M), rng.uniform(0, 3, M)
    corners = footprints(p, length, width, extra)
    want = [ref_footprint(_pose(p, i), length[i], width[i], extra[i]) for i in range(M)]
    np.testing.assert_allclose(corners, np.array(want), atol=TOL, rtol=0)
