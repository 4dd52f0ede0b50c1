"""Thumbnails show the incident: the scene view alone at the incident's worst frame, the camera
framing the ego and the incident's objects, the objects highlighted.

The geometry sent to the viewer is checked with a pinhole camera narrower than the viewer's
(vertical field of view 45 deg, aspect 16:9 of the thumbnail; Rerun's default eye is wider
and the scene view fills the thumbnail's width): every corner of the incident's objects'
boxes at the worst frame, and of a box around the ego, projects inside the image. Where a
headless viewer runs, the thumbnail shows the highlight's red where the objects project.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import rerun.blueprint as rrb
from PIL import Image

from tests.conftest import running_in_ci
from workbench.export import Selection, plan_clips
from workbench.export.thumbnail import ThumbnailView, box_corners_m
from workbench.export.views import THUMBNAIL_SIZE, write_recordings, write_thumbnails
from workbench.incidents import IncidentRequest, find_incidents
from workbench.replay.blueprint import thumbnail_blueprint
from workbench.replay.highlight import worst_frame

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
FOV_Y_RAD = math.radians(45.0)
ASPECT = THUMBNAIL_SIZE[0] / THUMBNAIL_SIZE[1]
#: Half length, half width and height of a box around the ego [m] (larger than any car).
EGO_HALF_LENGTH_M, EGO_HALF_WIDTH_M, EGO_HEIGHT_M = 3.0, 1.2, 2.0


def _ego_corners(x: float, y: float) -> np.ndarray:
    """(8, 3) corners of an axis-aligned box around ``(x, y)`` (any heading fits in it)."""
    r = math.hypot(EGO_HALF_LENGTH_M, EGO_HALF_WIDTH_M)
    return np.array(
        [(x + dx, y + dy, z) for dx in (-r, r) for dy in (-r, r) for z in (0, EGO_HEIGHT_M)]
    )


def _ndc(points: np.ndarray, view: ThumbnailView, fov_y_rad: float = FOV_Y_RAD) -> np.ndarray:
    """(N, 3): normalised image x, y (inside the image within [-1, 1], y up) and depth [m]."""
    assert view.eye is not None
    eye, target = (np.array(p, dtype=float) for p in view.eye)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    rel = points - eye
    depth = rel @ forward
    half_h = np.tan(fov_y_rad / 2) * depth
    return np.column_stack([(rel @ right) / (half_h * ASPECT), (rel @ up) / half_h, depth])


def _views(log: str, out: Path) -> list[tuple[Path, ThumbnailView]]:
    request = IncidentRequest(SAMPLES / log, engines=("rss",))
    report = find_incidents(request)
    plans = plan_clips(report, {}, Selection(all=True), 3_000_000_000)
    assert plans
    written = write_recordings(report, plans, out, request)
    assert set(written) == {p.stem for p in plans}
    return list(written.values())


@pytest.mark.parametrize(
    "log", ["highway_cut_in.mcap", "urban_intersection.mcap", "pedestrian_crossing.mcap"]
)
def test_the_incident_objects_lie_inside_the_thumbnail(log: str, tmp_path: Path) -> None:
    for _, view in _views(log, tmp_path):
        incident = view.incident
        assert incident is not None
        assert view.frame == worst_frame(incident)
        assert view.boxes_m is not None
        assert view.ego_m is not None
        assert len(view.boxes_m) == len(incident.objects)
        corners = np.vstack([box_corners_m(view.boxes_m), _ego_corners(*view.ego_m)])
        ndc = _ndc(corners, view)
        assert (ndc[:, 2] > 0).all()
        assert (np.abs(ndc[:, :2]) <= 1.0).all(), (incident.id, ndc[:, :2])


def test_box_corners_follow_the_heading() -> None:
    box = np.array([[10.0, 5.0, 1.0, 2.0, 1.0, 0.5, math.pi / 2]])
    corners = box_corners_m(box)
    assert corners.shape == (8, 3)
    # Turned by 90 deg: the length runs along y, the width along x.
    assert np.allclose(corners[:, 0].min(), 9.0)
    assert np.allclose(corners[:, 0].max(), 11.0)
    assert np.allclose(corners[:, 1].min(), 3.0)
    assert np.allclose(corners[:, 1].max(), 7.0)
    assert np.allclose(sorted(set(np.round(corners[:, 2], 6))), [0.5, 1.5])


def test_the_thumbnail_blueprint_is_the_scene_alone() -> None:
    blueprint = thumbnail_blueprint(None, ((0.0, -25.0, 60.0), (0.0, 0.0, 0.0)))
    root = blueprint.root_container
    assert root is not None
    assert [type(v) for v in root.contents] == [rrb.Spatial3DView]


def _reddish(pixels: np.ndarray) -> np.ndarray:
    """Pixels of the highlight's hue (shaded or blended: red clearly above green and blue)."""
    r, g, b = (pixels[..., k].astype(int) for k in range(3))
    return (r > 120) & (r > 2 * g) & (r > 1.4 * b)


def test_the_thumbnail_shows_the_highlighted_objects(tmp_path: Path) -> None:
    if not any(Path("/usr/share/vulkan/icd.d").glob("*.json")):
        reason = "no Vulkan driver (apt-get install mesa-vulkan-drivers)"
        if running_in_ci():
            pytest.fail(reason)
        pytest.skip(reason)
    recordings = dict(enumerate(_views("highway_cut_in.mcap", tmp_path)))
    pngs, skipped = write_thumbnails({str(k): v for k, v in recordings.items()})
    assert skipped is None
    width, height = THUMBNAIL_SIZE
    for key, (_, view) in recordings.items():
        with Image.open(pngs[str(key)]) as image:
            pixels = np.asarray(image.convert("RGB"))
        assert pixels.shape[:2] == (height, width)
        assert view.boxes_m is not None
        corners = box_corners_m(view.boxes_m)
        # The objects' pixels under any field of view from 45 to 70 deg and a scene view whose
        # top is anywhere under the viewer's top bar and view title (<= 80 px).
        xs: list[float] = []
        ys: list[float] = []
        for fov in (FOV_Y_RAD, math.radians(70.0)):
            ndc = _ndc(corners, view, fov)
            for top in (0, 80):
                xs.extend((ndc[:, 0] + 1) / 2 * width)
                ys.extend(top + (1 - ndc[:, 1]) / 2 * (height - top))
        x0, x1 = max(0, int(min(xs))), min(width, math.ceil(max(xs)) + 1)
        y0, y1 = max(0, int(min(ys))), min(height, math.ceil(max(ys)) + 1)
        region = pixels[y0:y1, x0:x1]
        assert region.size
        assert _reddish(region).sum() >= 50, (view.frame, (x0, x1, y0, y1))
