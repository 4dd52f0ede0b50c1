"""The unstructured RSS verdict of one frame: typed, frozen; record, layout and sinks read it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.unstructured import UnstructuredResponse

if TYPE_CHECKING:
    from rss.unstructured import UnstructuredAgents, UnstructuredResult

__all__ = ["UnstructuredDetail", "UnstructuredVerdict"]


@dataclass(frozen=True)
class UnstructuredDetail:
    """The checked sets of one frame, for drawing.

    Attributes:
        ego: The ego as checked (one row, heading of travel).
        result: The engine's result (sets, decisions, proper response).
        actor_ids: ``(K,)`` actor id of each agent of ``result``.
    """

    ego: UnstructuredAgents
    result: UnstructuredResult
    actor_ids: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class UnstructuredVerdict:
    """Unstructured RSS on one frame: ``K`` checked pairs, or none.

    Attributes:
        is_safe: No dangerous object.
        culprits: Ids of the dangerous objects, sorted.
        cause: ``"unstructured: <response>"`` when unsafe, else ``""``.
        margin: ``0.0`` when unsafe, else ``inf``.
        response: The resolved proper response (ad-rss ``ProperResponse``).
        decisions: ``(actor id, decision)`` per checked agent, sorted by id.
        heading_ranges_rad: Allowed headings while driving away, ``(begin, end)`` pairs.
        lon_mps2: Allowed longitudinal acceleration ``(min, max)`` [m/s²].
        lat_mps2: Allowed lateral acceleration ``(min, max)`` [m/s²], both sides.
        constellations: Number of unstructured pairs checked.
        invalid_objects: Selected actors that could not be checked, sorted.
        detail: The sets for drawing; ``None`` without pairs.
    """

    is_safe: bool
    lon_mps2: tuple[float, float]
    lat_mps2: tuple[float, float]
    culprits: tuple[str, ...] = ()
    cause: str = ""
    margin: float = float("inf")
    response: UnstructuredResponse = UnstructuredResponse.None_
    decisions: tuple[tuple[str, UnstructuredResponse], ...] = ()
    heading_ranges_rad: tuple[tuple[float, float], ...] = ()
    constellations: int = 0
    invalid_objects: tuple[str, ...] = ()
    detail: UnstructuredDetail | None = None
