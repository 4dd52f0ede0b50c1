"""The structured RSS verdict of one frame: typed and frozen; record, layout and sinks read it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

    from rss import FrameResult

__all__ = ["RssVerdict"]


@dataclass(frozen=True, slots=True)
class RssVerdict:
    """Structured RSS on one frame: ``C`` constellations, or none.

    Attributes:
        is_safe: No dangerous constellation.
        culprits: Labels of the dangerous objects, sorted.
        cause: ``"RSS <longitudinal response>"`` when unsafe, else ``""``.
        margin: ``0.0`` when unsafe, else ``inf``.
        invalid_objects: Ids of objects that could not be checked (not placeable, bad
            values), sorted.
        labels: ``(C,)`` actor id (or ``road_boundary_left/right``) of the other object of
            each constellation.
        constellation_type: ``(C,)`` :class:`rss.model.ConstellationType` codes.
        object_id: ``(C,)`` engine ids of the other objects (the record's order).
        result: The engine's result for this frame (``F = 1``); ``None`` without
            constellations.
        road_areas: Outline rings of each constellation's road area in the map frame [m]
            (``(C,)`` entries of closed ``(K, 2)`` rings; empty tuple: not computed).
        rejected: ``(object id, reason)`` of each malformed constellation left out of the
            frame (also in ``invalid_objects``).
        responsible: ``(C,)`` :class:`rss.structured.responsibility.Responsible` codes: who
            must act in each constellation (``None`` without constellations).
        profile: The parameter profile (``RssParams.profile_label``) the frame was checked
            with.
    """

    is_safe: bool
    culprits: tuple[str, ...] = ()
    cause: str = ""
    margin: float = float("inf")
    invalid_objects: tuple[str, ...] = ()
    labels: tuple[str, ...] = ()
    constellation_type: NDArray[np.int64] | None = None
    object_id: NDArray[np.int64] | None = None
    result: FrameResult | None = None
    road_areas: tuple[tuple[NDArray[np.float64], ...], ...] = ()
    rejected: tuple[tuple[str, str], ...] = ()
    responsible: NDArray[np.int64] | None = None
    profile: str = "adrss-5.0"

    def responsibility(self) -> dict[str, str]:
        """Who must act per object: ``ego``, ``object`` or ``both``, sorted by label.

        Every object one of whose constellations is dangerous from either side is listed.
        """
        if self.responsible is None:
            return {}
        codes: dict[str, int] = {}
        for label, code in zip(self.labels, self.responsible.tolist(), strict=True):
            if code:
                codes[label] = codes.get(label, 0) | int(code)
        names = {1: "ego", 2: "object", 3: "both"}
        return {label: names[code] for label, code in sorted(codes.items())}

    @property
    def constellations(self) -> int:
        """Number of constellations checked."""
        return len(self.labels)
