"""Reference timing of scene creation: ad-rss map integration 5.0 on the scene bench's frames.

ad-rss-map-integration 5.0 only runs in its own interpreter (``make oracle-adrss-map``
builds ``.venv-oracle-adrss-map`` with the §8.4 work-around), so the frames go to
``bench/scene_reference_oracle.py`` in a subprocess as JSON on stdin; the timings come
back as one JSON line on stdout. Frame format (plain JSON, ENU map frame)::

    {"scene": 0,                    # frames of one scene share the ad-rss core memories
     "ego": VEHICLE, "objects": [VEHICLE, ...]}
    VEHICLE = {"id": int, "x": m, "y": m, "yaw": rad, "v": m/s (>= 0, along the heading),
               "length": m, "width": m, "response_time": s}

Every object is sent as an ``OtherVehicle``; dynamics other than the response time are the
ad-rss unit-test values (the defaults of :class:`rss.params.RssDynamics`).
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from rss.scene import SceneEgo, SceneObjects

ROOT = Path(__file__).resolve().parents[1]
ORACLE_PYTHON = ROOT / ".venv-oracle-adrss-map" / "bin" / "python"
TIMEOUT_S = 3600.0


def scene_frame(ego: SceneEgo, objects: SceneObjects, scene: int = 0) -> dict[str, Any]:
    """One bench frame in the reference's JSON frame format (module docstring).

    Args:
        ego: The ego.
        objects: The other objects (``(N,)`` arrays); speeds are ``hypot(vx, vy)``.
        scene: Scene number; a new number starts fresh ad-rss memories.

    Returns:
        The frame as plain JSON data.
    """
    speed = np.hypot(objects.vx_mps, objects.vy_mps)
    return {
        "scene": scene,
        "ego": {
            "id": ego.object_id,
            "x": ego.x_m,
            "y": ego.y_m,
            "yaw": ego.yaw_rad,
            "v": ego.speed_mps,
            "length": ego.length_m,
            "width": ego.width_m,
            "response_time": ego.dynamics.response_time_s,
        },
        "objects": [
            {
                "id": int(objects.ids[i]),
                "x": float(objects.x_m[i]),
                "y": float(objects.y_m[i]),
                "yaw": float(objects.yaw_rad[i]),
                "v": float(speed[i]),
                "length": float(objects.length_m[i]),
                "width": float(objects.width_m[i]),
                "response_time": objects.dynamics[i].response_time_s,
            }
            for i in range(len(objects.ids))
        ],
    }


def oracle_python() -> Path:
    """The oracle interpreter: ``RSS_MAP_ORACLE_PYTHON`` if set, else the side venv's."""
    return Path(os.environ.get("RSS_MAP_ORACLE_PYTHON") or ORACLE_PYTHON)


def reference_unavailable(map_path: Path) -> str | None:
    """Why the reference cannot run on ``map_path`` (one line), or None if it can."""
    python = oracle_python()
    if not python.is_file():
        return f"ad-rss-map-integration interpreter {python} missing (make oracle-adrss-map)"
    if map_path.suffix != ".xodr" or not map_path.is_file():
        return f"ad-map needs an OpenDRIVE map, not {map_path.name}"
    return None


def reference_ms_per_frame(frames: list[dict[str, Any]], map_path: Path) -> dict[str, Any] | None:
    """CPU time of ad-rss map integration 5.0 per frame, by phase.

    Args:
        frames: Frames in the JSON frame format (:func:`scene_frame`), at least one.
        map_path: OpenDRIVE map (``.xodr``) the frames are placed on.

    Returns:
        None when the reference cannot run (:func:`reference_unavailable` says why), else
        ``{"frames": n, "ms_per_frame": {phase: ms}, "constellations_per_frame": float,
        "relevant_per_frame": float, "situations_per_frame": float,
        "types_per_frame": {constellation type: float}, "failed_frames": int}`` with
        phases ``matching`` (``RssObjectData`` with ``getMapMatchedBoundingBox``, ego and
        all objects), ``append`` (``appendConstellations``, all objects),
        ``world_model`` (``getWorldModel``), ``extraction``, ``checking``, ``resolving``
        (the ad-rss core chain); ``relevant`` counts constellations other than
        ``NotRelevant``, ``situations`` those left after extraction (which merges a
        pair's constellations of one type, e.g. ad-rss' two ``OppositeDirection`` ones
        per intersection route pair).

    Raises:
        RuntimeError: The oracle process failed (message: the end of its stderr).
    """
    if reference_unavailable(map_path) is not None:
        return None
    proc = subprocess.run(  # noqa: S603 - our interpreter, our script
        [str(oracle_python()), "-m", "bench.scene_reference_oracle", str(map_path.resolve())],
        input=json.dumps({"frames": frames}),
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=TIMEOUT_S,
        check=False,
    )
    if proc.returncode != 0:
        raise RuntimeError(f"ad-rss reference timing failed: {proc.stderr[-2000:]}")
    result: dict[str, Any] = json.loads(proc.stdout.strip().splitlines()[-1])
    return result
