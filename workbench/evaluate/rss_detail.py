"""What the structured RSS runner hands to the viewer for one frame (beside its JSON record)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

    from rss.engine import FrameResult

__all__ = ["RssFrameDetail"]


@dataclass(frozen=True, slots=True)
class RssFrameDetail:
    """The checked constellations of one frame, for drawing.

    Attributes:
        labels: Actor id (or ``road_boundary_left/right``) of the other object of each of the
            ``C`` constellations.
        constellation_type: ``(C,)`` :class:`rss.model.ConstellationType` codes.
        result: The engine's result for this one frame (``C`` constellations, ``F = 1``).
        road_areas: Outline of the road area of each constellation, ``(C,)`` entries of
            closed ``(K, 2)`` rings in the map frame [m] (empty tuple: not available).
    """

    labels: tuple[str, ...]
    constellation_type: NDArray[np.int64]
    result: FrameResult
    road_areas: tuple[NDArray[np.float64], ...] = ()
