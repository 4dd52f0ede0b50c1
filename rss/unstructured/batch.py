"""What the batched set builders share: per-agent dynamics and pieces as corner indices.

The fast builders (:mod:`rss.unstructured.vehicle_batch`, :mod:`rss.unstructured.pedestrian_batch`)
compute every trajectory point of a batch in a few stacked kernel calls, then the
footprint corners of all points at once: a ``(R * 4, N, 2)`` table (row ``r`` = one
trajectory point of every agent, its corners FR, FL, BL, BR at ``4 r .. 4 r + 3``). Which
corners form which convex piece depends only on the step counts of the settings, so the
pieces are a cached :class:`PiecePlan` of corner indices; one gather turns the table
into :class:`TrajectorySets` (whose shapely hulls are built only when asked for).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from rss.unstructured.kinematics import Points, footprints
from rss.unstructured.sets import TrajectorySets

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.dynamics import RssDynamics, UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents

__all__ = [
    "CORNERS",
    "AgentDynamics",
    "PiecePlan",
    "RowPieces",
    "constant",
    "plan_sets",
    "sets_of_points",
    "span",
]

#: Corners per footprint (FR, FL, BL, BR).
CORNERS = 4
#: Agent counts up to which :meth:`PiecePlan.per_piece` keeps its arrays.
PER_PIECE_CACHE = 64


@dataclass(frozen=True)
class AgentDynamics:
    """The dynamics values of ``N`` agents sharing one :class:`UnstructuredSettings`.

    Attributes:
        settings: The shared unstructured settings (step counts, radii).
        response_time_s: ``(N,)`` response time rho [s].
        max_speed_mps: ``(N,)`` speed cap of accelerations [m/s].
        accel_max_mps2: ``(N,)`` maximal acceleration [m/s²].
        brake_max_mps2: ``(N,)`` maximal braking (< 0) [m/s²].
        brake_min_mps2: ``(N,)`` minimal braking (< 0) [m/s²].
        front_extra_m: ``(N,)`` footprint extension in front (the ego's
            ``min_longitudinal_safety_distance``, else 0) [m].
    """

    settings: UnstructuredSettings
    response_time_s: FloatArray
    max_speed_mps: FloatArray
    accel_max_mps2: FloatArray
    brake_max_mps2: FloatArray
    brake_min_mps2: FloatArray
    front_extra_m: FloatArray

    @staticmethod
    def of(dynamics: Sequence[RssDynamics], front_extra_m: FloatArray) -> AgentDynamics:
        """Stack one dynamics per agent (all with the same ``unstructured`` settings)."""
        values = np.array(
            [
                (
                    d.response_time_s,
                    d.max_speed_on_acceleration_mps,
                    d.accel_max_mps2,
                    d.brake_max_mps2,
                    d.brake_min_mps2,
                )
                for d in dynamics
            ],
            dtype=np.float64,
        ).reshape(-1, 5)
        rho, vcap, accel, brake_max, brake_min = values.T
        return AgentDynamics(
            dynamics[0].unstructured, rho, vcap, accel, brake_max, brake_min, front_extra_m
        )

    def take(self, index: IntArray) -> AgentDynamics:
        """The agents at ``index``."""
        return AgentDynamics(
            self.settings,
            *(
                getattr(self, f)[index]
                for f in (
                    "response_time_s",
                    "max_speed_mps",
                    "accel_max_mps2",
                    "brake_max_mps2",
                    "brake_min_mps2",
                    "front_extra_m",
                )
            ),
        )


class RowPieces:
    """Collects pieces as lists of footprint rows (whole footprints) or single corners.

    Has the ``add`` interface of :class:`rss.unstructured.sets.PieceCollector`, so
    :func:`rss.unstructured.sets.front_and_sides` plans pieces for both.
    """

    def __init__(self) -> None:
        """Start empty."""
        self.corners: list[list[int]] = []
        self.brake: list[bool] = []

    def add(self, *rows: int | Sequence[int], brake: bool) -> None:
        """Add the hull of the footprints at the given rows (ints or sequences of ints)."""
        flat = [r for group in rows for r in ([group] if isinstance(group, int) else group)]
        self.add_corners([CORNERS * r + c for r in flat for c in range(CORNERS)], brake=brake)

    def add_corners(self, corners: Sequence[int], *, brake: bool) -> None:
        """Add the hull of single corners (index ``4 row + corner``)."""
        self.corners.append(list(corners))
        self.brake.append(brake)

    def plan(self) -> PiecePlan:
        """The collected pieces, padded to one width (a repeated corner leaves a hull as is)."""
        width = max(len(c) for c in self.corners)
        index = np.array([c + [c[-1]] * (width - len(c)) for c in self.corners], dtype=np.int64)
        size = np.array([len(c) for c in self.corners], dtype=np.int64)
        brake = np.array(self.brake, dtype=bool)
        for a in (index, size, brake):
            a.setflags(write=False)
        return PiecePlan(index, size, brake)


@dataclass(frozen=True)
class PiecePlan:
    """Corner indices of every piece of one agent.

    Attributes:
        index: ``(P, K)`` corner indices into the ``(R * 4)`` corner rows, padded by
            repeating a piece's last corner.
        size: ``(P,)`` corners of each piece before padding.
        brake: ``(P,)`` piece belongs to the brake set.
    """

    index: IntArray
    size: IntArray
    brake: BoolArray
    _per_piece: dict[int, tuple[IntArray, IntArray, BoolArray]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )
    gather: IntArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        """``gather``: ``index.T`` in C order (``take`` along it is ~8x quicker than ``[]``)."""
        gather = np.ascontiguousarray(self.index.T)
        gather.setflags(write=False)
        object.__setattr__(self, "gather", gather)

    def per_piece(self, count: int) -> tuple[IntArray, IntArray, BoolArray]:
        """``(size, owner, brake)`` of the ``P * count`` pieces of ``count`` agents, read-only.

        Piece-major (owner = agent index); kept per ``count`` up to :data:`PER_PIECE_CACHE`.
        """
        out = self._per_piece.get(count)
        if out is None:
            out = (
                np.repeat(self.size, count),
                np.arange(self.size.size * count) % count,  # np.tile's values, quicker
                np.repeat(self.brake, count),
            )
            for a in out:
                a.setflags(write=False)
            if count <= PER_PIECE_CACHE:
                self._per_piece[count] = out
        return out


def plan_sets(corners: FloatArray, plan: PiecePlan) -> TrajectorySets:
    """The pieces of ``N`` agents from their corner table (hulls are built on demand).

    Args:
        corners: ``(R * 4, N, 2)`` footprint corners (or other points) per row.
        plan: The pieces.

    Returns:
        ``P * N`` pieces, piece-major (owner = agent index).
    """
    pieces, width = plan.index.shape
    n = corners.shape[1]
    coords = corners.take(plan.gather, axis=0).reshape(width, pieces * n, 2)
    return TrajectorySets(coords, *plan.per_piece(n), n)


def constant(values: object, dtype: type = np.int64) -> np.ndarray:
    """A read-only array (the cached row layouts of the builders)."""
    out: np.ndarray = np.array(values, dtype=dtype)
    out.setflags(write=False)
    return out


def span(start: int, stop: int) -> list[int]:
    """Rows ``start .. stop - 1``."""
    return list(range(start, stop))


def sets_of_points(
    x_m: FloatArray,
    y_m: FloatArray,
    yaw_rad: FloatArray,
    agents: UnstructuredAgents,
    dyn: AgentDynamics,
    *,
    plan: PiecePlan,
) -> TrajectorySets:
    """The pieces of ``plan`` from the poses ``(R, N)`` of its footprint table's rows."""
    points = Points(x_m, y_m, yaw_rad, x_m, yaw_rad)  # speeds and yaw rates are not used
    corners = footprints(points, agents.length_m, agents.width_m, dyn.front_extra_m)
    table = corners.transpose(0, 2, 1, 3).reshape(-1, len(agents), 2)  # (R * 4, N, 2)
    return plan_sets(table, plan)
