"""CommonRoad scenarios (XML 2018b and 2020a) as drives: one recorded vehicle becomes the ego.

Both format variants are read with ``xml.etree`` in one ``iterparse`` pass: 2018b lists
``<obstacle>`` elements with ``<role>dynamic</role>``, 2020a lists ``<dynamicObstacle>``
(and ``<staticObstacle>``). Every recorded state sits on the scenario's time grid, so frame
``k`` is at ``t_ns = time_step * timeStepSize`` (integer nanoseconds) and holds the
obstacles that have a state at exactly that step (``match_dt_ns = 0``); static obstacles
appear in every frame.

Ego promotion: ``ego_id`` names a dynamic vehicle obstacle (car, truck, bus, motorcycle,
taxi, priority vehicle); by default the longest-lived one is taken (ties: lowest id).
Frames are built on the ego's own time steps. Its yaw rate is the finite difference of
the unwrapped orientation, its acceleration the recorded one or else the finite
difference of its speed.

Plan: a recorded obstacle has no planner output, so each frame's ``Plan`` is the ego's
own recorded future over the next ``PLAN_HORIZON_NS`` (4 s), starting with the current
state at ``t_offset_s = 0``; engines that check a plan then check what the driver
actually did.

A non-finite ego pose or speed stops the frame stream with ``InvalidValueError`` naming
the file, time and value after every earlier frame was yielded; non-finite actor values
only clear that actor row's ``valid`` flag.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NoReturn

import numpy as np

from loaders.commonroad_scenario import Scenario, Track, load_scenario
from loaders.drive import DriveInfo, TopicInfo, TopicRoles
from loaders.errors import EmptyLogError, InvalidValueError, MissingEgoTopicError
from loaders.maps.commonroad import lane_map_from_elements
from loaders.records import ActorTable, EgoState, Frame, ObjectClass, Plan
from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence
    from pathlib import Path

    from numpy.typing import NDArray

    from loaders.maps.model import LaneMap

__all__ = ["PLAN_HORIZON_NS", "CommonRoadDrive", "commonroad_ego_candidates", "open_commonroad"]

#: How far ahead of each frame the ego's recorded future is given as its plan.
PLAN_HORIZON_NS = 4_000_000_000
_CLASSES = {
    "car": ObjectClass.CAR,
    "taxi": ObjectClass.CAR,
    "priorityVehicle": ObjectClass.CAR,
    "truck": ObjectClass.TRUCK,
    "bus": ObjectClass.BUS,
    "motorcycle": ObjectClass.MOTORCYCLE,
    "bicycle": ObjectClass.BICYCLE,
    "pedestrian": ObjectClass.PEDESTRIAN,
}
_COLUMNS = ("x_m", "y_m", "yaw_rad", "vx_mps", "vy_mps", "length_m", "width_m")


def commonroad_ego_candidates(path: Path) -> list[str]:
    """Ids of the obstacles that can be promoted to ego, longest-lived first.

    Args:
        path: CommonRoad scenario XML.

    Returns:
        Dynamic vehicle obstacle ids sorted by number of recorded states (descending),
        ties by id.
    """
    return [t.id for t in load_scenario(path).candidates()]


def open_commonroad(
    path: Path, *, ego_id: str | None = None, lane_map: LaneMap | None = None
) -> CommonRoadDrive:
    """Open a CommonRoad scenario as a drive.

    Args:
        path: CommonRoad scenario XML (2018b or 2020a).
        ego_id: Obstacle promoted to ego; default the longest-lived vehicle.
        lane_map: Map to use instead of the scenario's own lanelet network.

    Returns:
        The drive; frames are generated lazily on the ego's time steps.

    Raises:
        MissingEgoTopicError: If ``ego_id`` is not a dynamic vehicle obstacle (the message
            lists the candidates).
        EmptyLogError: If the scenario has no dynamic vehicle obstacle.
        CorruptLogError: If the XML is malformed.
        UnsupportedFormatError: If the root element is not ``commonRoad``.
        InvalidValueError: If ``timeStepSize`` is missing or not positive.
    """
    scenario = load_scenario(path)
    candidates = scenario.candidates()
    if not candidates:
        raise EmptyLogError(path, "no dynamic vehicle obstacle to promote to ego")
    by_id = {t.id: t for t in candidates}
    ego = candidates[0] if ego_id is None else by_id.get(str(ego_id))
    if ego is None:
        names = ", ".join(by_id)
        detail = f"{ego_id} is not a dynamic vehicle obstacle; candidates: {names}"
        raise MissingEgoTopicError(path, detail, topic=f"obstacle/{ego_id}", value=ego_id)
    return CommonRoadDrive(path, scenario, ego, lane_map, len(candidates))


class CommonRoadDrive:
    """A CommonRoad scenario seen from one promoted obstacle (implements ``Drive``)."""

    def __init__(
        self,
        path: Path,
        scenario: Scenario,
        ego: Track,
        lane_map: LaneMap | None,
        candidate_count: int,
    ) -> None:
        """Index the actors and derive the ego's rates; use ``open_commonroad`` instead."""
        self._path = path
        self._scenario = scenario
        self._ego = ego
        self._map = lane_map
        others = [t for t in scenario.tracks if t.dynamic and t.id != ego.id]
        self._actors = _ActorIndex(others, [t for t in scenario.tracks if not t.dynamic])
        self._valid_count, self._yaw_rate, self._accel = _ego_rates(ego, scenario.dt_ns)
        dims = {"length_m": ego.length_m, "width_m": ego.width_m}
        self._dims = {
            name: value for name, value in dims.items() if math.isfinite(value) and value > 0
        }
        dt, topic = scenario.dt_ns, f"obstacle/{ego.id}"
        self._info = DriveInfo(
            path=path,
            source_format=f"commonroad-{scenario.version}",
            start_ns=int(ego.steps[0]) * dt,
            end_ns=int(ego.steps[-1]) * dt,
            topics=(
                TopicInfo(topic, "commonroad/obstacle", len(ego.steps), "ego"),
                TopicInfo("obstacles", "commonroad/obstacle", len(others), "objects"),
            ),
            roles=TopicRoles(ego=topic, objects=("obstacles",), plan=topic),
            match_tolerance_ns=0,
            frame_count=len(ego.steps),
            map_source=lane_map.source if lane_map is not None else str(path),
            notes={
                "ego_id": ego.id,
                "ego_candidates": str(candidate_count),
                "benchmark_id": scenario.benchmark_id,
                "time_step_ns": str(dt),
                "plan": f"ego's recorded future, {PLAN_HORIZON_NS // 10**9} s",
                **_uncertainty_note(scenario.tracks),
            },
        )

    @property
    def info(self) -> DriveInfo:
        """What was detected about the drive."""
        return self._info

    @property
    def lane_map(self) -> LaneMap:
        """The scenario's lanelet network (built on first access) or the override."""
        if self._map is None:
            self._map = lane_map_from_elements(self._scenario.network, str(self._path))
        return self._map

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield one frame per ego time step within ``[start_ns, end_ns)``.

        Raises:
            InvalidValueError: At the first ego state with a non-finite pose or speed,
                after every earlier frame was yielded.
        """
        ego, dt = self._ego, self._scenario.dt_ns
        horizon = PLAN_HORIZON_NS // dt
        for i, step in enumerate(ego.steps.tolist()):
            t_ns = step * dt
            if (start_ns is not None and t_ns < start_ns) or (
                end_ns is not None and t_ns >= end_ns
            ):
                continue
            if i >= self._valid_count:
                self._raise_invalid(i, t_ns)
            stop = int(np.searchsorted(ego.steps[: self._valid_count], step + horizon, "right"))
            window = slice(i, stop)
            plan = Plan(
                x_m=ego.x_m[window],
                y_m=ego.y_m[window],
                yaw_rad=ego.yaw_rad[window],
                t_offset_s=(ego.steps[window] - step) * ns_to_s(dt),
                speed_mps=ego.speed_mps[window],
            )
            state = EgoState(
                x_m=float(ego.x_m[i]),
                y_m=float(ego.y_m[i]),
                z_m=0.0,
                yaw_rad=float(ego.yaw_rad[i]),
                speed_mps=float(ego.speed_mps[i]),
                accel_mps2=float(self._accel[i]),
                yaw_rate_radps=float(self._yaw_rate[i]),
                **self._dims,
            )
            yield Frame(i, t_ns, state, self._actors.at(step), plan, {"time_step": step})

    def _raise_invalid(self, i: int, t_ns: int) -> NoReturn:
        ego = self._ego
        names = ("x_m", "y_m", "yaw_rad", "speed_mps")
        name = next(n for n in names if not math.isfinite(float(getattr(ego, n)[i])))
        detail = f"ego obstacle {ego.id} at time step {int(ego.steps[i])}: {name}"
        value = float(getattr(ego, name)[i])
        raise InvalidValueError(
            self._path, detail, topic=f"obstacle/{ego.id}", t_ns=t_ns, value=value
        )

    def close(self) -> None:
        """Nothing to release: the file was read in one pass when the drive was opened."""


class _ActorIndex:
    """Every non-ego state in one table sorted by time step, sliced per frame."""

    def __init__(self, tracks: list[Track], static: list[Track]) -> None:
        def stack(items: list[Track]) -> dict[str, NDArray[np.generic]]:
            sizes = [len(t.steps) for t in items]
            cols: dict[str, NDArray[np.generic]] = {
                "steps": np.concatenate([t.steps for t in items] or [np.zeros(0, np.int64)]),
                "ids": np.repeat(np.array([t.id for t in items], dtype=np.str_), sizes),
                "object_class": np.repeat(
                    np.array([_CLASSES.get(t.kind, ObjectClass.UNKNOWN) for t in items], np.int8),
                    sizes,
                ),
            }
            for name in _COLUMNS:
                parts = [
                    np.broadcast_to(getattr(t, name), (n,))
                    for t, n in zip(items, sizes, strict=True)
                ]
                cols[name] = np.concatenate(parts or [np.zeros(0)]).astype(np.float64)
            return cols

        cols = stack(tracks)
        order = np.argsort(cols["steps"], kind="stable")
        self._cols = {name: col[order] for name, col in cols.items()}
        self._static = stack(static)

    def at(self, step: int) -> ActorTable:
        """Actors with a state at exactly ``step``, then every static obstacle."""
        steps = self._cols["steps"]
        lo, hi = np.searchsorted(steps, [step, step + 1])
        cols = {
            name: np.concatenate((self._cols[name][lo:hi], self._static[name]))
            for name in ("ids", "object_class", *_COLUMNS)
        }
        return ActorTable.from_columns(**cols)


def _uncertainty_note(tracks: Sequence[Track]) -> dict[str, str]:
    """``{"uncertain_states": ...}`` when some states were intervals or shapes, else empty."""
    uncertain = [t for t in tracks if t.uncertain_states]
    if not uncertain:
        return {}
    states = sum(t.uncertain_states for t in uncertain)
    names = sorted({name for t in uncertain for name in t.uncertain})
    return {
        "uncertain_states": f"{states} states of {len(uncertain)} obstacles "
        f"({', '.join(names)}): interval centres used"
    }


def _ego_rates(ego: Track, dt_ns: int) -> tuple[int, NDArray[np.float64], NDArray[np.float64]]:
    """Valid prefix length, yaw rate and acceleration of the ego over that prefix."""
    finite = np.all(np.isfinite(np.vstack((ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps))), axis=0)
    k = int(np.argmin(finite)) if not np.all(finite) else len(ego.steps)
    steps, dt_s = ego.steps[:k].astype(np.float64), ns_to_s(dt_ns)
    if k < 2:  # noqa: PLR2004 - a finite difference needs two states
        zeros = np.zeros(k)
        return k, zeros, np.where(np.isfinite(ego.accel_mps2[:k]), ego.accel_mps2[:k], 0.0)
    yaw_rate = np.gradient(np.unwrap(ego.yaw_rad[:k]), steps) / dt_s
    given = ego.accel_mps2[:k]
    accel = np.where(np.isfinite(given), given, np.gradient(ego.speed_mps[:k], steps) / dt_s)
    return k, yaw_rate, accel
