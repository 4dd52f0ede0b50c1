"""Thumbnails show the incident: the camera of a clip's recording frames the ego and the
incident's objects at the incident's first frame (the thumbnail's frame).

Projected with a pinhole camera narrower than the viewer's (vertical field of view 45 deg,
aspect 1.5 of the scene view; Rerun's default eye is wider), every corner of the ego's and
the objects' boxes lies inside the image.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from workbench.export import Selection, plan_clips
from workbench.export.views import incident_focus_m
from workbench.incidents import IncidentRequest, find_incidents
from workbench.replay.blueprint import incident_eye

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
FOV_Y_RAD = math.radians(45.0)
ASPECT = 1.5
#: Half length, half width and height of a car's box [m] (larger than the samples' cars).
HALF_LENGTH_M, HALF_WIDTH_M, HEIGHT_M = 3.0, 1.2, 2.0


def _corners(x: float, y: float) -> np.ndarray:
    """(8, 3) corners of an axis-aligned box around ``(x, y)`` (any heading fits in it)."""
    r = math.hypot(HALF_LENGTH_M, HALF_WIDTH_M)
    return np.array(
        [(x + dx, y + dy, z) for dx in (-r, r) for dy in (-r, r) for z in (0, HEIGHT_M)]
    )


def _ndc(points: np.ndarray, eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(N, 3): normalised image x, y (inside the image within [-1, 1]) and depth [m]."""
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    rel = points - eye
    depth = rel @ forward
    half_h = np.tan(FOV_Y_RAD / 2) * depth
    return np.column_stack([(rel @ right) / (half_h * ASPECT), (rel @ up) / half_h, depth])


@pytest.mark.parametrize(
    "log", ["highway_cut_in.mcap", "urban_intersection.mcap", "pedestrian_crossing.mcap"]
)
def test_the_incident_objects_lie_inside_the_thumbnail(log: str) -> None:
    report = find_incidents(IncidentRequest(SAMPLES / log, engines=("rss",)))
    plans = plan_clips(report, {}, Selection(all=True), 3_000_000_000)
    assert plans
    for plan in plans:
        focus = incident_focus_m(report, plan)
        assert focus is not None
        ego, objects = focus
        assert plan.incident is not None
        assert len(objects) == len(plan.incident.objects)
        eye, target = (np.array(p) for p in incident_eye(ego, objects))
        for x, y in (ego, *objects):
            ndc = _ndc(_corners(x, y), eye, target)
            assert (ndc[:, 2] > 0).all()
            assert (np.abs(ndc[:, :2]) <= 1.0).all(), (plan.stem, (x, y), ndc[:, :2])
