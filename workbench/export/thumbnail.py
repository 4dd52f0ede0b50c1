"""What a clip's thumbnail shows: the incident's worst frame, framed on its objects (pure).

The thumbnail is the scene view alone (:func:`workbench.replay.blueprint.thumbnail_blueprint`)
at the incident's worst frame (:func:`workbench.replay.highlight.worst_frame`), its objects
highlighted and the other actors dimmed as in the review. The camera
(:func:`workbench.replay.blueprint.incident_eye`) frames the ego and every ground corner of
the incident's objects' boxes at that frame, as the clip's replay saw them
(:class:`workbench.replay.highlight.CulpritBoxes`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from workbench.replay.blueprint import incident_eye
from workbench.replay.highlight import worst_frame

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from workbench.export.plan import ClipPlan
    from workbench.incidents import Incident, IncidentReport
    from workbench.replay.highlight import CulpritBoxes

__all__ = ["ThumbnailView", "box_corners_m", "thumbnail_view"]

Vec3 = tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class ThumbnailView:
    """A clip thumbnail's frame and camera.

    Attributes:
        frame: The drive frame number shown (the incident's worst frame).
        eye: Camera ``(position, look_target)`` [m], map frame; ``None``: the recording's
            own blueprint at ``frame`` (a window without incident).
        incident: The incident whose objects are highlighted.
        ego_m: Ego position ``(x, y)`` [m] at ``frame``.
        boxes_m: ``(N, 7)`` boxes of the incident's objects at ``frame`` (centre x, y, z,
            half length, half width, half height [m], yaw [rad]).
    """

    frame: int
    eye: tuple[Vec3, Vec3] | None = None
    incident: Incident | None = None
    ego_m: tuple[float, float] | None = None
    boxes_m: NDArray[np.float64] | None = None


def box_corners_m(boxes_m: NDArray[np.float64]) -> NDArray[np.float64]:
    """``(8 N, 3)`` corners [m] of ``(N, 7)`` boxes (:attr:`ThumbnailView.boxes_m`)."""
    signs = np.array([(a, b, z) for a in (-1, 1) for b in (-1, 1) for z in (-1, 1)], dtype=float)
    dl = signs[None, :, 0] * boxes_m[:, None, 3]
    dw = signs[None, :, 1] * boxes_m[:, None, 4]
    c, s = np.cos(boxes_m[:, None, 6]), np.sin(boxes_m[:, None, 6])
    x = boxes_m[:, None, 0] + dl * c - dw * s
    y = boxes_m[:, None, 1] + dl * s + dw * c
    z = boxes_m[:, None, 2] + signs[None, :, 2] * boxes_m[:, None, 5]
    return np.stack([x, y, z], axis=-1).reshape(-1, 3)


def thumbnail_view(
    report: IncidentReport, plan: ClipPlan, culprits: CulpritBoxes | None
) -> ThumbnailView:
    """The thumbnail of ``plan``'s clip, from the boxes its replay collected.

    Falls back to the incident's first frame (positions of ``report``) where the replay saw
    no culprit at the worst frame.
    """
    incident = plan.incident
    if incident is None:
        first = plan.frames[0] if plan.frames else 0
        return ThumbnailView(frame=first)
    frame = worst_frame(incident)
    ego = None if culprits is None else culprits.ego_m.get(frame)
    boxes = None if culprits is None else culprits.boxes_at(frame, incident.objects)
    if ego is None or boxes is None or len(boxes) == 0:
        frame = incident.start_frame
        ego = report.ego_at_start_m.get(frame)
        at_start = report.objects_at_start_m.get(frame, {})
        focus = [at_start[o] for o in incident.objects if o in at_start]
        if ego is None:
            return ThumbnailView(frame=frame, incident=incident)
        return ThumbnailView(frame, incident_eye(ego, focus), incident, ego, None)
    corners = [(float(x), float(y)) for x, y, _ in box_corners_m(boxes)]
    return ThumbnailView(frame, incident_eye(ego, corners), incident, ego, boxes)
