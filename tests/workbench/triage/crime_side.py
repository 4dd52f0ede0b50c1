"""TTC and required deceleration of commonroad-crime 0.4.5 (CriMe) on a CommonRoad scenario.

CriMe is not ours and is not in the project venv (it brings commonroad-io, which pins
protobuf); ``make oracle-crime`` runs it in a side venv that also sees the project venv. Its
quirks on the NGSIM scenarios (../shared/reference/commonroad-crime-notes.md) are worked
around as follows:

- the scenario is translated to the ego's first position and rotated by minus the ego's mean
  heading, so the ego points along +x (CriMe multiplies speeds by the cosine of the lane's
  absolute heading and adds half a car length to x and y);
- the lanelet network is rebuilt after the rotation (commonroad-io keeps its old index);
- the reference path is the ego's own recorded trajectory, extended by 300 m straight at both
  ends (CriMe's default path is too short on these maps);
- every acceleration is set to 0 after CriMe derived them (it drops the other's sign), so
  TTC and ALongReq are the constant-speed TTC and required deceleration;
- the in-path gate (lateral offset on that path at most half the two widths + 0.5 m) is ours,
  CriMe's same-lane test lets adjacent-lane cars through;
- TypeErrors raised inside TTC (junctions, map ends) are caught and counted.

Only pair-steps within ``RANGE_M`` of the ego are computed (a 1.5 s TTC needs a closing speed
over 100 m/s beyond), ALongReq only for pair-steps in path and closing (elsewhere it cannot flag).
"""

from __future__ import annotations

import importlib
import logging
import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from tests.workbench.triage.conflicts import (
    IN_PATH_MARGIN_M,
    PairStep,
    conflicts,
    flag_agreement,
    near_path,
    numpy_pair_steps,
)

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

#: Pair-steps farther apart (centre to centre) are not computed [m].
RANGE_M = 150.0
#: The reference path is extended this far straight beyond the ego's first and last position.
PATH_EXTENSION_M = 300.0
#: Vehicle types that can play the ego (as loaders.commonroad_scenario.VEHICLE_TYPES).
EGO_TYPES = frozenset({"CAR", "TRUCK", "BUS", "MOTORCYCLE", "TAXI", "PRIORITY_VEHICLE"})


def available() -> bool:
    """Whether commonroad-crime can be imported here."""
    try:
        importlib.import_module("commonroad_crime")
    except ImportError:
        return False
    return True


@dataclass(slots=True)
class CrimeRun:
    """CriMe's pair-steps on one scenario.

    Attributes:
        ego_id: The vehicle in the ego role.
        ego_first_step: The ego's first time step (frame 0 of our loader).
        pair_steps: Every computed pair-step.
        errors: Exceptions caught inside CriMe, by type name.
        seconds: Wall time of the run [s].
    """

    ego_id: str
    ego_first_step: int
    pair_steps: list[PairStep] = field(default_factory=list)
    errors: dict[str, int] = field(default_factory=dict)
    seconds: float = 0.0


def _mod(name: str) -> Any:
    return importlib.import_module(name)


def _states(obstacle: Any) -> list[Any]:
    trajectory = getattr(obstacle.prediction, "trajectory", None)
    return [obstacle.initial_state, *(trajectory.state_list if trajectory else ())]


def pick_ego(scenario: Any) -> Any:
    """The longest-lived vehicle (most states), ties by the lowest id: our loader's choice."""
    vehicles = [o for o in scenario.dynamic_obstacles if o.obstacle_type.name in EGO_TYPES]
    return min(vehicles, key=lambda o: (-len(_states(o)), int(o.obstacle_id)))


def _rotated(xml: Path) -> tuple[Any, Any]:
    """The scenario with the ego at the origin pointing along +x, its lane index rebuilt."""
    scenario, _ = _mod("commonroad.common.file_reader").CommonRoadFileReader(str(xml)).open()
    ego = pick_ego(scenario)
    yaw = np.array([s.orientation for s in _states(ego)])
    heading = float(math.atan2(np.sin(yaw).mean(), np.cos(yaw).mean()))
    scenario.translate_rotate(-np.asarray(ego.initial_state.position, dtype=float), -heading)
    lanelet = _mod("commonroad.scenario.lanelet")
    network = lanelet.LaneletNetwork.create_from_lanelet_network(scenario.lanelet_network)
    scenario.replace_lanelet_network(network)
    ego = scenario.obstacle_by_id(ego.obstacle_id)
    scenario.assign_obstacles_to_lanelets(
        time_steps=[ego.initial_state.time_step], obstacle_ids={ego.obstacle_id}
    )
    assignment = ego.prediction.center_lanelet_assignment
    if not assignment or not assignment.get(ego.initial_state.time_step):
        # CriMe's default path needs a lanelet under the ego at its start: the nearest one.
        start = np.asarray(ego.initial_state.position, dtype=float)
        nearest = min(
            network.lanelets,
            key=lambda la: float(np.min(np.linalg.norm(la.center_vertices - start, axis=1))),
        )
        ego.prediction.center_lanelet_assignment = {
            ego.initial_state.time_step: {nearest.lanelet_id}
        }
    return scenario, ego


def _reference_path(ego: Any) -> Any:
    """Curvilinear frame along the ego's recorded positions, 1 m apart, extended both ways."""
    points = np.array([s.position for s in _states(ego)], dtype=float)
    kept = [points[0]]
    for p in points[1:]:
        if np.linalg.norm(p - kept[-1]) >= 1.0:
            kept.append(p)
    path = np.array(kept)
    if len(path) < 2:
        yaw = float(ego.initial_state.orientation)
        path = np.array([points[0], points[0] + [math.cos(yaw), math.sin(yaw)]])
    head = path[1] - path[0]
    tail = path[-1] - path[-2]
    head, tail = head / np.linalg.norm(head), tail / np.linalg.norm(tail)
    ext = np.arange(1.0, PATH_EXTENSION_M + 1.0, 1.0)[:, None]
    path = np.vstack([path[0] - ext[::-1] * head, path, path[-1] + ext * tail])
    general = _mod("commonroad_crime.utility.general")
    path = general.resample_polyline(general.chaikins_corner_cutting(path), 1.0)
    clcs = _mod("commonroad_clcs.pycrccosy").CurvilinearCoordinateSystem
    return clcs(list(path), 25.0, 0.1)


def _zero_accelerations(states: list[Any]) -> None:
    for s in states:
        s.acceleration = 0.0
        s.acceleration_y = 0.0


def _measures(scenario: Any, ego: Any) -> tuple[Any, Any, Any]:
    config = _mod("commonroad_crime.data_structure.configuration").CriMeConfiguration()
    config.update(ego_id=ego.obstacle_id, sce=scenario)
    ttc = _mod("commonroad_crime.measure.time.ttc").TTC(config)
    along = _mod("commonroad_crime.measure.acceleration.a_long_req").ALongReq(config)
    clcs = _reference_path(ego)
    config.update(CLCS=clcs)
    for measure in (ttc, along, ttc._hw_object, along._hw_object):
        _zero_accelerations(_states(measure.ego_vehicle))
    return ttc, along, clcs


def crime_pair_steps(xml: Path, keep: Callable[[str, int], bool] | None = None) -> CrimeRun:
    """CriMe's TTC and required deceleration for every other vehicle near the ego.

    Args:
        xml: The scenario.
        keep: ``(object id, time step) -> bool``: compute only the pair-steps it keeps (the
            acceptance test keeps those that a plain recompute finds near the ego's path).

    Raises:
        ImportError: commonroad-crime is not installed here.
    """
    started = time.perf_counter()
    logging.disable(logging.WARNING)  # CriMe and its path library warn per pair-step
    try:
        run = _run(xml, keep)
    finally:
        logging.disable(logging.NOTSET)
    run.seconds = time.perf_counter() - started
    return run


def _run(xml: Path, keep: Callable[[str, int], bool] | None) -> CrimeRun:
    scenario, ego = _rotated(xml)
    ttc, along, clcs = _measures(scenario, ego)
    solver = _mod("commonroad_crime.utility.solver")
    ego_states = {s.time_step: s for s in _states(ttc.ego_vehicle)}
    run = CrimeRun(str(ego.obstacle_id), int(ego.initial_state.time_step))
    for other in scenario.dynamic_obstacles:
        if other.obstacle_id == ego.obstacle_id:
            continue
        limit = (ego.obstacle_shape.width + other.obstacle_shape.width) / 2 + IN_PATH_MARGIN_M
        prepared = False
        for state in _states(other):
            ego_state = ego_states.get(state.time_step)
            if ego_state is None:
                continue
            if np.linalg.norm(state.position - ego_state.position) > RANGE_M:
                continue
            if keep is not None and not keep(str(other.obstacle_id), int(state.time_step)):
                continue
            if not prepared:
                for measure in (ttc, along):
                    measure.set_other_vehicles(other.obstacle_id)
                    _zero_accelerations(_states(measure.other_vehicle))
                prepared = True
            step = _pair_step(run, (ttc, along, clcs, solver), other, state.time_step, limit)
            if step is not None:
                run.pair_steps.append(step)
    return run


def _pair_step(
    run: CrimeRun, tools: tuple[Any, Any, Any, Any], other: Any, t: int, limit: float
) -> PairStep | None:
    ttc, along, clcs, solver = tools
    domain_error = _mod("commonroad_clcs.pycrccosy").CartesianProjectionDomainError
    try:
        ttc_s = float(ttc.compute(other.obstacle_id, t, verbose=False))
    except (TypeError, domain_error) as error:  # junctions, map ends; off the path
        name = type(error).__name__
        run.errors[name] = run.errors.get(name, 0) + 1
        return None
    gap = float(ttc._hw_object.value)
    ego_state = ttc.ego_vehicle.state_at_time(t)
    other_state = ttc.other_vehicle.state_at_time(t)
    try:
        lateral = float(
            solver.compute_clcs_distance(clcs, ego_state.position, other_state.position)[1]
        )
    except (ValueError, domain_error):
        lateral = math.inf  # outside the path's projection domain
    closing = float(ego_state.velocity - other_state.velocity)  # along +x after the rotation
    in_path = math.isfinite(gap) and abs(lateral) <= limit
    decel = 0.0
    if in_path and math.isfinite(ttc_s):
        decel = max(0.0, -float(along.compute(other.obstacle_id, t, verbose=False)))
    if not math.isfinite(ttc_s) or math.isnan(ttc_s):
        ttc_s = math.inf
    return PairStep(
        str(other.obstacle_id), int(t), gap, lateral, closing, ttc_s, decel, in_path, limit
    )


def drive_verdict(xml: Path, *, full: bool = False) -> dict[str, Any]:
    """The independent measure's verdict on one drive, JSON-ready (every number finite).

    A *real conflict* is a run of pair-steps that CriMe flags and the plain recompute
    (:func:`~tests.workbench.triage.conflicts.numpy_pair_steps`) flags too; pair-steps only
    one side flags are listed apart (``crime_only``, ``numpy_only``) with the agreement.

    Args:
        xml: The scenario.
        full: CriMe on every pair-step within ``RANGE_M``; otherwise only on those the
            recompute finds ahead within the in-path gate plus 1 m (the only ones the rule
            can flag when both lateral offsets differ by less than that).
    """
    started = time.perf_counter()
    ego_id, ours = numpy_pair_steps(xml)
    numpy_s = time.perf_counter() - started
    near = near_path(ours)
    run = crime_pair_steps(xml, None if full else (lambda o, s: (o, s) in near))
    if run.ego_id != ego_id:
        raise AssertionError(f"{xml.name}: CriMe's ego {run.ego_id}, the loader's {ego_id}")
    flagged = {(p.object_id, p.step) for p in ours if p.critical}
    confirmed = [p for p in run.pair_steps if p.critical and (p.object_id, p.step) in flagged]
    crime_flags = {(p.object_id, p.step) for p in run.pair_steps if p.critical}
    computed = {(p.object_id, p.step) for p in run.pair_steps}
    first = run.ego_first_step
    return {
        "scenario": xml.stem,
        "ego": ego_id,
        "ego_first_step": first,
        "mode": "full" if full else "near-path",
        "pair_steps": {
            "asked": len(ours) if full else len(near),
            "crime": len(run.pair_steps),
            "numpy": len(ours),
        },
        "crime_errors": dict(sorted(run.errors.items())),
        "seconds": {"crime": round(run.seconds, 2), "numpy": round(numpy_s, 2)},
        "agreement": flag_agreement(run.pair_steps, ours),
        "conflicts": [c.record(first) for c in conflicts(confirmed)],
        "crime_only": [
            c.record(first)
            for c in conflicts(p for p in run.pair_steps if (p.object_id, p.step) not in flagged)
        ],
        "numpy_only": [
            c.record(first)
            for c in conflicts(p for p in ours if (p.object_id, p.step) in computed - crime_flags)
        ],
    }
