"""Hypothesis properties of the trajectory sets and decisions (our engine only)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rss.model import ObjectType
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured import UnstructuredAgents, check_unstructured, trajectory_sets

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics

SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
#: Area slack of the sampled polygons [m²] (the sides are sampled, not exact envelopes).
SLACK = 0.5

speeds = st.floats(0.0, 12.0)
angles = st.floats(-np.pi, np.pi)
kinds = st.sampled_from([ObjectType.OtherVehicle, ObjectType.Pedestrian])


def _one(kind: ObjectType, yaw: float, speed: float, yaw_rate: float = 0.0) -> UnstructuredAgents:
    pedestrian = kind == ObjectType.Pedestrian
    return UnstructuredAgents.from_rows(
        [
            {
                "object_id": 1,
                "object_type": int(kind),
                "x_m": 0.0,
                "y_m": 0.0,
                "yaw_rad": yaw,
                "speed_min_mps": speed,
                "speed_max_mps": speed,
                "yaw_rate_radps": 0.0 if pedestrian else yaw_rate,
                "length_m": 0.6 if pedestrian else 4.5,
                "width_m": 0.6 if pedestrian else 2.0,
            }
        ]
    )


def _dyn(kind: ObjectType) -> RssDynamics:
    return (
        DEFAULT_PEDESTRIAN_DYNAMICS if kind == ObjectType.Pedestrian else DEFAULT_VEHICLE_DYNAMICS
    )


@SETTINGS
@given(kinds, angles, speeds, st.floats(-0.4, 0.4))
def test_brake_set_lies_in_the_continue_forward_set(kind, yaw, speed, rate) -> None:
    sets = trajectory_sets(_one(kind, yaw, speed, rate), [_dyn(kind)])
    brake, forward = sets.polygons(brake=True)[0], sets.polygons(brake=False)[0]
    assert shapely.difference(brake, forward).area <= 1e-6


@SETTINGS
@given(kinds, angles, speeds, st.floats(0.1, 2.0), st.floats(0.2, 1.5))
def test_sets_grow_with_response_time_and_speed(kind, yaw, speed, rho, factor) -> None:
    """Where the model is monotone: pedestrians at walking speed (a fast pedestrian's
    response-time arc wraps around its 2 m turning circle, and the sampled set shrinks)."""
    if kind == ObjectType.Pedestrian:
        speed = min(speed, 2.0)
    agent, dyn = _one(kind, yaw, speed), _dyn(kind)
    base = trajectory_sets(agent, [dataclasses.replace(dyn, response_time_s=rho)])
    longer = trajectory_sets(agent, [dataclasses.replace(dyn, response_time_s=rho * factor)])
    faster = trajectory_sets(_one(kind, yaw, speed * factor), [dyn])
    for brake in (True, False):
        a = base.polygons(brake=brake)[0]
        if factor >= 1.0:
            assert longer.polygons(brake=brake)[0].area >= a.area - SLACK
            assert (
                faster.polygons(brake=False)[0].area
                >= trajectory_sets(agent, [dyn]).polygons(brake=False)[0].area - SLACK
            )
        else:
            assert longer.polygons(brake=brake)[0].area <= a.area + SLACK


def _scene(
    data: st.DataObject,
) -> tuple[UnstructuredAgents, UnstructuredAgents, list[RssDynamics]]:
    n = data.draw(st.integers(1, 4))
    rows, dyns = [], []
    for i in range(n):
        kind = data.draw(kinds)
        r, phi = data.draw(st.floats(3.0, 30.0)), data.draw(angles)
        one = _one(kind, data.draw(angles), data.draw(st.sampled_from([0.0, 0.05, 1.0, 5.0])))
        row = {f: float(getattr(one, f)[0]) for f in one.__dataclass_fields__}
        row.update(object_id=i + 1, object_type=int(kind), x_m=r * np.cos(phi), y_m=r * np.sin(phi))
        rows.append(row)
        dyns.append(_dyn(kind))
    ego = _one(
        ObjectType.EgoVehicle, data.draw(angles), data.draw(st.sampled_from([0.0, 2.0, 8.0]))
    )
    return ego, UnstructuredAgents.from_rows(rows), dyns


def _moved(a: UnstructuredAgents, theta: float, dx: float, dy: float) -> UnstructuredAgents:
    c, s = np.cos(theta), np.sin(theta)
    yaw = (a.yaw_rad + theta + np.pi) % (2 * np.pi) - np.pi
    return dataclasses.replace(
        a, x_m=c * a.x_m - s * a.y_m + dx, y_m=s * a.x_m + c * a.y_m + dy, yaw_rad=yaw
    )


@SETTINGS
@given(st.data(), angles, st.floats(-500.0, 500.0), st.floats(-500.0, 500.0))
def test_decisions_are_invariant_under_rigid_motion(data, theta, dx, dy) -> None:
    ego, agents, dyns = _scene(data)
    before, _ = check_unstructured(ego, agents, DEFAULT_EGO_DYNAMICS, dyns, DEFAULT_EGO_DYNAMICS)
    after, _ = check_unstructured(
        _moved(ego, theta, dx, dy),
        _moved(agents, theta, dx, dy),
        DEFAULT_EGO_DYNAMICS,
        dyns,
        DEFAULT_EGO_DYNAMICS,
    )
    np.testing.assert_array_equal(before.decisions.response, after.decisions.response)
    np.testing.assert_array_equal(before.decisions.is_safe, after.decisions.is_safe)
    drive = np.isfinite(before.decisions.heading_begin_rad)
    turned = np.angle(np.exp(1j * (before.decisions.heading_begin_rad[drive] + theta)))
    np.testing.assert_allclose(
        np.angle(np.exp(1j * (turned - after.decisions.heading_begin_rad[drive]))), 0.0, atol=1e-9
    )
