"""The batched set builders and the box-filtered intersections agree with their references.

References: the step-by-step builders (:func:`rss.unstructured.reference_vehicle.vehicle_sets`,
:func:`rss.unstructured.reference_pedestrian.pedestrian_sets`, one dynamics per call, one kernel
call per step) and an all-pairs shapely test of every piece hull.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import pytest
import shapely

from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured.agents import MotionModel, UnstructuredAgents, motion_model
from rss.unstructured.batch import AgentDynamics
from rss.unstructured.engine import intersections, trajectory_sets
from rss.unstructured.pedestrian_batch import pedestrian_sets_batch
from rss.unstructured.reference_pedestrian import pedestrian_sets
from rss.unstructured.reference_vehicle import vehicle_sets
from rss.unstructured.vehicle_batch import vehicle_sets_batch
from tests.rss.unstructured.generators import random_ego, random_frame

if TYPE_CHECKING:
    from rss.unstructured.sets import TrajectorySets

#: A vehicle whose intermediate brake steps collapse (brake_max == brake_min).
FLAT_BRAKE = dataclasses.replace(DEFAULT_VEHICLE_DYNAMICS, brake_max_mps2=-4.0)


def _same_sets(fast: TrajectorySets, ref: TrajectorySets, row: int) -> None:
    for brake in (True, False):
        a, b = fast.polygons(brake=brake)[row], ref.polygons(brake=brake)[0]
        assert a.area > 0.0
        assert shapely.symmetric_difference(a, b).area <= 1e-9 * max(a.area, 1.0)


@pytest.mark.parametrize(
    ("model", "choices", "build", "reference"),
    [
        (
            MotionModel.VEHICLE,
            (DEFAULT_VEHICLE_DYNAMICS, DEFAULT_EGO_DYNAMICS, FLAT_BRAKE),
            vehicle_sets_batch,
            vehicle_sets,
        ),
        (
            MotionModel.PEDESTRIAN,
            (DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_EGO_DYNAMICS),
            pedestrian_sets_batch,
            pedestrian_sets,
        ),
    ],
)
def test_batched_sets_equal_the_stepwise_reference(model, choices, build, reference) -> None:
    """Mixed dynamics values and front extensions in one batch, agent by agent."""
    rng = np.random.default_rng(7)
    agents, _ = random_frame(rng, 60)
    agents = agents.take(np.flatnonzero(motion_model(agents.object_type) == model))
    dyns = [choices[i % len(choices)] for i in range(len(agents))]
    extra = np.where(np.arange(len(agents)) % 4 == 0, 0.5, 0.0)
    fast = build(agents, AgentDynamics.of(dyns, extra))
    assert fast.count == len(agents)
    for i in range(len(agents)):
        ref = reference(agents.take(np.array([i])), dyns[i], extra[i : i + 1])
        _same_sets(fast, ref, i)


def _all_pairs(ego: TrajectorySets, agents: TrajectorySets) -> tuple[np.ndarray, ...]:
    """The three conditions from every piece pair (no filter)."""
    e = np.repeat(np.arange(ego.owner.size), agents.owner.size)
    a = np.tile(np.arange(agents.owner.size), ego.owner.size)
    hit = shapely.intersects(ego.hulls[e], agents.hulls[a])
    out = []
    for mask in (ego.brake[e], agents.brake[a], ego.brake[e] & agents.brake[a]):
        flags = np.zeros(agents.count, dtype=bool)
        flags[agents.owner[a[hit & mask]]] = True
        out.append(flags)
    return tuple(out)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_box_filtered_intersections_equal_all_pairs(seed: int) -> None:
    rng = np.random.default_rng(seed)
    ego = random_ego(rng)
    agents, dyns = random_frame(rng, 30)
    ego_sets = trajectory_sets(ego, [DEFAULT_EGO_DYNAMICS], ego=True)
    agent_sets = trajectory_sets(agents, dyns)
    fast = intersections(ego_sets, agent_sets)
    want = _all_pairs(ego_sets, agent_sets)
    assert any(f.any() for f in want)
    for got, ref in zip(fast, want, strict=True):
        np.testing.assert_array_equal(got, ref)


def test_one_batch_for_the_ego_and_the_vehicles_equals_separate_batches() -> None:
    rng = np.random.default_rng(3)
    ego = random_ego(rng)
    agents, dyns = random_frame(rng, 12)
    both = UnstructuredAgents.concat((ego, agents))
    mask = np.arange(len(both)) == 0
    joint = trajectory_sets(both, [DEFAULT_EGO_DYNAMICS, *dyns], ego=mask)
    alone = trajectory_sets(ego, [DEFAULT_EGO_DYNAMICS], ego=True)
    _same_sets(joint, alone, 0)
    others = trajectory_sets(agents, dyns)
    for brake in (True, False):
        got, want = joint.polygons(brake=brake)[1:], others.polygons(brake=brake)
        assert all(shapely.equals(g, w) for g, w in zip(got, want, strict=True))


def test_hulls_are_built_once_and_are_the_hulls_of_the_points() -> None:
    rng = np.random.default_rng(5)
    agents, dyns = random_frame(rng, 4)
    sets = trajectory_sets(agents, dyns)
    first = sets.hulls_at(np.array([0, 2]))
    assert sets.hulls_at(np.array([2, 0]))[1] is first[0]
    for i, hull in enumerate(sets.hulls):
        points = shapely.multipoints(sets.coords[: sets.size[i], i])
        assert shapely.equals(hull, shapely.convex_hull(points))


def test_grouping_by_settings_keeps_every_agent_its_own_dynamics() -> None:
    """Equal settings from distinct objects share a batch, other settings get their own."""
    rng = np.random.default_rng(11)
    agents, dyns = random_frame(rng, 12)
    copy = dataclasses.replace(DEFAULT_VEHICLE_DYNAMICS.unstructured)
    wide = dataclasses.replace(copy, vehicle_min_radius=6.0)
    mixed = [
        dataclasses.replace(d, unstructured=(copy, wide, d.unstructured)[i % 3])
        if d is DEFAULT_VEHICLE_DYNAMICS
        else d
        for i, d in enumerate(dyns)
    ]
    joint = trajectory_sets(agents, mixed)
    for i in range(len(agents)):
        alone = trajectory_sets(agents.take(np.array([i])), [mixed[i]])
        _same_sets(joint, alone, i)
